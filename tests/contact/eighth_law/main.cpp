// ctest contact.registry_eighth_law (run.cmake): compiled against a copy of include/ whose registry holds an
// eighth law (eighth.hpp). Asks the resolution guard for the eighth law's limit, at run time as the kernel does.
#include "pounding/contact/registry.hpp"
#include "pounding/physics/resolution.hpp"

int main(int argc, char**) {
  using namespace pounding;
  static_assert(contact::Laws::size == 8, "the registry holds the eighth law");
  const Stepper s = argc > 1 ? Stepper::rk4 : Stepper::central_difference;
  return physics::resolution_limit(s, false, ContactLaw::eighth) > 0.0 ? 0 : 1;
}
