#pragma once
// Writes a Results to an HDF5 file (docs/results-format.md): format 3 with /system when Results::system is not
// empty, else format 2 exactly as before (schema.hpp pair_format_version; whatever the Header says). Built in
// memory and renamed into place (h5::AtomicFile), so a failure leaves neither a partial file nor a temporary.
// Errors: InputError (the OS error, e.g. a full disk), std::runtime_error (HDF5), std::logic_error (a dataset
// without units and description, a field that does not fill its shape, an inconsistent SystemTable, per-floor or
// per-element fields without a SystemTable or whose floors or elements differ from it -- refused before any file).
#include <string>

#include "pounding/results/results.hpp"

namespace pounding::results {

void write(const std::string& path, const Results& r);

}  // namespace pounding::results
