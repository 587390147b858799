#pragma once
// Ground-motion records: one Record type, the readers for the formats earthquake engineers use, an AT2
// writer, and the intensity measures `pounding records show` prints.
//
// Formats read (detected from the content, never from the file name):
//   PEER_AT2_NGAW2     4 header lines, line 4 `NPTS=  7992, DT= .0050 SEC, ...`, values in g
//   PEER_AT2_NGAW1     older 4-line header, line 4 `NPTS= 2000, DT= .02000 SEC` or `2000 .02000 NPTS, DT`,
//                      values like `.123E-02`
//   AT2_4LINE          the textbook 4-line El Centro variant (`NPTS=1559, DT=.02`, fixed-point values)
//   TIME_ACC_2COL      two columns: time (s, uniform step) and acceleration
//   ONE_COLUMN         one value per line (or several per line, Fortran style); dt from the caller
// CRLF/CR line ends and trailing blanks are tolerated; `#`, `%` and `!` start a comment line in the text
// formats; `,` and `;` separate values like blanks. Units: g unless stated (ReadOptions::units, or the AT2
// header's "UNITS OF G" / "CM/S/S" when ReadOptions::header_units).
//
// What the readers refuse (InputError naming file:line and the fix), whatever the record is used for:
//   - a value that is not a finite number, or that overflows when converted to m/s^2 (1e308 g);
//   - a time step outside [record_dt_min, record_dt_max] (AT2 DT, the two-column time step, the one-column
//     dt), and a DT that is not a number ("DT= NaN" is "not a number", not "missing");
//   - an AT2 whose NPTS differs from the number of values it holds, either way (the message names the
//     NPTS line and both numbers). Every PEER file we know holds exactly NPTS values (the 85 real records
//     in ../shared/records/real all do), so no slack is allowed: a mismatch means a truncated or edited file.
// What an ANALYSIS refuses on top (require_analysable: `pounding run`, `simulate`): a record shorter than
// record_duration_min, and a PGA above record_pga_max_g after units and scale -- the signature of a file in
// cm/s^2 read as g, or of a wrong scale. `records show` and `records spectrum` still display such a record
// (they are how one inspects it) but print the same message as a WARNING on stderr.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pounding/core/enum_names.hpp"
#include "pounding/core/error.hpp"

namespace pounding {

inline constexpr double g_accel = 9.80665;  // m/s^2 per g

// Limits of a ground-motion record (see the header comment). Recorded accelerograms are sampled at
// 0.001-0.05 s; the largest PGAs ever recorded are about 4 g, so 5 g is beyond any real motion.
inline constexpr double record_dt_min = 1e-4, record_dt_max = 0.1;  // s
inline constexpr double record_pga_max_g = 5.0;                     // g, after units and scale
inline constexpr double record_duration_min = 2.0;                  // s, (npts - 1) dt

enum class AccUnits { g, m_s2, cm_s2 };
inline constexpr EnumName<AccUnits> acc_units_names[] = {
    {AccUnits::g, "g"}, {AccUnits::m_s2, "m/s2"}, {AccUnits::cm_s2, "cm/s2"}};
constexpr const auto& enum_names(AccUnits) { return acc_units_names; }  // to_string(AccUnits), enum_names.hpp
AccUnits parse_units(const std::string& name);  // "g", "m/s2", "cm/s2"; InputError otherwise
double to_m_s2(AccUnits u);                     // factor from the unit to m/s^2

struct Record {
  std::string name;                          // file stem or generated name
  std::string source;                        // path, or "synthetic:..." for generated records
  double dt = 0.0;                           // s
  std::vector<double> acc;                   // m/s^2
  std::map<std::string, std::string> meta;   // format, event, station, units, units_from, ...
  int peak_line = 0;                         // line of the file holding the largest |value| (0: not from a file)
  double duration() const { return acc.empty() ? 0.0 : dt * static_cast<double>(acc.size() - 1); }
  double pga() const;                        // m/s^2
  bool synthetic() const { return source.rfind("synthetic:", 0) == 0; }
};

struct ReadOptions {
  AccUnits units = AccUnits::g;  // units of the values in the file
  double dt = 0.0;               // required for one-column files, ignored otherwise
  bool header_units = true;      // an AT2 header that names its units (G, CM/S/S, M/S/S) overrides `units`
};

// Reads PEER NGA-West2/West1 .AT2, the 4-line El Centro variant, two-column time/acc text, or one-column
// text (format detected from the content). Throws InputError naming file, line and what was expected.
Record read_record(const std::string& path, const ReadOptions& options = {});
// The same from text already in memory; `where` names it in errors (and becomes Record::source).
Record parse_record(std::string_view text, const std::string& where, const ReadOptions& options = {});

// Where the user sets what require_analysable's messages tell them to change.
struct AnalysisContext {
  double scale = 1.0;           // factor already applied to rec.acc (1: none)
  std::string scale_setting;    // e.g. "[records] scale"; empty when the user gives no scale
  std::string units_setting;    // e.g. "[records] units = \"cm/s2\"" or "--units cm/s2": how to say cm/s^2
};
// The first limit the record breaks as an analysis input (duration, PGA), or nothing. The error names the
// file and the line of the peak sample, the PGA found and the likely cause (units, scale).
std::optional<InputError> analysis_problem(const Record& rec, const AnalysisContext& context);
// Throws analysis_problem's error.
void require_analysable(const Record& rec, const AnalysisContext& context);

// Writes a PEER NGA-West2-style AT2 file (values in g, 5 per line, %15.7E) that read_record (and
// OpenSees' ReadRecord.tcl / PEER tools) read back. Written to a temporary name and renamed.
void write_at2(const Record& rec, const std::string& path);

// Intensity measures of a record. The acceleration is taken as linear between samples (the same
// assumption the kernel and the spectra make), so the integrals below are exact for that signal:
//   velocity     v_{k+1} = v_k + h (a_k + a_{k+1}) / 2
//   displacement u_{k+1} = u_k + h v_k + h^2 (a_k / 3 + a_{k+1} / 6)
//   Arias        Ia = pi / (2 g) * int a^2 dt,  int over a step = h (a_k^2 + a_k a_{k+1} + a_{k+1}^2) / 3
// No baseline correction is applied (PEER records are already corrected), so PGD of an uncorrected
// record includes its drift.
struct Measures {
  double pga = 0, pgv = 0, pgd = 0;  // m/s^2, m/s, m
  double arias = 0;                  // Ia, m/s
  double t05 = 0, t45 = 0, t95 = 0;  // s: times at 5, 45 and 95 % of Ia (t45 is R&DK's t_mid)
  double d5_95() const { return t95 - t05; }
  double arias_sg() const { return arias / g_accel; }  // Ia in s*g, the unit of Rezaeian & Der Kiureghian
};
Measures measure(const Record& rec);
// Normalised cumulative Arias intensity at each sample (0 ... 1); empty for a zero record.
std::vector<double> husid(const Record& rec);
// Time at which the normalised cumulative Arias intensity reaches `fraction` (linear within a step).
double husid_time(const std::vector<double>& husid, double dt, double fraction);

}  // namespace pounding
