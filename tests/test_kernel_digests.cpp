// Kernel digests (issue 11, criterion C2): SHA-256 of every BatchResult array for every stepper x contact
// law x Hertz exponent x energy on/off x Hertzdamp damping law, on benchmark_batch(37) under
// builtin_motion(0.005, 10) at 2 substeps. tests/data/kernel_digests.txt was written by this file built
// against fd5ca6f (before the redesign); any change of a last bit in any configuration fails here. A
// deliberate change regenerates the file in its own commit, with the reason:
//   POUNDING_WRITE_DIGESTS=tests/data/kernel_digests.txt build/test_kernel_digests
#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "pounding/contact/registry.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/workloads/workloads.hpp"

#ifndef POUNDING_TEST_SOURCE_DIR
#error "POUNDING_TEST_SOURCE_DIR is set by CMakeLists.txt for the test targets"
#endif
#ifndef POUNDING_BITS_NOT_CLAIMED
#error "POUNDING_BITS_NOT_CLAIMED (empty, or why this build makes no identical-bits claim) is set by CMakeLists.txt"
#endif

using namespace pounding;

namespace {

// FIPS 180-4 SHA-256, enough for digests of test data.
class Sha256 {
 public:
  void update(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
      block_[fill_++] = p[i];
      if (fill_ == 64) compress(), fill_ = 0;
    }
    bits_ += 8ULL * n;
  }
  std::string hex() {
    const std::uint64_t bits = bits_;
    const unsigned char pad = 0x80, zero = 0;
    update(&pad, 1);
    while (fill_ != 56) update(&zero, 1);
    for (int i = 7; i >= 0; --i) {
      const auto b = static_cast<unsigned char>(bits >> (8 * i));
      update(&b, 1);
    }
    std::string out;
    char buf[9];
    for (auto w : h_) std::snprintf(buf, sizeof buf, "%08x", w), out += buf;
    return out;
  }

 private:
  static std::uint32_t rotr(std::uint32_t x, int n) { return (x >> n) | (x << (32 - n)); }
  void compress() {
    static constexpr std::uint32_t k[64] = {
        0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
        0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
        0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
        0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
        0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
        0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
        0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
        0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2};
    std::uint32_t w[64];
    for (int i = 0; i < 16; ++i)
      w[i] = std::uint32_t(block_[4 * i]) << 24 | std::uint32_t(block_[4 * i + 1]) << 16 |
             std::uint32_t(block_[4 * i + 2]) << 8 | std::uint32_t(block_[4 * i + 3]);
    for (int i = 16; i < 64; ++i) {
      const std::uint32_t s0 = rotr(w[i - 15], 7) ^ rotr(w[i - 15], 18) ^ (w[i - 15] >> 3);
      const std::uint32_t s1 = rotr(w[i - 2], 17) ^ rotr(w[i - 2], 19) ^ (w[i - 2] >> 10);
      w[i] = w[i - 16] + s0 + w[i - 7] + s1;
    }
    std::uint32_t a = h_[0], b = h_[1], c = h_[2], d = h_[3], e = h_[4], f = h_[5], g = h_[6], h = h_[7];
    for (int i = 0; i < 64; ++i) {
      const std::uint32_t t1 = h + (rotr(e, 6) ^ rotr(e, 11) ^ rotr(e, 25)) + ((e & f) ^ (~e & g)) + k[i] + w[i];
      const std::uint32_t t2 = (rotr(a, 2) ^ rotr(a, 13) ^ rotr(a, 22)) + ((a & b) ^ (a & c) ^ (b & c));
      h = g, g = f, f = e, e = d + t1, d = c, c = b, b = a, a = t1 + t2;
    }
    h_[0] += a, h_[1] += b, h_[2] += c, h_[3] += d, h_[4] += e, h_[5] += f, h_[6] += g, h_[7] += h;
  }
  std::array<std::uint32_t, 8> h_{0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
                                  0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};
  std::array<unsigned char, 64> block_{};
  std::size_t fill_ = 0;
  std::uint64_t bits_ = 0;
};

template <class V>
void add(Sha256& s, const V& v) {
  s.update(v.data(), v.size() * sizeof(v[0]));
}

std::string digest(const BatchResult& r) {
  Sha256 s;
  add(s, r.peak_u1), add(s, r.peak_u2), add(s, r.peak_closing), add(s, r.t_peak_closing);
  add(s, r.t_first_impact), add(s, r.impact_count), add(s, r.peak_force), add(s, r.peak_penetration);
  add(s, r.contact_energy), add(s, r.contact_time), add(s, r.peak_acc1), add(s, r.peak_acc2);
  add(s, r.clamp_count), add(s, r.status), add(s, r.final_u1), add(s, r.final_v1), add(s, r.final_u2);
  add(s, r.final_v2), add(s, r.e_input), add(s, r.e_kinetic), add(s, r.e_strain), add(s, r.e_viscous);
  add(s, r.e_hysteretic), add(s, r.e_contact_stored);
  return s.hex();
}

// Every configuration's name -> digest, computed now.
std::map<std::string, std::string> compute_all() {
  const PairBatch batch = benchmark_batch(37);
  const std::vector<double> ag = builtin_motion(0.005, 10.0);
  GroundMotion gm{0.005, ag, 0.0};
  std::map<std::string, std::string> out;
  for (Stepper st : {Stepper::central_difference, Stepper::newmark, Stepper::rk4, Stepper::nigam_jennings})
    for (ContactLaw law : contact::law_ids)
      for (double n : {1.5, 1.3})
        for (bool energy : {false, true})
          for (DampingLaw dl : {DampingLaw::lankarani_nikravesh, DampingLaw::calibrated}) {
            ContactModel cm;
            cm.law = law, cm.damping = dl, cm.n = n;
            KernelSettings ks;
            ks.stepper = st, ks.substeps = 2, ks.energy = energy;
            BatchResult r;
            run_batch(batch, cm, gm, ks, r);
            std::ostringstream name;
            name << to_string(st) << ' ' << to_string(law) << " n=" << n << " energy=" << energy << ' '
                 << to_string(dl);
            out[name.str()] = digest(r);
          }
  return out;
}

}  // namespace

TEST(KernelDigests, Sha256KnownAnswers) {  // FIPS 180-4 examples: the digest itself is right
  Sha256 a;
  a.update("abc", 3);
  EXPECT_EQ(a.hex(), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  Sha256 b;
  const char* m = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
  b.update(m, std::strlen(m));
  EXPECT_EQ(b.hex(), "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(KernelDigests, EveryConfigurationBitIdenticalToTheStoredBaseline) {
  // The stored digests are claimed for the Release build only (CMakeLists.txt, POUNDING_BITS_NOT_CLAIMED).
  if (const std::string why = POUNDING_BITS_NOT_CLAIMED; !why.empty() && !std::getenv("POUNDING_WRITE_DIGESTS"))
    GTEST_SKIP() << "not applicable: " << why;
  const auto now = compute_all();
  if (const char* path = std::getenv("POUNDING_WRITE_DIGESTS")) {
    std::ofstream f(path);
    f << "# SHA-256 of every BatchResult array: stepper, law, n, energy, damping law -> digest\n";
    for (const auto& [k, v] : now) f << k << " = " << v << '\n';
    GTEST_SKIP() << "wrote " << now.size() << " digests to " << path;
  }
  std::ifstream f(std::string(POUNDING_TEST_SOURCE_DIR) + "/tests/data/kernel_digests.txt");
  ASSERT_TRUE(f) << "tests/data/kernel_digests.txt is missing";
  std::map<std::string, std::string> stored;
  std::string line;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto eq = line.find(" = ");
    stored[line.substr(0, eq)] = line.substr(eq + 3);
  }
  ASSERT_EQ(stored.size(), now.size());
  int differ = 0;
  for (const auto& [k, v] : now) {
    auto it = stored.find(k);
    ASSERT_NE(it, stored.end()) << "no stored digest for " << k;
    if (it->second != v) ++differ, ADD_FAILURE() << k << ": digest changed";
  }
  EXPECT_EQ(differ, 0) << "of " << now.size() << " configurations";
}
