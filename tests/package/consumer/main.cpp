// One pair of bilinear SDOF structures through pounding::run_batch under the builtin motion, as a program
// outside the repository would write it (tests/package/run_consumer.cmake builds it against an install).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "pounding/contact/model.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/core/version.hpp"
#include "pounding/io/hdf5.hpp"
#include "pounding/workloads/workloads.hpp"

int main() {
  using namespace pounding;
  PairBatch batch;
  batch.resize(1);
  PairParams p;
  p.s1 = Structure::from_period(1.0e7, 1.0, 0.05);
  p.s2 = Structure::from_period(1.2e7, 1.4, 0.05);
  p.gap = 0.05;
  p.kc = hertz_stiffness_spheres(1.0e7, 1.2e7, 2400.0, 24.86e9, 0.15);
  p.e = 0.65;
  batch.set(0, p);

  const double dt = 0.01;
  const std::vector<double> ag = builtin_motion(dt, 20.0);
  GroundMotion motion;
  motion.dt = dt;
  motion.ag = ag;
  ContactModel contact;  // Hertzdamp, Lankarani-Nikravesh
  KernelSettings settings;
  settings.substeps = 10;
  BatchResult out;
  run_batch(batch, contact, motion, settings, out);

  const bool ok = out.status[0] == static_cast<std::uint8_t>(LaneStatus::ok) && std::isfinite(out.peak_closing[0]) &&
                  out.peak_closing[0] > 0;
  std::printf("pounding %s: peak closing %.6g m, %d impacts, status %s\n", program_version, out.peak_closing[0],
              out.impact_count[0], std::string(to_string(static_cast<LaneStatus>(out.status[0]))).c_str());
  // HDF5 through pounding::io: the package's HDF5 link dependency works without FindHDF5 in this C++-only project
  const std::string h5 = "consumer-peak.h5";
  {
    h5::AtomicFile file(h5);
    h5::write_dataset(file.root(), "peak_closing", std::span<const double>(out.peak_closing.data(), 1));
    file.commit();
  }
  const std::vector<double> back = h5::read_doubles(h5::open_read(h5).get(), "peak_closing");
  std::remove(h5.c_str());
  std::printf("HDF5 round trip: %s\n", back.size() == 1 && back[0] == out.peak_closing[0] ? "ok" : "FAILED");
  return ok && back.size() == 1 && back[0] == out.peak_closing[0] ? 0 : 1;
}
