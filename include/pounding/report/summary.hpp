#pragma once
// Text summaries of kernel results: one `name: value` per line (SI units in the names).
#include <string>

#include "pounding/contact/model.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/motion/records.hpp"

namespace pounding {

std::string format_summary(const BatchResult& r, std::size_t lane, const ContactModel& cm, const PairParams& p,
                           const Record& rec, const KernelSettings& ks);

}  // namespace pounding
