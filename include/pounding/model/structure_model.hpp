#pragma once
// What every structure model is written against (architecture.md 2.5): per-lane parameters Params<T> kept in
// the tile, the committed state State<T> (displacement and restoring force of each DOF), and the functions
// the steppers call, written once over the lane type T (double or simd::V):
//   restoring(p, committed, u_new, du)            the force after the increment du = u_new - committed.u
//                                                 (passed, not recomputed: central difference forms it as h v)
//   tangent(p, committed, u_new, du, fs_new)      dfs/du at the new state (Newmark's Newton iteration)
//   linear_stiffness(p)                           the stiffness of the linear part (Nigam-Jennings advances
//                                                 m, c and this exactly; the rest is a remainder load)
//   hysteretic_increment(p, committed, du, fs_new) energy dissipated by the increment (energy balance)
//   strain_energy(p, u, fs)                       recoverable energy at a state
// plus params(Structure), store/load to and from the tile, initial_force(p, u0), dofs and the contact DOF.
// Today every model is an SDOF (dofs == 1, contact at DOF 0); the steppers static_assert it.
#include <concepts>

#include "pounding/kernel/lane.hpp"
#include "pounding/kernel/tile.hpp"

namespace pounding::model {

template <class M>
concept StructureModel =
    requires(const typename M::template Params<double>& p, typename M::template State<double> s,
             const typename M::template Params<simd::V>& pv, typename M::template State<simd::V> sv, double x,
             simd::V y, const kernel::Tile& t, kernel::Tile& tm, const Structure& st) {
      { M::dofs } -> std::convertible_to<int>;
      { M::contact_dof } -> std::convertible_to<int>;
      { s.u } -> std::convertible_to<double>;
      { s.fs } -> std::convertible_to<double>;
      { M::params(st) } -> std::same_as<typename M::template Params<double>>;
      M::store(tm, 0, 0, p);
      { M::template load<double>(t, 0, 0) } -> std::same_as<typename M::template Params<double>>;
      { M::template load<simd::V>(t, 1, 0) } -> std::same_as<typename M::template Params<simd::V>>;
      { M::initial_force(p, x) } -> std::same_as<double>;
      { M::template restoring<double>(p, s, x, x) } -> std::same_as<double>;
      { M::template restoring<simd::V>(pv, sv, y, y) } -> std::same_as<simd::V>;
      { M::template tangent<double>(p, s, x, x, x) } -> std::same_as<double>;
      { M::template linear_stiffness<double>(p) } -> std::same_as<double>;
      { M::template hysteretic_increment<double>(p, s, x, x) } -> std::same_as<double>;
      { M::template hysteretic_increment<simd::V>(pv, sv, y, y) } -> std::same_as<simd::V>;
      { M::strain_energy(p, x, x) } -> std::same_as<double>;
    };

}  // namespace pounding::model
