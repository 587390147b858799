#pragma once
// Writes a Results to an HDF5 file (format 1, bit-compatible with the files written before this module):
// built in memory and renamed into place (h5::AtomicFile), so a failure leaves neither a partial file nor a
// temporary. Errors: InputError (the OS error, e.g. a full disk) or std::runtime_error (HDF5).
#include <string>

#include "pounding/results/results.hpp"

namespace pounding::results {

void write(const std::string& path, const Results& r);

}  // namespace pounding::results
