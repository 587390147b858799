#pragma once
// Muthukumar & DesRoches (2006), parameter study of the elastic 2-DOF model (muthukumar-desroches-2006-
// hertzdamp.txt): stereomechanical, Kelvin and Hertzdamp at e = 1 and 0.6, T1/T2 = 0.3, 0.5, 0.7, records in
// three PGA bands, mean amplification of the stiff system's peaks. A qualitative consistency check (the stored
// paper lacks T2 and the Kelvin stiffness); docs/validation.md and tools/muthukumar_sensitivity.sh.
#include <string>
#include <vector>

namespace pounding::accuracy {

struct MuthukumarRow {
  std::string level;  // low, moderate, high
  double period_ratio = 0;
  std::string model;  // stereomechanical, kelvin, hertzdamp (e = 1: linear / hertz)
  double e = 0;
  int records = 0;
  double disp_amp = 0, acc_amp = 0;  // mean over records
  int diverged = 0;
};

struct MuthukumarOptions {
  double T2 = 1.0;            // flexible system period (s), T1 = 0.3, 0.5, 0.7 T2 (ASSUMED)
  double kelvin_k = 0.0;      // N/m; 0: 25,000 kip/in = 4.378e9 N/m (ASSUMED: the paper's digits are lost)
  double kelvin_scale = 1.0;  // multiplies the Kelvin/linear stiffness (sensitivity sweep)
  int substeps = 0;           // 0: h <= 0.5 ms
  std::string records = "all";      // all: every record of the directory in a band; matched: muthukumar_table_i()
  std::vector<std::string> levels;  // empty: low, moderate, high
  std::vector<double> ratios;       // empty: 0.3, 0.5, 0.7 (each must be one of them)
};

// The paper's Table I (27 records; stations and events readable, components and most PGAs lost in the
// stored text) against the records of ../shared/records/real.
struct TableIRecord {
  std::string level;    // the paper's PGA level of the record
  std::string event;    // as printed
  std::string station;  // as printed
  std::vector<std::string> files;  // our files of the same event and station, in the paper's band; empty: none
  std::string note;                // why not matched, or which component choice was made
};
std::vector<TableIRecord> muthukumar_table_i();

// Bad options (unknown level, ratio or record set, non-positive T2/stiffness) are InputErrors naming the option.
std::vector<MuthukumarRow> muthukumar(const std::string& record_dir, const MuthukumarOptions& opt,
                                      std::vector<std::string>* log = nullptr);

}  // namespace pounding::accuracy
