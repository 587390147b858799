#pragma once
// Writes a Results to an HDF5 file in the current format (schema.hpp's format_version, whatever the Header says;
// docs/results-format.md): built in memory and renamed into place (h5::AtomicFile), so a failure leaves neither a
// partial file nor a temporary. Errors: InputError (the OS error, e.g. a full disk), std::runtime_error (HDF5),
// std::logic_error (a dataset without units and description, or a field that does not fill its shape).
#include <string>

#include "pounding/results/results.hpp"

namespace pounding::results {

void write(const std::string& path, const Results& r);

}  // namespace pounding::results
