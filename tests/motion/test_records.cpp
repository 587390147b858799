// Record readers: every real file against MANIFEST.tsv (numbers we did not compute), the formats'
// edge cases, every bad-input error naming file and line, the AT2 writer round trip, and the
// intensity measures against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "pounding/core/error.hpp"
#include "pounding/motion/records.hpp"
#include "test_data.hpp"

using namespace pounding;
namespace fs = std::filesystem;

namespace {

const std::string real_dir = testdata::real_records_dir();

std::vector<std::string> split_tab(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string f;
  while (std::getline(ss, f, '\t')) out.push_back(f);
  return out;
}

// Expects parse_record(text) to throw an InputError whose where() is "name:line" and whose message
// contains `needle`.
void expect_error(const std::string& text, int line, const std::string& needle, ReadOptions o = {}) {
  try {
    parse_record(text, "bad.AT2", o);
    FAIL() << "no error for:\n" << text;
  } catch (const InputError& e) {
    if (line > 0) EXPECT_EQ(e.where(), "bad.AT2:" + std::to_string(line)) << e.what();
    else EXPECT_EQ(e.where(), "bad.AT2") << e.what();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

std::string fmt_value(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%15.7E", v);
  return b;
}

const char* at2_header = "PEER NGA STRONG MOTION DATABASE RECORD\nX, 1/1/2000, Y, 0\nACCELERATION TIME SERIES IN UNITS OF G\n";

}  // namespace

TEST(RecordsManifest, EveryRealRecordMatchesManifest) {
  POUNDING_REQUIRE_REAL_RECORDS();
  std::ifstream in(real_dir + "/MANIFEST.tsv");
  ASSERT_TRUE(in) << real_dir << "/MANIFEST.tsv";
  std::string line;
  std::getline(in, line);
  const auto head = split_tab(line);
  ASSERT_GE(head.size(), 9u);
  ASSERT_EQ(head[0], "file");
  ASSERT_EQ(head[5], "format");
  ASSERT_EQ(head[6], "dt_s");
  ASSERT_EQ(head[7], "npts");
  ASSERT_EQ(head[8], "pga_g");
  int n = 0;
  double worst = 0;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const auto f = split_tab(line);
    ASSERT_GE(f.size(), 9u) << line;
    SCOPED_TRACE(f[0]);
    const Record r = read_record(real_dir + "/" + f[0]);
    const double dt = std::stod(f[6]);
    const std::size_t npts = std::stoul(f[7]);
    const double pga = std::stod(f[8]);
    EXPECT_EQ(r.acc.size(), npts);
    EXPECT_NEAR(r.dt, dt, 1e-6 * dt);
    // 0.1 %, or half a unit of the manifest's last printed digit when that is coarser (0.0283 g is
    // printed to 4 decimals: +-0.00005 g is already 0.18 %).
    const auto dot = f[8].find('.');
    const int decimals = dot == std::string::npos ? 0 : static_cast<int>(f[8].size() - dot - 1);
    const double printed = 0.5 * std::pow(10.0, -decimals);
    const double err = std::abs(r.pga() / g_accel - pga);
    worst = std::max(worst, err / pga);
    EXPECT_LE(err, std::max(1e-3 * pga, printed)) << "PGA " << r.pga() / g_accel << " g vs manifest " << pga;
    // The format we detect agrees with the manifest's family.
    const std::string fmt = r.meta.at("format");
    if (f[5] == "TIME_ACC_2COL_G") EXPECT_EQ(fmt, "TIME_ACC_2COL");
    else if (f[5] == "AT2_4LINE_PEKNOLD") EXPECT_EQ(fmt, "AT2_4LINE");
    else EXPECT_EQ(fmt, f[5]);
    ++n;
  }
  EXPECT_EQ(n, 85);
  std::printf("85 records parsed; worst PGA disagreement with MANIFEST %.3g %%\n", 100 * worst);
}

TEST(RecordsFormats, Ngaw2HeaderCrlfAndMetadata) {
  std::string t = "PEER NGA STRONG MOTION DATABASE RECORD\r\nDuzce Turkey, 11/12/1999, Lamont 362, E\r\n"
                  "ACCELERATION TIME SERIES IN UNITS OF G\r\n"
                  "NPTS=      7, DT=   .0100 SEC,  -5 POLE @      .03000 HZ\r\n"
                  "  -.2415593E-03  .1E+00  -.5E-01  .0  .1  \r\n  .2  -.3   \r\n\r\n";
  Record r = parse_record(t, "x.AT2");
  ASSERT_EQ(r.acc.size(), 7u);
  EXPECT_DOUBLE_EQ(r.dt, 0.01);
  EXPECT_DOUBLE_EQ(r.acc[0], -0.2415593e-3 * g_accel);
  EXPECT_DOUBLE_EQ(r.acc[6], -0.3 * g_accel);
  EXPECT_EQ(r.meta["station"], "Lamont 362");
  EXPECT_EQ(r.meta["component"], "E");
  EXPECT_EQ(r.meta["format"], "PEER_AT2_NGAW2");
}

TEST(RecordsFormats, Ngaw1OldStyleNptsDtLine) {
  // Older PEER files put the numbers first: "  2000   .02000   NPTS, DT".
  std::string t = "PACIFIC ENGINEERING\nNORTHRIDGE 01/17/94 1231, ARLETA, 360\n"
                  "ACCELERATION TIME HISTORY IN UNITS OF G\n   4   .02000   NPTS, DT\n .1E-02 -.2D-02 +.3e-2 4.E-03\n";
  Record r = parse_record(t, "x.AT2");
  ASSERT_EQ(r.acc.size(), 4u);
  EXPECT_DOUBLE_EQ(r.dt, 0.02);
  EXPECT_DOUBLE_EQ(r.acc[1], -0.002 * g_accel);
  EXPECT_DOUBLE_EQ(r.acc[3], 0.004 * g_accel);
  EXPECT_EQ(r.meta["format"], "PEER_AT2_NGAW1");
}

TEST(RecordsFormats, HeaderUnitsCmS2) {
  std::string t = "A\nB\nACCELERATION IN CM/S/S\nNPTS= 2, DT= 0.01\n 981.0 -9.80665\n";
  Record r = parse_record(t, "x.AT2");
  EXPECT_DOUBLE_EQ(r.acc[0], 9.81);
  EXPECT_DOUBLE_EQ(r.acc[1], -0.0980665);
  ReadOptions o;
  o.header_units = false;  // trust the caller instead: g
  Record r2 = parse_record(t, "x.AT2", o);
  EXPECT_DOUBLE_EQ(r2.acc[0], 981.0 * g_accel);
  // a station named like a unit on line 2 does not change the units; line 3 decides
  Record r3 = parse_record("A\nGalway, 1/1/2000, GAL 1, 0\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 1, DT= .01\n 0.5\n", "y.AT2");
  EXPECT_DOUBLE_EQ(r3.acc[0], 0.5 * g_accel);
  EXPECT_EQ(r3.meta["units"], "g");
}

TEST(RecordsFormats, TwoColumnAndOneColumn) {
  Record r = parse_record("# time acc\n0.0 0.0\r\n0.005, 0.1\n0.010\t-0.2  \n0.015 0.05\n", "a.txt");
  EXPECT_EQ(r.meta["format"], "TIME_ACC_2COL");
  ASSERT_EQ(r.acc.size(), 4u);
  EXPECT_NEAR(r.dt, 0.005, 1e-15);
  EXPECT_DOUBLE_EQ(r.acc[2], -0.2 * g_accel);
  Record h = parse_record("time acc\n0 0\n0.01 1\n", "h.csv");  // a header row of names is allowed
  EXPECT_EQ(h.acc.size(), 2u);
  ReadOptions o;
  o.dt = 0.02;
  o.units = AccUnits::cm_s2;
  Record c = parse_record("1.0\n-2.0\n3 4\n", "b.txt", o);
  EXPECT_EQ(c.meta["format"], "ONE_COLUMN");
  ASSERT_EQ(c.acc.size(), 4u);
  EXPECT_DOUBLE_EQ(c.acc[3], 0.04);
  EXPECT_DOUBLE_EQ(c.dt, 0.02);
}

TEST(RecordsErrors, NptsDisagreesWithValues) {
  expect_error(std::string(at2_header) + "NPTS= 5, DT= .01 SEC\n .1 .2 .3\n .4\n", 4,
               "NPTS = 5 but 4 values found (data end at line 6)");
  // more values than NPTS: the NPTS line, both numbers and where the surplus starts (issue 10.4)
  expect_error(std::string(at2_header) + "NPTS= 2, DT= .01 SEC\n .1 .2\n .3\n", 4,
               "more values than NPTS: NPTS = 2 on line 4 but the file holds 3 values (the first extra one on line 6)");
}

TEST(RecordsErrors, NonNumericToken) {
  expect_error(std::string(at2_header) + "NPTS= 3, DT= .01 SEC\n .1 .2\n .3x\n", 6, "'.3x' is not a number");
  expect_error("0 0\n0.01 1\n0.02 abc\n", 3, "'abc' is not a number");
}

TEST(RecordsErrors, MissingOrNonPositiveDt) {
  expect_error(std::string(at2_header) + "NPTS= 3\n .1 .2 .3\n", 4, "DT missing");
  expect_error(std::string(at2_header) + "NPTS= 3, DT= 0.0 SEC\n .1 .2 .3\n", 4, "DT = 0 is not positive");
  expect_error(std::string(at2_header) + "NPTS= 3, DT= -.01 SEC\n .1 .2 .3\n", 4, "not positive");
  expect_error(std::string(at2_header) + "NPTS= x, DT= .01\n .1\n", 4, "NPTS missing");
  expect_error("1\n2\n3\n", 0, "one-column record without a time step");
}

TEST(RecordsErrors, UnevenTimeColumn) {
  expect_error("0 0\n0.01 1\n0.02 2\n0.035 3\n0.04 4\n", 4, "uneven time column");
  expect_error("0 0\n0.01 1\n0.02 1 2\n", 3, "3 values on a row");
  expect_error("0.02 0\n0.01 1\n0.0 2\n", 3, "no positive time step");
}

TEST(RecordsErrors, EmptyFile) {
  expect_error("", 0, "empty record file");
  expect_error("  \r\n\n\t\n", 0, "empty record file");
  expect_error("# only a comment\n", 0, "no acceleration values");
  expect_error(std::string(at2_header) + "NPTS= 0, DT= .01\n", 4, "NPTS missing");
}

TEST(RecordsErrors, NonFiniteValues) {
  expect_error(std::string(at2_header) + "NPTS= 3, DT= .01\n .1 nan .3\n", 5, "non-finite value 'nan'");
  expect_error(std::string(at2_header) + "NPTS= 3, DT= .01\n .1 .2E+999 .3\n", 5, "non-finite value");
  expect_error("0 0\n0.01 inf\n", 2, "non-finite");
}

// Issue 10.4: a value that overflows when converted to m/s^2 is non-finite too, on its line.
TEST(RecordsErrors, ValueOverflowingInMetresPerSecondSquared) {
  expect_error(std::string(at2_header) + "NPTS= 3, DT= .01\n .1 .2\n 1e308\n", 6,
               "value '1e308' g overflows to infinity in m/s2");
  ReadOptions o;
  o.units = AccUnits::m_s2;
  EXPECT_NO_THROW(parse_record("0 0\n0.01 1e308\n", "big.txt", o));  // finite: the PGA bound's business
  o.units = AccUnits::g;
  expect_error("0 0\n0.01 1\n0.02 -1e308\n", 3, "value '-1e+308' g overflows", o);
}

// Issue 10.4: DT outside [1e-4, 0.1] s on its line with the range; NaN is "not a number", not "missing".
TEST(RecordsErrors, DtOutsideItsRangeOrNotANumber) {
  const std::string v = "\n .1 .2 .3\n";
  expect_error(std::string(at2_header) + "NPTS= 3, DT= 1e308 SEC" + v, 4, "DT = 1e+308 s is outside [0.0001, 0.1] s");
  expect_error(std::string(at2_header) + "NPTS= 3, DT= 1e-300 SEC" + v, 4, "DT = 1e-300 s is outside [0.0001, 0.1] s");
  expect_error(std::string(at2_header) + "NPTS= 3, DT= .2 SEC" + v, 4, "DT = 0.2 s is outside");
  expect_error(std::string(at2_header) + "NPTS= 3, DT= NaN SEC" + v, 4, "DT = 'NaN' is not a number");
  expect_error(std::string(at2_header) + "NPTS= 3, DT= 1e999 SEC" + v, 4, "DT = '1e999' is not a finite number");
  expect_error(std::string(at2_header) + "   3   nan   NPTS, DT" + v, 4, "DT = 'nan' is not a number");
  EXPECT_NO_THROW(parse_record(std::string(at2_header) + "NPTS= 3, DT= .0001 SEC" + v, "ok.AT2"));
  EXPECT_NO_THROW(parse_record(std::string(at2_header) + "NPTS= 3, DT= 0.1 SEC" + v, "ok.AT2"));
  expect_error("0 0\n0.5 1\n1.0 2\n", 3, "the time column's step (0 to 1 s in 2 steps) = 0.5 s is outside");
  ReadOptions o;
  o.dt = 1.0;
  expect_error("1\n2\n", 0, "the time step given for this one-column record = 1 s is outside", o);
}

// Issue 10.5: file text in a message is a short escaped excerpt, never raw bytes.
TEST(RecordsErrors, BinaryGarbageIsEscaped) {
  std::string garbage = std::string(at2_header) + "NPTS= 3, DT= .01\n .1 ";
  garbage += std::string("\x01\xff\x1b[2J\0", 7) + std::string(60, 'z') + "\n";  // with a NUL byte
  try {
    parse_record(garbage, "bad.AT2");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "bad.AT2:5");
    EXPECT_EQ(e.what_part(), "'\\x01\\xFF\\x1B[2J\\x00" + std::string(33, 'z') + "...' is not a number");
  }
  EXPECT_EQ(escaped_excerpt("ab\tc\x7f\xc3\xa9"), "ab\\x09c\\x7F\\xC3\\xA9");
  EXPECT_EQ(escaped_excerpt(std::string(50, 'a'), 40), std::string(40, 'a') + "...");
}

// Issue 10.5: one wording for every unknown key.
TEST(RecordsErrors, UnknownKeyWording) {
  const InputError e = unknown_key_error("colour", "[records]", "s.toml:3 [records].colour", "suite, files");
  EXPECT_STREQ(e.what(), "unknown key 'colour' in [records], s.toml:3 [records].colour, check the spelling; "
                         "[records] takes: suite, files");
  EXPECT_EQ(unknown_key_error("--x", "pounding run", "command line", "--out", "option").what_part(),
            "unknown option '--x' in pounding run");
}

// Issue 10.4: what an analysis refuses -- PGA above 5 g after units and scale (the peak's line and the likely
// cause), records shorter than 2 s -- and what it accepts.
TEST(RecordsAnalysis, PgaBoundNamesThePeakLineAndTheCause) {
  // 4 s at 0.01 s; 0.3 g written in cm/s^2 (294), the peak (490.3 cm/s^2 = 0.5 g) on line 45
  std::string t = "PEER NGA STRONG MOTION DATABASE RECORD\nX, 1/1/2000, Y, 0\nACCELERATION TIME SERIES\nNPTS= 401, DT= .01\n";
  for (int i = 0; i < 401; ++i)
    t += (i == 203 ? std::string(" 490.3") : fmt_value(294.2 * std::sin(0.1 * i))) + (i % 5 == 4 ? "\n" : "");
  t += "\n";
  const Record as_g = parse_record(t, "cms2.AT2");
  EXPECT_EQ(as_g.peak_line, 45);
  const AnalysisContext study{1.0, "[records] scale", "set [records] units = \"cm/s2\""};
  auto problem = analysis_problem(as_g, study);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->where(), "cms2.AT2:45");
  EXPECT_EQ(problem->what_part(), "PGA 490.3 g is above the 5 g of any real ground motion");
  EXPECT_EQ(problem->fix(), "is the file in cm/s2 (its values in g read as cm/s2 give a PGA of 0.5 g)? "
                            "set [records] units = \"cm/s2\"");
  EXPECT_THROW(require_analysable(as_g, study), InputError);
  ReadOptions o;
  o.units = AccUnits::cm_s2;
  const Record right = parse_record(t, "cms2.AT2", o);
  EXPECT_FALSE(analysis_problem(right, study));
  EXPECT_NO_THROW(require_analysable(right, study));
  // a normal record times 1000: the scale is named, not the units
  Record scaled = right;
  for (double& a : scaled.acc) a *= 1000.0;
  problem = analysis_problem(scaled, {1000.0, "[records] scale", "set [records] units = \"cm/s2\""});
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->what_part(), "PGA 500 g is above the 5 g of any real ground motion (0.5 g in the file, times scale 1000)");
  EXPECT_NE(problem->fix().find("[records] scale = 1000 is too large"), std::string::npos) << problem->fix();
  // the header says g: changing [records] units would not help, so the message says so
  std::string g_header = t;
  g_header.replace(g_header.find("ACCELERATION TIME SERIES"), 24, "ACCELERATION TIME SERIES IN UNITS OF G");
  problem = analysis_problem(parse_record(g_header, "g.AT2", o), study);
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->fix().find("header line 3 says its values are in g"), std::string::npos) << problem->fix();
}

TEST(RecordsAnalysis, ShorterThanTwoSecondsIsRefused) {
  const Record one = parse_record(std::string(at2_header) + "NPTS= 1, DT= .01\n 0.5\n", "one.AT2");
  auto problem = analysis_problem(one, {});
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->where(), "one.AT2");
  EXPECT_NE(problem->what_part().find("less than the 2 s"), std::string::npos) << problem->what();
  Record two;
  two.source = "two";
  two.dt = 0.01;
  two.acc.assign(201, 0.1);  // exactly 2 s
  EXPECT_FALSE(analysis_problem(two, {}));
  two.acc.pop_back();
  EXPECT_TRUE(analysis_problem(two, {}));
}

// Every real record passes the readers' and the analysis' limits (issue 10.4: nothing real is refused).
TEST(RecordsAnalysis, EveryRealRecordIsAnalysable) {
  POUNDING_REQUIRE_REAL_RECORDS();
  int n = 0;
  for (const auto& e : fs::directory_iterator(real_dir)) {
    const std::string ext = e.path().extension().string();
    if (ext != ".AT2" && ext != ".txt") continue;
    const Record r = read_record(e.path().string());
    EXPECT_FALSE(analysis_problem(r, {})) << analysis_problem(r, {})->what();
    ++n;
  }
  EXPECT_EQ(n, 85);
}

TEST(RecordsErrors, MissingFileNamesThePath) {
  try {
    read_record("/nonexistent/record.AT2");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "/nonexistent/record.AT2");
  }
}

TEST(RecordsWriter, At2RoundTripIsWithinPrintedPrecision) {
  Record r;
  r.name = "rt";
  r.dt = 0.005;
  for (int i = 0; i < 23; ++i) r.acc.push_back(std::sin(0.3 * i) * 3.7 - 0.01 * i);
  const std::string path = (fs::temp_directory_path() / "pounding_test_rt.AT2").string();
  write_at2(r, path);
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  Record b = read_record(path);
  fs::remove(path);
  ASSERT_EQ(b.acc.size(), r.acc.size());
  EXPECT_DOUBLE_EQ(b.dt, 0.005);
  EXPECT_EQ(b.meta["format"], "PEER_AT2_NGAW2");
  for (std::size_t i = 0; i < r.acc.size(); ++i) EXPECT_NEAR(b.acc[i], r.acc[i], 1e-7 * 3.7 + 1e-12);
}

// The AT2 writer formats with fmt; its bytes must stay those of the printf writer it replaced ("%8zu",
// "%12.6f", "%15.7E"): the file written is compared with a printf rendering of the same record, on values
// across the whole double range, rounding ties, subnormals, signed zeros and record steps of every magnitude.
std::string printf_at2(const Record& r) {
  std::string l2 = r.name;
  if (auto it = r.meta.find("description"); it != r.meta.end()) l2 += ", " + it->second;
  std::string text = "PEER NGA STRONG MOTION DATABASE RECORD (format); written by pounding\n" + l2 +
                     "\nACCELERATION TIME SERIES IN UNITS OF G\n";
  char buf[64];
  std::snprintf(buf, sizeof buf, "NPTS=%8zu, DT=%12.6f SEC\n", r.acc.size(), r.dt);
  text += buf;
  for (std::size_t i = 0; i < r.acc.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%15.7E", r.acc[i] / g_accel);
    text += buf;
    if (i % 5 == 4 || i + 1 == r.acc.size()) text += '\n';
  }
  return text;
}

TEST(RecordsWriter, At2BytesAreThoseOfThePrintfWriter) {
  Record r;
  r.name = "bytes";
  r.meta["description"] = "fmt vs printf";
  std::uint64_t x = 0x9E3779B97F4A7C15ull;  // xorshift: doubles of every exponent and mantissa
  for (int i = 0; i < 200000; ++i) {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    double v;
    std::uint64_t bits = x;
    std::memcpy(&v, &bits, sizeof v);
    if (std::isfinite(v)) r.acc.push_back(v);
    r.acc.push_back(std::ldexp(static_cast<double>(x >> 11) / 9007199254740992.0 - 0.5, static_cast<int>(x % 40) - 20));
  }
  for (double v : {0.0, -0.0, 1.0, -1.0, 5e-324, -5e-324, 2.2250738585072014e-308, 1.7976931348623157e308,
                   1.25e-8, 1.00000005, 9.99999995, 0.123456785, 1e-100, 123456785.0,
                   std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                   std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::quiet_NaN()})
    r.acc.push_back(v * g_accel);
  for (int k = 0; k < 1000; ++k) r.acc.push_back((1.0 + (k + 0.5) * 1e-7) * g_accel);  // ties at the 8th digit
  // (dt up to 1e30: the printf writer's 64-byte buffer cut longer header lines, which no real dt reaches)
  for (double dt : {0.005, 0.01, 1e-7, 0.0000005, 123456.7890125, 3.0000005, 1e23, 1e30,
                    std::numeric_limits<double>::infinity()}) {
    r.dt = dt;
    const std::string path = (fs::temp_directory_path() / "pounding_test_bytes.AT2").string();
    write_at2(r, path);
    std::ifstream in(path, std::ios::binary);
    const std::string written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    fs::remove(path);
    const std::string expected = printf_at2(r);
    EXPECT_EQ(written.size(), expected.size()) << "dt " << dt;
    std::size_t at = 0;
    while (at < written.size() && at < expected.size() && written[at] == expected[at]) ++at;
    EXPECT_EQ(at, written.size()) << "dt " << dt << ": the AT2 bytes differ from printf's at byte " << at << ": '"
                                  << written.substr(at < 40 ? 0 : at - 40, 80) << "' vs '"
                                  << expected.substr(at < 40 ? 0 : at - 40, 80) << "'";
  }
}

TEST(RecordsMeasures, ClosedFormsForASine) {
  // a(t) = A sin(2 pi t / T) over whole periods, finely sampled (linear between samples, error O(h^2)):
  // v = A T/(2 pi) (1 - cos) -> PGV = A T / pi; Ia = pi/(2g) A^2 D / 2; the Husid curve of sin^2 over
  // many periods is ~linear, so t05 ~ 0.05 D, t95 ~ 0.95 D.
  const double A = 2.0, T = 0.5, D = 20.0, h = 1e-4;
  Record r;
  r.dt = h;
  const auto n = static_cast<std::size_t>(std::lround(D / h)) + 1;
  for (std::size_t k = 0; k < n; ++k) r.acc.push_back(A * std::sin(2 * std::numbers::pi * k * h / T));
  const Measures m = measure(r);
  EXPECT_NEAR(m.pga, A, 1e-6);
  EXPECT_NEAR(m.pgv, A * T / std::numbers::pi, 1e-6);
  // u(t) = A T/(2pi) t - A (T/2pi)^2 sin(...): the peak is at the end, A T D/(2 pi)
  EXPECT_NEAR(m.pgd, A * T * D / (2 * std::numbers::pi), 1e-5);
  // linear interpolation of a sine underestimates int a^2 by ~(omega h)^2/12 = 1.3e-7 relative
  EXPECT_NEAR(m.arias / (std::numbers::pi / (2 * g_accel) * A * A * D / 2), 1.0, 1e-6);
  EXPECT_NEAR(m.t05, 0.05 * D, T / 2);
  EXPECT_NEAR(m.t95, 0.95 * D, T / 2);
  EXPECT_NEAR(m.d5_95(), 0.9 * D, T / 2);
}

TEST(RecordsMeasures, AriasExactForPiecewiseLinear) {
  // Two samples a0, a1: int_0^h (a0 + (a1-a0) t/h)^2 dt = h (a0^2 + a0 a1 + a1^2)/3 exactly.
  Record r;
  r.dt = 0.2;
  r.acc = {1.0, 3.0};
  EXPECT_NEAR(measure(r).arias, std::numbers::pi / (2 * g_accel) * 0.2 * 13.0 / 3.0, 1e-15);
}
