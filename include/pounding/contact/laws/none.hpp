#pragma once
// No contact element: the uncoupled pair.
#include "pounding/contact/law.hpp"

namespace pounding::contact {

struct None : NoForceElement {
  static constexpr std::string_view name = "none";
  static constexpr LawTraits traits{.has_force = false, .needs_stiffness = false,
                                    .restitution = RestitutionKind::elastic,
                                    .restitution_note = "no contact element: the bodies pass through each other"};
  static constexpr ResolutionLimits resolution = ResolutionLimits::no_force_element();
};

}  // namespace pounding::contact
