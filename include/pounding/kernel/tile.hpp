#pragma once
// One tile of lanes: derived constants, state, observer accumulators, stepper scratch. Members are distinct
// arrays, so the compiler knows they do not alias; a lane's arithmetic depends only on its own inputs.
#include <limits>

#include "pounding/kernel/batch.hpp"

namespace pounding::kernel {

inline constexpr int tile_width = 64;
inline constexpr double inf = std::numeric_limits<double>::infinity();
// Internal stand-in for an infinite yield force: finite so that qy * 0 == 0 in the dissipation sum.
inline constexpr double elastic_qy = 1e300;

struct alignas(64) Tile {
  int n = 0;   // lanes in use
  int np = 0;  // lanes padded to the SIMD width (copies of the first lane): the array steppers run all of them
  // constants
  double m1[tile_width], m2[tile_width], im1[tile_width], im2[tile_width];
  double k1[tile_width], k2[tile_width], c1[tile_width], c2[tile_width];
  double ak1[tile_width], ak2[tile_width];    // alpha k
  double qy1[tile_width], qy2[tile_width];    // (1 - alpha) fy: half-width of the kinematic band
  double kp1[tile_width], kp2[tile_width];    // (1 - alpha) k: stiffness of the elasto-plastic part
  double gap[tile_width], kc[tile_width], cd[tile_width], e[tile_width], meff[tile_width];
  // state
  double u1[tile_width], v1[tile_width], a1[tile_width], fs1[tile_width];
  double u2[tile_width], v2[tile_width], a2[tile_width], fs2[tile_width];
  double F[tile_width], iv0[tile_width], dprev[tile_width];
  // observers
  double pu1[tile_width], pu2[tile_width], pclose[tile_width], tpclose[tile_width], tfirst[tile_width];
  double nimp[tile_width], nclamp[tile_width], pF[tile_width], ppen[tile_width], Wc[tile_width];
  double tcon[tile_width], pa1[tile_width], pa2[tile_width], bad[tile_width];
  double nout[tile_width];  // onsets outside the e(v0) curve's valid range (KernelSettings::restitution)
  // energy
  double Ein[tile_width], Evis[tile_width], Ehys[tile_width], Dimp[tile_width];
  // scratch (Newton iterates, NJ coefficients)
  double x1[tile_width], x2[tile_width], y1[tile_width], y2[tile_width], conv[tile_width], sw[tile_width];
  double nj1[8][tile_width], nj2[8][tile_width];
};

// The schedule and settings one tile runs with.
struct Context {
  const KernelSettings* settings;
  const double* ag;  // ground acceleration at every integration step (size nsteps + 1)
  long nsteps;
  double h;
  double v0_min;
  double lim;            // displacement limit of the divergence guard
  SeriesRecorder* rec;   // null unless the recorded lane is in this tile
  int rec_lane;
};

}  // namespace pounding::kernel
