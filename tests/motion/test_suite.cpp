// Record suites: the seed study's Table 1 as a suite file, its resolution to the four real records
// in ../shared/records/real (checked against MANIFEST.tsv) and to synthetic stand-ins at the listed
// PGA, and every suite-file error naming file, line and key.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <unistd.h>

#include "pounding/core/error.hpp"
#include "pounding/motion/suite.hpp"
#include "test_data.hpp"

using namespace pounding;
namespace fs = std::filesystem;

namespace {

const std::string src_dir = testdata::source_dir();
const std::string real_dir = testdata::real_records_dir();

void expect_suite_error(const std::string& text, int line, const std::string& needle) {
  try {
    parse_suite(text, "s.toml");
    FAIL() << "no error for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), line > 0 ? "s.toml:" + std::to_string(line) : "s.toml") << e.what();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

std::map<std::string, double> manifest_pga() {
  std::map<std::string, double> m;
  std::ifstream in(real_dir + "/MANIFEST.tsv");
  std::string line;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string f[9];
    for (auto& x : f) std::getline(ss, x, '\t');
    if (f[0] != "file" && !f[8].empty()) m[f[0]] = std::stod(f[8]);
  }
  return m;
}

}  // namespace

// The build embeds the records file byte for byte (cmake/Embed.cmake: raw string, no newline added or lost).
TEST(SuiteFile, EmbeddedDefaultIsTheRecordsFile) {
  std::ifstream in(src_dir + "/records/stochastic-pounding-suite.toml", std::ios::binary);
  ASSERT_TRUE(in);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), default_suite_text());
}

TEST(SuiteFile, HoldsTable1OfTheSeedStudy) {
  const Suite s = load_suite(src_dir + "/records/stochastic-pounding-suite.toml");
  ASSERT_EQ(s.entries.size(), 25u);
  // spot checks against the cleaned Table 1
  const SuiteEntry& e1 = s.entries[0];
  EXPECT_EQ(e1.id, "EQ1");
  EXPECT_EQ(e1.event, "Morgan Hill");
  EXPECT_EQ(e1.year, 1984);
  EXPECT_EQ(e1.station, "Gilroy Array #4");
  ASSERT_TRUE(e1.site);
  EXPECT_DOUBLE_EQ(e1.site->M, 6.2);
  EXPECT_DOUBLE_EQ(e1.site->R_km, 11.5);
  EXPECT_DOUBLE_EQ(e1.site->vs30, 221.78);
  EXPECT_EQ(e1.site->F, 0);
  EXPECT_DOUBLE_EQ(e1.pga_g, 0.35);
  EXPECT_DOUBLE_EQ(s.entries[12].pga_g, 0.99);  // EQ13 Tarzana
  EXPECT_DOUBLE_EQ(s.entries[16].site->M, 6.8);  // EQ17, M read from neighbouring rows
  EXPECT_EQ(s.entries[20].station, "Kawanishi Izumozaki EW");
  EXPECT_EQ(s.entries[23].station, "Misato, Miyagi Kitaura");
  EXPECT_DOUBLE_EQ(s.entries[24].site->R_km, 38.0);
  // ranges stated in the paper: M 6-7.5, PGA 0.3-1 g, R 11-38 km
  std::set<std::uint64_t> seeds;
  for (const auto& e : s.entries) {
    EXPECT_GE(e.site->M, 6.0);
    EXPECT_LE(e.site->M, 7.5);
    EXPECT_GE(e.pga_g, 0.3);
    EXPECT_LE(e.pga_g, 1.0);
    EXPECT_GE(e.site->R_km, 10.9);
    EXPECT_LE(e.site->R_km, 38.0);
    seeds.insert(e.seed);
  }
  EXPECT_EQ(seeds.size(), 25u);  // distinct streams
}

TEST(SuiteResolve, FourRealRecordsFromTheSharedDirectoryTheRestSynthetic) {
  POUNDING_REQUIRE_REAL_RECORDS();
  const auto pga = manifest_pga();
  const Suite s = default_suite();
  ResolveOptions o;
  o.records_dir = real_dir;
  const auto t0 = std::chrono::steady_clock::now();
  const auto rs = resolve_suite(s, o);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(rs.size(), 25u);
  // the component whose PGA is closest to Table 1's: Poe Road 270 (0.4463 vs 0.47), Capitola 000
  // (0.5285 vs 0.51), Coolwater TR (0.4169 vs 0.42), Duzce 270 (0.3579 vs 0.36)
  const std::map<std::string, std::string> expect = {{"EQ2", "SuperstitionHills_1987_PoeRoadTemp_270.txt"},
                                                     {"EQ3", "LomaPrieta_1989_Capitola_000.txt"},
                                                     {"EQ6", "Landers_1992_Coolwater_TR.txt"},
                                                     {"EQ15", "Kocaeli_1999_Duzce_270.txt"}};
  int real = 0;
  for (std::size_t i = 0; i < rs.size(); ++i) {
    const auto& r = rs[i];
    SCOPED_TRACE(r.id + ": " + r.note);
    EXPECT_EQ(r.id, s.entries[i].id);
    EXPECT_EQ(r.synthetic, r.record.synthetic());
    if (auto it = expect.find(r.id); it != expect.end()) {
      ASSERT_FALSE(r.synthetic);
      ++real;
      EXPECT_EQ(fs::path(r.record.source).filename().string(), it->second);
      EXPECT_NEAR(r.record.pga() / g_accel, pga.at(it->second), 1e-3 * pga.at(it->second));  // unscaled
      EXPECT_DOUBLE_EQ(r.scale, 1.0);
    } else {
      ASSERT_TRUE(r.synthetic);
      EXPECT_NEAR(r.record.pga() / g_accel, s.entries[i].pga_g, 1e-12);
      EXPECT_DOUBLE_EQ(r.record.dt, 0.01);
    }
  }
  EXPECT_EQ(real, 4);
  std::printf("suite resolved (4 real + 21 synthetic) in %.3f s\n", secs);
}

TEST(SuiteResolve, AllSyntheticIsReproducible) {
  const Suite s = default_suite();
  ResolveOptions o;
  o.synthetic_only = true;
  const auto t0 = std::chrono::steady_clock::now();
  const auto a = resolve_suite(s, o);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto b = resolve_suite(s, o);
  std::size_t samples = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_TRUE(a[i].synthetic);
    ASSERT_EQ(a[i].record.acc.size(), b[i].record.acc.size());
    EXPECT_EQ(0, std::memcmp(a[i].record.acc.data(), b[i].record.acc.data(), a[i].record.acc.size() * sizeof(double)));
    EXPECT_NEAR(a[i].record.pga() / g_accel, s.entries[i].pga_g, 1e-12);
    samples += a[i].record.acc.size();
  }
  std::printf("25 synthetic records (%zu samples) generated in %.3f s\n", samples, secs);
}

TEST(SuiteResolve, UserFilesWithScaleAndRelativePaths) {
  const fs::path dir = fs::temp_directory_path() / "pounding_test_suite";
  fs::create_directories(dir);
  {
    std::ofstream(dir / "a.txt") << "0 0\n0.01 0.1\n0.02 -0.2\n";
    std::ofstream(dir / "user.toml") << "[suite]\nname = \"mine\"\n[[record]]\nid = \"A\"\nfile = \"a.txt\"\nscale = 2.5\n";
  }
  const Suite s = load_suite((dir / "user.toml").string());
  const auto rs = resolve_suite(s);
  ASSERT_EQ(rs.size(), 1u);
  EXPECT_FALSE(rs[0].synthetic);
  EXPECT_NEAR(rs[0].record.pga(), 2.5 * 0.2 * g_accel, 1e-12);
  // real files are never replaced silently: a missing file is an error
  {
    std::ofstream(dir / "user.toml") << "[[record]]\nid = \"A\"\nfile = \"missing.AT2\"\nM = 7\nR_km = 10\nvs30 = 300\nF = 0\n";
  }
  EXPECT_THROW(resolve_suite(load_suite((dir / "user.toml").string())), InputError);
  fs::remove_all(dir);
}

TEST(SuiteResolve, RequireRealRefusesSyntheticStandIns) {
  const Suite s = default_suite();
  ResolveOptions o;
  o.allow_synthetic = false;
  try {
    resolve_entry(s, s.entries[0], o);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("EQ1"), std::string::npos);
    EXPECT_EQ(e.where(), s.path + ":" + std::to_string(s.entries[0].line));
  }
}

TEST(SuiteErrors, NameFileLineAndKey) {
  expect_suite_error("[[record]]\nid = \"A\"\nfile = \"a\"\nspeed = 3\n", 4, "unknown key 'speed'");
  expect_suite_error("[[record]]\nfile = \"a\"\n", 1, "without id");
  expect_suite_error("[[record]]\nid = \"A\"\nfile = \"a\"\n[[record]]\nid = \"A\"\nfile = \"b\"\n", 5, "repeated");
  expect_suite_error("[[record]]\nid = \"A\"\nM = 7\nR_km = 10\nvs30 = 300\nF = 2\n", 6, "F = 2");
  expect_suite_error("[[record]]\nid = \"A\"\nM = \"big\"\n", 3, "M must be a number");
  expect_suite_error("[[record]]\nid = \"A\"\nM = 7\n", 1, "neither file nor a complete site");
  expect_suite_error("[suite]\nname = \"x\"\n[[record]]\nid = \"A\"\nfile = \"a\"\npga_g = -1\n", 6, "pga_g = -1");
  expect_suite_error("[suite]\ndt = 0\n[[record]]\nid = \"A\"\nfile = \"a\"\n", 2, "dt = 0");
  expect_suite_error("[suite]\nname = \"x\"\n", 0, "no [[record]] entries");
  expect_suite_error("[suite]\nname = \"x\n", 2, "TOML syntax");
  expect_suite_error("[[record]]\nid = \"A\"\nM = 12\nR_km = 10\nvs30 = 300\nF = 0\n", 1, "M = 12");
  expect_suite_error("[[record]]\nid = \"A\"\nfile = \"a\"\nunits = \"furlongs\"\n", 4, "units = 'furlongs'");
}

// Issue 23 item 7: a suite's records directory is listed by record_files_in, the one reader of a records
// directory (a study's [records] directory and `records select --directory` use it): a directory without .AT2 or
// .txt files is an error naming it, not a silent fall-back to synthetic stand-ins for every entry.
TEST(SuiteResolve, ADirectoryWithoutRecordsIsAnError) {
  const fs::path dir = fs::temp_directory_path() / ("pounding_suite_empty_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "notes.dat") << "1 2 3\n";
  ResolveOptions o;
  o.records_dir = dir.string();
  try {
    resolve_suite(default_suite(), o);
    ADD_FAILURE() << "a directory without records was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.what_part().find("no .AT2 or .txt records"), std::string::npos) << e.what();
    EXPECT_EQ(e.where(), dir.string());
    EXPECT_NE(e.fix().find("real_dir"), std::string::npos) << e.fix();
  }
  fs::remove_all(dir);
}
