// The hysteresis registry's driver traits (model/hysteresis/registry.hpp, architecture.md 2.5.2, D9) give the
// decisions and numbers study/run.cpp computed by value before the registry, bit for bit: elastic_at's
// `peak <= margin * fy / k` and the IDA bisection's `fy /= f`, on 1e5 random bilinear specs (elastic fy = inf,
// zero stiffness, peaks exactly at and one ulp around the yield displacement included). And the identity
// unscaled_equivalent stands for, R(f w; spec) = f R(w; spec'), through the model's own restoring force.
// And the list's traits per model (docs/runner-design.md section 5): law_of and visit_hysteresis agree with the
// list, names, roles and lane_stepper as each model declares, pack/unpack a round trip, problems silent on a valid
// spec and naming the field on a bad one, load and stored_energy the rows the system stepper reads, stays_elastic by
// law the model's own answer; and no source outside the list names a model by its index.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <type_traits>
#include <cmath>
#include <cstdint>
#include <limits>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "pounding/model/hysteresis/registry.hpp"
#include "test_data.hpp"

namespace pounding {
namespace {

using model::BilinearKinematic;

static_assert(model::Hysteresis<BilinearKinematic>);
static_assert(model::Hysteresis<model::BoucWen> && model::Hysteresis<model::FrictionPendulum>);

Structure random_spec(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Structure s;
  s.m = std::exp(std::log(1e3) + u(rng) * std::log(1e7));
  s.k = std::exp(std::log(1e2) + u(rng) * std::log(1e10));
  const double pick = u(rng);
  s.fy = pick < 0.05 ? std::numeric_limits<double>::infinity() : std::exp(std::log(1e1) + u(rng) * std::log(1e8));
  if (pick > 0.999) s.k = 0.0;  // fy / 0: inf (or nan with fy = inf): the old expression's own answer stands
  s.alpha = u(rng) < 0.2 ? 0.0 : 0.2 * u(rng);
  return s;
}

// study/run.cpp elastic_at before the registry (commit 0032648), per body
bool elastic_before(double fy, double k, double u, double margin) { return u <= margin * fy / k; }

TEST(HysteresisTraits, BilinearStaysElasticIsTheOldExpressionBitForBit) {
  std::mt19937_64 rng(20251126);
  std::uniform_real_distribution<double> u(0.0, 2.0);
  constexpr double margin = 1.0 - 1e-9;  // study/run.cpp's
  int elastic = 0, yielded = 0;
  for (int n = 0; n < 100000; ++n) {
    const Structure s = random_spec(rng);
    const double uy = margin * s.fy / s.k;
    // a random peak, and peaks at, just below and just above the yield displacement
    for (double peak : {u(rng) * (std::isfinite(uy) ? uy : 1.0), uy, std::nextafter(uy, 0.0),
                        std::nextafter(uy, std::numeric_limits<double>::infinity())}) {
      const bool want = elastic_before(s.fy, s.k, peak, margin);
      ASSERT_EQ(BilinearKinematic::stays_elastic(s, peak, margin), want)
          << "k " << s.k << " fy " << s.fy << " peak " << peak;
      (want ? elastic : yielded) += 1;
    }
  }
  EXPECT_GT(elastic, 100000);  // both answers are exercised
  EXPECT_GT(yielded, 50000);
}

TEST(HysteresisTraits, BilinearUnscaledEquivalentIsTheOldDivisionBitForBit) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n = 0; n < 100000; ++n) {
    const Structure s = random_spec(rng);
    const double f = std::exp(std::log(1e-3) + u(rng) * std::log(1e6));
    Structure before = s;
    before.fy /= f;  // study/run.cpp's bisection before the registry: pp.s1.fy /= mid
    const std::optional<Structure> now = BilinearKinematic::unscaled_equivalent(s, f);
    ASSERT_TRUE(now.has_value());
    ASSERT_EQ(std::bit_cast<std::uint64_t>(now->fy), std::bit_cast<std::uint64_t>(before.fy)) << s.fy << " / " << f;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(now->k), std::bit_cast<std::uint64_t>(s.k));
    ASSERT_EQ(std::bit_cast<std::uint64_t>(now->alpha), std::bit_cast<std::uint64_t>(s.alpha));
    ASSERT_EQ(std::bit_cast<std::uint64_t>(now->m), std::bit_cast<std::uint64_t>(s.m));
    ASSERT_EQ(std::bit_cast<std::uint64_t>(now->c), std::bit_cast<std::uint64_t>(s.c));
  }
}

// What the trait promises, through the model's restoring force on a cyclic path that yields: R(f w; s) and
// f R(w; s') agree to round-off at every step (the kernel-level identity is tests/study/test_ida_scaling.cpp).
TEST(HysteresisTraits, BilinearUnscaledEquivalentScalesTheRestoringForce) {
  const Structure s{1e6, 4e7, 0.0, 2e5, 0.05};  // yield displacement 5 mm
  for (double f : {0.3, 2.5}) {
    const Structure se = *BilinearKinematic::unscaled_equivalent(s, f);
    const auto p = BilinearKinematic::params(s), pe = BilinearKinematic::params(se);
    double fs = 0.0, fse = 0.0, w_old = 0.0, worst = 0.0, w_max = 0.0;
    for (int i = 1; i <= 4000; ++i) {
      const double w = 0.02 / f * std::sin(i * 0.005) * (1.0 + i / 2000.0);  // f w: growing cycles to ~8x yield
      fs = BilinearKinematic::restoring<double>(p, fs, f * (w - w_old), f * w);
      fse = BilinearKinematic::restoring<double>(pe, fse, w - w_old, w);
      worst = std::max(worst, std::abs(fs - f * fse) / (f * s.fy));
      w_max = std::max(w_max, std::abs(f * w));
      w_old = w;
    }
    EXPECT_LT(worst, 1e-12) << "f " << f;
    EXPECT_GT(w_max, 4.0 * s.fy / s.k) << "the path yields";
    EXPECT_FALSE(BilinearKinematic::stays_elastic(s, w_max, 1.0));
  }
}

// One valid description per registered model, packed (the test's own table: a new model adds its line here).
template <class H> typename H::Spec valid_spec();
template <> Structure valid_spec<BilinearKinematic>() { return {0.0, 4e7, 0.0, 2e5, 0.05}; }
template <> model::BoucWen::Spec valid_spec<model::BoucWen>() { return {2e6, 0.1, 0.02, 1.0, 0.6, 0.4, 2}; }
template <> model::FrictionPendulum::Spec valid_spec<model::FrictionPendulum>() {
  return {5e6, 2.0, 0.04, 0.1, 30.0, 5e-4};
}
template <> model::TensionGap::Spec valid_spec<model::TensionGap>() { return {1e8, 2e6, 0.01, 0.03, 1}; }
template <> model::CompressionGap::Spec valid_spec<model::CompressionGap>() { return {4e8, 7e6, 0.0, 0.05, -1}; }
template <> model::HyperbolicGap::Spec valid_spec<model::HyperbolicGap>() { return {2.03e7, 2.5e7, 0.7, 3.26e5, 0.0254, 1}; }
template <> model::QHyst::Spec valid_spec<model::QHyst>() { return {3e7, 4e5, 0.03, 0.5}; }

struct Reported {
  std::vector<std::string> fields;
  void operator()(std::string_view field, std::string_view, std::string_view, auto...) { fields.emplace_back(field); }
};
template <class H> std::vector<std::string> problems_of(const model::SpringSpec& s) {
  Reported r;
  H::problems(s, r);
  return r.fields;
}
bool same_bits(const model::SpringSpec& a, const model::SpringSpec& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

template <class H> void check_model(int index) {
  SCOPED_TRACE(std::string(H::name));
  EXPECT_EQ(model::law_of<H>, index);
  EXPECT_EQ(model::hysteresis_name(index), H::name);
  EXPECT_EQ(model::law_named(H::name), index);
  bool visited = false;
  model::visit_hysteresis(index, [&]<class G>() { visited = std::is_same_v<G, H>; });
  EXPECT_TRUE(visited) << "visit_hysteresis(law_of<H>) calls H";
  EXPECT_EQ(model::runs_on_lane_stepper(index), H::lane_stepper);
  const auto spec = valid_spec<H>();
  const model::SpringSpec packed = H::pack(spec);
  EXPECT_TRUE(same_bits(H::pack(H::unpack(packed)), packed)) << "pack(unpack(s)) == s";
  EXPECT_TRUE(problems_of<H>(packed).empty()) << "a valid spec has no problems";
  EXPECT_GT(packed.k, 0.0) << "k: the initial tangent validation and omega_max read";
  // load: the rows hold the model's params, the force at rest in d0 from them; stored_energy is >= 0
  for (double d0 : {0.0, 0.004, -0.1}) {
    model::SpringRows r{};
    const double f0 = H::load(packed, d0, r);
    EXPECT_TRUE(std::isfinite(f0)) << d0;
    EXPECT_EQ(r[0], H::params(spec).k) << "slot 0: the model's k";
    EXPECT_GE(H::stored_energy(r, d0, f0), 0.0) << d0;
  }
  EXPECT_EQ(model::stays_elastic(index, packed, 1e-4, 1.0), H::stays_elastic(spec, 1e-4, 1.0));
  EXPECT_EQ(model::stays_elastic(index, packed, 1.0, 1.0), H::stays_elastic(spec, 1.0, 1.0));
}
template <class... Hs> void check_all(TypeList<Hs...>) {
  int i = 0;
  (check_model<Hs>(i++), ...);
}

TEST(HysteresisTraits, EachModelsTraitsFollowTheList) {
  check_all(model::Hystereses{});
  EXPECT_EQ(model::hysteresis_name(-1), "");
  EXPECT_EQ(model::hysteresis_name(static_cast<int>(model::Hystereses::size)), "");
  EXPECT_EQ(model::law_named("takeda-not-yet"), -1);
  bool called = false;
  model::visit_hysteresis(static_cast<int>(model::Hystereses::size), [&]<class>() { called = true; });
  EXPECT_FALSE(called) << "a law outside the list calls nothing";
  EXPECT_FALSE(model::stays_elastic(-1, model::SpringSpec{}, 0.0, 1.0));
}

TEST(HysteresisTraits, RolesLaneStepperAndFastPathAsEachModelDeclares) {
  const auto roles = [](int law) {
    const model::Roles& r = model::hysteresis_roles[static_cast<std::size_t>(law)];
    return std::string(r.storey ? "s" : "") + (r.isolator ? "i" : "") + (r.link ? "l" : "");
  };
  EXPECT_EQ(roles(model::law_of<BilinearKinematic>), "sil");  // storeys, linear and lead-rubber bearings, hinges
  EXPECT_EQ(roles(model::law_of<model::BoucWen>), "i");
  EXPECT_EQ(roles(model::law_of<model::FrictionPendulum>), "i");
  EXPECT_EQ(roles(model::law_of<model::TensionGap>), "l");
  EXPECT_EQ(roles(model::law_of<model::CompressionGap>), "l");
  EXPECT_EQ(roles(model::law_of<model::HyperbolicGap>), "l");
  EXPECT_EQ(roles(model::law_of<model::QHyst>), "sl");  // bridge frames' storeys
  int lane = 0;
  for (int law = 0; law < static_cast<int>(model::Hystereses::size); ++law) lane += model::runs_on_lane_stepper(law);
  EXPECT_EQ(lane, 1) << "Newmark and RK4 run the bilinear model only (they need its tangent)";
  int fast = 0;
  for (int law = 0; law < static_cast<int>(model::Hystereses::size); ++law) fast += model::fast_path(law);
  EXPECT_EQ(fast, 1) << "the system stepper's straight loop and stick path run the bilinear model only";
  EXPECT_TRUE(model::fast_path(model::law_of<BilinearKinematic>));
  EXPECT_FALSE(model::fast_path(-1));
  EXPECT_TRUE(model::runs_on_lane_stepper(model::law_of<BilinearKinematic>));
}

// Each model's problems name the field the driver's message uses, once per spring, on a planted bad number.
TEST(HysteresisTraits, ProblemsReportAPlantedBadNumber) {
  using Fields = std::vector<std::string>;
  model::SpringSpec s = model::BoucWen::pack(valid_spec<model::BoucWen>());
  s.p[2] = -1.0;  // u_y < 0
  EXPECT_EQ(problems_of<model::BoucWen>(s), Fields{"smooth"});
  s = model::FrictionPendulum::pack(valid_spec<model::FrictionPendulum>());
  s.p[5] = 0.0;  // u_y = 0
  EXPECT_EQ(problems_of<model::FrictionPendulum>(s), Fields{"smooth"});
  s = model::TensionGap::pack(valid_spec<model::TensionGap>());
  s.p[0] = -0.01;  // slack < 0
  EXPECT_EQ(problems_of<model::TensionGap>(s), Fields{"link"});
  s = model::CompressionGap::pack(valid_spec<model::CompressionGap>());
  s.p[1] = 0.5;  // side
  EXPECT_EQ(problems_of<model::CompressionGap>(s), Fields{"link"});
  s = model::HyperbolicGap::pack(valid_spec<model::HyperbolicGap>());
  s.k = 1e7;  // K_ur below K_max
  EXPECT_EQ(problems_of<model::HyperbolicGap>(s), Fields{"link"});
  s = model::QHyst::pack(valid_spec<model::QHyst>());
  s.p[0] = 1.5;  // beta outside [0, 1]
  EXPECT_EQ(problems_of<model::QHyst>(s), Fields{"link"});
}

// The list is the only place a model is named: no source in src/, include/ or tests/ tests a law by an index constant,
// a family predicate or a count of the list (each was a switch to edit for a new model before the traits).
TEST(HysteresisTraits, NoSourceNamesAModelByItsIndex) {
  const std::regex banned(R"(\blaw_(bilinear|bouc_wen|friction_pendulum|restrainer|abutment|hyperbolic_abutment|qhyst)\b|)"
                          R"(\bis_(gap|smooth)_law\b|Hystereses::size\s*==)");
  namespace fs = std::filesystem;
  int files = 0;
  for (const char* top : {"src", "include", "tests"})
    for (const auto& e : fs::recursive_directory_iterator(fs::path(testdata::source_dir()) / top)) {
      if (!e.is_regular_file() || e.path().filename() == "test_hysteresis_traits.cpp") continue;
      const auto ext = e.path().extension();
      if (ext != ".cpp" && ext != ".hpp") continue;
      ++files;
      std::ifstream in(e.path());
      std::string line;
      for (int n = 1; std::getline(in, line); ++n)
        EXPECT_FALSE(std::regex_search(line, banned)) << e.path().string() << ":" << n << ": " << line;
    }
  EXPECT_GT(files, 100);
}

}  // namespace
}  // namespace pounding
