#pragma once
// ASCE 7-16 design spectrum from the mapped MCER accelerations (issue 23 item 6): Ss, S1 (g, the risk-targeted
// maximum considered earthquake spectral accelerations at 0.2 s and 1 s, site class B/C boundary, ch. 22) and
// the site class give
//   SMS = Fa Ss, SM1 = Fv S1 (eqs. 11.4-1, 11.4-2),   SDS = 2/3 SMS, SD1 = 2/3 SM1 (eqs. 11.4-3, 11.4-4),
// with Fa from Table 11.4-1 (Ss <= 0.25, 0.5, 0.75, 1.0, 1.25, >= 1.5) and Fv from Table 11.4-2 as amended by
// Supplement 1 (S1 <= 0.1, 0.2, 0.3, 0.4, 0.5, >= 0.6), straight-line interpolation between the columns and
// the end values held beyond them (the tables' notes). Values: /work/shared/research/fragility-and-codes.md 3.1.
//
// Refused (InputError, with the clause and what to do instead), never silently computed:
//   - site class F: §11.4.8 / §20.3.1 require a site response analysis (ch. 21);
//   - §11.4.8 site-specific ground-motion procedures: site class E with Ss >= 1.0, site classes D and E with
//     S1 >= 0.2 (the tables' values there are given "for TS only"). The standard's exceptions (E with Ss >= 1:
//     Fa of site class C; D with S1 >= 0.2: Cs by eq. 12.8-2 up to 1.5 TS and 1.5 x eqs. 12.8-3/4 beyond, ELF
//     only; E with S1 >= 0.2: T <= TS and ELF only) change the design procedure, not just a coefficient, so
//     the engineer applies them and gives SDS and SD1 directly; the message says so.
//   - site class E with 0.75 < Ss < 1.0: Table 11.4-1 has no value at Ss = 1.0 ("see §11.4.8") to interpolate
//     toward.
// Site class "D-default" is §11.4.3's default site class D (soil properties not known in enough detail):
// Fa = max(Fa of D, 1.2) per §11.4.4.
#include <string>
#include <string_view>

#include "pounding/motion/design_spectrum.hpp"

namespace pounding {

enum class Asce7SiteClass { A, B, C, D, D_default, E, F };
// "A".."F" or "D-default" (case as written); throws InputError naming `where` otherwise.
Asce7SiteClass parse_asce7_site_class(std::string_view name, const std::string& where);
std::string_view to_string(Asce7SiteClass c);

struct Asce7MapValues {
  double ss = 0;  // g, mapped MCER Sa at 0.2 s, (0, 5]
  double s1 = 0;  // g, mapped MCER Sa at 1 s, (0, 3]
  Asce7SiteClass site = Asce7SiteClass::D;
  double tl = 8;  // s, long-period transition period (Figs. 22-14 to 22-17)
};

struct Asce7SiteCoefficients {
  double fa = 0, fv = 0, sms = 0, sm1 = 0, sds = 0, sd1 = 0;
  // Site class D with S1 >= 0.2 taken by 11.4.8 exception 2 (asked for with `exception_2`): Fv is Table 11.4-2's
  // value "for TS only", and the ELF's Cs is eq. 12.8-2 up to T = 1.5 TS and 1.5 x eqs. 12.8-3/4 beyond.
  bool exception_2 = false;
};

// Fa and Fv and the spectral values; InputError (where: "Ss", "S1" or "site class") for the refused cases above
// and for Ss, S1 outside their ranges.
// exception_2: site class D (and D-default) with S1 >= 0.2 is designed by 11.4.8 exception 2 (ELF only) instead of
// being refused.
Asce7SiteCoefficients asce7_site_coefficients(const Asce7MapValues& m, bool exception_2 = false);
// The design spectrum of those values (SDS, SD1, TL), validated.
Asce7Spectrum asce7_from_maps(const Asce7MapValues& m);
// "Ss = 1.5 g, S1 = 0.6 g, site class C: Fa = 1.2, Fv = 1.4 (Tables 11.4-1/11.4-2), SMS = .., SM1 = .."
std::string describe(const Asce7MapValues& m);

}  // namespace pounding
