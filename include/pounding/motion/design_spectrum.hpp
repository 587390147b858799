#pragma once
// Code design spectra (issue 14 groundwork): the target spectra that records are scaled to. Every
// spectrum gives the 5 %-damped (EC8: xi-damped) elastic pseudo-spectral acceleration Sa in g at a period
// T in s. Formulas and tables: /work/shared/research/fragility-and-codes.md section 3.
//   ASCE 7-16 §11.4.6 design spectrum from SDS, SD1 (g) and TL (s): T0 = 0.2 SD1/SDS, TS = SD1/SDS,
//     T < T0: SDS (0.4 + 0.6 T/T0);  T0 <= T <= TS: SDS;  TS < T <= TL: SD1/T;  T > TL: SD1 TL/T^2.
//   EN 1998-1 §3.2.2.2 horizontal elastic spectrum (eqs. 3.2-3.5), type 1 or 2, ground A-E (tables
//     3.2/3.3), ag = gammaI agR, eta = sqrt(10/(5 + xi%)) >= 0.55 (eq. 3.6):
//     T <= TB: ag S (1 + T/TB (2.5 eta - 1));  TB..TC: 2.5 ag S eta;  TC..TD: 2.5 ag S eta TC/T;
//     T >= TD: 2.5 ag S eta TC TD/T^2 (the code stops at 4 s; the last branch is continued beyond it).
//   Iranian Standard 2800, 4th edition: Sa = A B I with B = B1 N,
//     B1 = S0 + (S - S0 + 1) T/T0 (T < T0), S + 1 (T0 <= T < Ts), (S + 1) Ts/T (T >= Ts);
//     N = 1 (T < Ts), 1 + k (T - Ts)/(4 - Ts) (Ts <= T < 4), 1 + k (T >= 4), k = 0.7 for A >= 0.30, 0.4 for
//     A <= 0.25. VERIFY: the soil table (T0, Ts, S, S0) and the N factor come from secondary sources, not from
//     the standard's own text: ebrahimraeyat/civilTools (building/soil.py, spectral.py), and, checked on
//     2026-11-25, a second, independent implementation (a Persian-language building calculator's soilCoef and
//     N factor, found through the code index) that agrees in every value, the A >= 0.30 / A <= 0.25 split too.
//   NZS 1170.5:2004 (Structural design actions, Part 5: Earthquake actions -- New Zealand) clause 3.1.1:
//     C(T) = Ch(T) Z R N(T, D); Ch(T) of table 3.1 / eqs C3.1 of the commentary, the column for the modal
//     response spectrum and numerical integration time-history methods (Ch(0) = 1.0, 1.33, 1.12 for classes
//     A/B, C, D/E). Site class A and B (rock) share one shape:
//       A/B: T < 0.1: 1.0 + 1.35 T/0.1; 0.1-0.3: 2.35; 0.3-1.5: 1.6 (0.5/T)^0.75; 1.5-3: 1.05/T; > 3: 3.15/T^2
//       C:   T < 0.1: 1.33 + 1.60 T/0.1; 0.1-0.3: 2.93; 0.3-1.5: 2.0 (0.5/T)^0.75; 1.5-3: 1.32/T; > 3: 3.96/T^2
//       D:   T < 0.1: 1.12 + 1.88 T/0.1; 0.1-0.56: 3.0; 0.56-1.5: 2.4 (0.75/T)^0.75; 1.5-3: 2.14/T; > 3: 6.42/T^2
//       E:   T < 0.1: 1.12 + 1.88 T/0.1; 0.1-1.0: 3.0; 1.0-1.5: 3.0/T^0.75; 1.5-3: 3.32/T; > 3: 9.96/T^2
//     (the branches meet within 0.4 % at every corner). Z: hazard factor (table 3.3, 0.13 Auckland ... 0.6),
//     R: return period factor (table 3.5, 0.2 ... 1.8), N(T, D) = 1: sites more than 20 km from the faults of
//     table 3.6 (the near-fault factor is not modelled). Cross-checked on 2026-11-26 against an independent
//     public implementation (Agent6-6-6/NZS1170.5-Seismic-Coefficient-functions, Loading_C_h_T, RSM case).
//   Tabulated: the user's (T, Sa) points, linear in T between them; outside the table is an error.
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace pounding {

// ---- ASCE 7-16 ----
struct Asce7Spectrum {
  double sds = 0;  // g, design short-period spectral acceleration, (0, 5]
  double sd1 = 0;  // g, design 1-s spectral acceleration, (0, 5]
  double tl = 8;   // s, long-period transition period, [1, 20] and > TS
};
double asce7_t0(const Asce7Spectrum& s);  // 0.2 SD1/SDS
double asce7_ts(const Asce7Spectrum& s);  // SD1/SDS
double sa(const Asce7Spectrum& s, double period);

// ---- Eurocode 8 ----
enum class Ec8Type { type1, type2 };  // type 2 where the dominating surface-wave magnitude Ms <= 5.5
enum class Ec8Ground { A, B, C, D, E };
struct Ec8GroundParams {
  double s, tb, tc, td;  // soil factor; corner periods in s (EN 1998-1 tables 3.2 and 3.3)
};
Ec8GroundParams ec8_ground_params(Ec8Type type, Ec8Ground ground);
// Damping correction eta = sqrt(10/(5 + xi)), xi in percent, never below 0.55. Throws InputError for
// xi outside [0, 50] %.
double ec8_eta(double damping_percent);
struct Ec8Spectrum {
  Ec8Type type = Ec8Type::type1;
  Ec8Ground ground = Ec8Ground::A;
  double agr = 0;               // g, reference peak ground acceleration on ground A, (0, 2]
  double importance = 1.0;      // gammaI, [0.8, 1.4]; ag = gammaI agR
  double damping_percent = 5;   // xi, [0, 50] %
};
double sa(const Ec8Spectrum& s, double period);

// ---- Iranian Standard 2800, 4th edition (VERIFY, see above) ----
enum class Iran2800Soil { I, II, III, IV };
struct Iran2800SoilParams {
  double t0, ts, s, s0;  // s, s, -, -
};
// A selects the column: A >= 0.30 (very high, high hazard) or A <= 0.25 (moderate, low).
Iran2800SoilParams iran2800_soil_params(Iran2800Soil soil, double a);
struct Iran2800Spectrum {
  double a = 0.35;  // design base acceleration ratio: 0.35, 0.30, 0.25 or 0.20
  Iran2800Soil soil = Iran2800Soil::II;
  double importance = 1.0;  // I, [0.8, 1.4]
};
double iran2800_b(const Iran2800Spectrum& s, double period);  // B = B1 N
double sa(const Iran2800Spectrum& s, double period);          // A B I

// ---- NZS 1170.5:2004 ----
enum class Nzs1170Site { A, B, C, D, E };
struct Nzs1170Spectrum {
  Nzs1170Site site = Nzs1170Site::C;
  double z = 0.4;  // hazard factor Z, [0.1, 0.6]
  double r = 1.0;  // return period factor R (Ru, Rs), [0.2, 1.8]
};
double nzs1170_ch(Nzs1170Site site, double period);  // spectral shape factor Ch(T)
double sa(const Nzs1170Spectrum& s, double period);   // Ch(T) Z R, N = 1
// "A".."E" (upper or lower case) -> the class; nullopt otherwise.
std::optional<Nzs1170Site> parse_nzs1170_site(std::string_view text);
std::string_view to_string(Nzs1170Site site);

// ---- Tabulated ----
struct TabulatedSpectrum {
  std::vector<double> periods;  // s, >= 0, strictly increasing, at least 2
  std::vector<double> sa;       // g, >= 0
  std::string source = "tabulated spectrum";  // file name (or a label) for messages and describe()
};
double sa(const TabulatedSpectrum& s, double period);
// Reads "period,sa" lines (s, g). Blank lines and lines starting with '#' are skipped; the first other
// line may be a header (its first field not a number). Throws InputError with file:line for a bad
// number, a wrong field count, a non-increasing period or a negative Sa, and naming the file when it
// holds fewer than 2 points or cannot be read.
TabulatedSpectrum read_tabulated_spectrum(const std::string& path);

// Each validate() throws InputError naming the parameter and its allowed range.
void validate(const Asce7Spectrum& s);
void validate(const Ec8Spectrum& s);
void validate(const Iran2800Spectrum& s);
void validate(const Nzs1170Spectrum& s);
void validate(const TabulatedSpectrum& s);

// ---- Any of the above ----
class DesignSpectrum {
 public:
  using Params = std::variant<Asce7Spectrum, Ec8Spectrum, Iran2800Spectrum, TabulatedSpectrum, Nzs1170Spectrum>;
  // Validates the parameters (InputError otherwise).
  explicit DesignSpectrum(Params params);
  // Sa in g at T in s; throws InputError for a negative or non-finite T (or, tabulated, outside the table).
  double sa(double period) const;
  // One line naming the code and every parameter, e.g. "ASCE 7-16 11.4.6: SDS = 1.2 g, SD1 = 0.56 g, TL = 8 s".
  std::string describe() const;
  const Params& params() const { return params_; }

 private:
  Params params_;
};

}  // namespace pounding
