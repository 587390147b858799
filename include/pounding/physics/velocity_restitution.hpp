#pragma once
// The kernel's e(v0) hook (VelocityRestitution, issue 26 §3) for Hertzdamp: at each contact onset the lane's
// damping becomes xibar(e(v0)) / v0 (the damping law's xibar of the curve's e at the latched approach velocity v0,
// contact/restitution.hpp), and onsets outside the curve's valid range are counted (BatchResult::restitution_outside).
// The object owns the curve and must outlive the run that points at it (KernelSettings::restitution = &x.hook).
#include "pounding/contact/model.hpp"
#include "pounding/contact/restitution.hpp"
#include "pounding/kernel/batch.hpp"

namespace pounding::physics {

class HertzdampRestitution {
 public:
  HertzdampRestitution(contact::RestitutionCurve curve, const ContactModel& cm) : curve_(std::move(curve)), cm_(cm) {
    hook.self = this;
    hook.damping = [](const void* self, double v0) {
      const auto* h = static_cast<const HertzdampRestitution*>(self);
      return hertzdamp_xibar(h->cm_.damping, h->curve_(v0), h->cm_.n);
    };
    hook.outside = [](const void* self, double v0) {
      return !static_cast<const HertzdampRestitution*>(self)->curve_.in_range(v0);
    };
  }
  HertzdampRestitution(const HertzdampRestitution&) = delete;
  HertzdampRestitution& operator=(const HertzdampRestitution&) = delete;
  const contact::RestitutionCurve& curve() const { return curve_; }
  VelocityRestitution hook;

 private:
  contact::RestitutionCurve curve_;
  ContactModel cm_;
};

}  // namespace pounding::physics
