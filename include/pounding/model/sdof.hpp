#pragma once
// A single-degree-of-freedom structure (mass m, viscous damping c from the tile) whose spring is a hysteresis
// law H: the StructureModel the steppers run by default is Sdof<BilinearKinematic> (model::Registered).
#include "pounding/model/hysteresis/bilinear_kinematic.hpp"
#include "pounding/model/structure_model.hpp"

namespace pounding::model {

template <class H> struct Sdof {
  using Spring = H;  // the hysteresis model (model/hysteresis/registry.hpp)
  static constexpr int dofs = 1, contact_dof = 0;
  template <class T> using Params = typename H::template Params<T>;
  template <class T> struct State { T u, fs; };  // committed displacement and restoring force

  static Params<double> params(const Structure& s) { return H::params(s); }
  static void store(kernel::Tile& t, int body, int i, const Params<double>& p) { H::store(t, body, i, p); }
  template <class T> POUNDING_INLINE static Params<T> load(const kernel::Tile& t, int body, int i) {
    return H::template load<T>(t, body, i);
  }
  static double initial_force(const Params<double>& p, double u0) { return H::initial_force(p, u0); }
  template <class T> POUNDING_INLINE static T restoring(const Params<T>& p, State<T> c, T u_new, T du) {
    return H::template restoring<T>(p, c.fs, du, u_new);
  }
  template <class T> POUNDING_INLINE static T tangent(const Params<T>& p, State<T> c, T, T du, T fs_new) {
    return H::template tangent<T>(p, c.fs, du, fs_new);
  }
  template <class T> POUNDING_INLINE static T linear_stiffness(const Params<T>& p) { return p.k; }
  template <class T> POUNDING_INLINE static T hysteretic_increment(const Params<T>& p, State<T> c, T du, T fs_new) {
    return H::template dissipated<T>(p, c.fs, du, fs_new);
  }
  static double strain_energy(const Params<double>& p, double u, double fs) { return H::strain_energy(p, u, fs); }
};

using Registered = Sdof<BilinearKinematic>;
static_assert(StructureModel<Registered>);

}  // namespace pounding::model
