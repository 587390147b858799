// ASCE 7-16 site coefficients and the design spectrum from mapped values: see asce7_site.hpp.
#include "pounding/motion/asce7_site.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "pounding/core/error.hpp"

namespace pounding {

namespace {

constexpr std::array<std::string_view, 7> site_names{"A", "B", "C", "D", "D-default", "E", "F"};

// Straight-line interpolation in a table row at columns x (held constant beyond the ends).
template <std::size_t N>
double interpolate(const std::array<double, N>& x, const std::array<double, N>& y, double v) {
  if (v <= x.front()) return y.front();
  if (v >= x.back()) return y.back();
  std::size_t k = 1;
  while (x[k] < v) ++k;
  return y[k - 1] + (v - x[k - 1]) / (x[k] - x[k - 1]) * (y[k] - y[k - 1]);
}

const char* const specific_fix =
    "run the site-specific ground-motion procedure of ASCE 7-16 ch. 21 and give SDS and SD1 directly (sds and sd1 "
    "in [target_spectrum], --sds and --sd1 for pounding spectrum)";

}  // namespace

Asce7SiteClass parse_asce7_site_class(std::string_view name, const std::string& where) {
  for (std::size_t i = 0; i < site_names.size(); ++i)
    if (name == site_names[i]) return static_cast<Asce7SiteClass>(i);
  throw InputError(fmt::format("site class '{}' is not an ASCE 7-16 site class", escaped_excerpt(name)), where,
                   "use \"A\", \"B\", \"C\", \"D\", \"D-default\" (11.4.3's default: Fa >= 1.2), \"E\" or \"F\"");
}

std::string_view to_string(Asce7SiteClass c) { return site_names.at(static_cast<std::size_t>(c)); }

Asce7SiteCoefficients asce7_site_coefficients(const Asce7MapValues& m, bool exception_2) {
  require_range(m.ss, 1e-6, 5.0, "Ss", "(0, 5] g (the mapped MCER Sa at 0.2 s)");
  require_range(m.s1, 1e-6, 3.0, "S1", "(0, 3] g (the mapped MCER Sa at 1 s)");
  using S = Asce7SiteClass;
  if (m.site == S::F)
    throw InputError("site class F needs a site response analysis (ASCE 7-16 11.4.8 and 20.3.1)", "site class",
                     specific_fix);
  if (m.site == S::E && m.ss >= 1.0)
    throw InputError(fmt::format("site class E with Ss = {:g} g >= 1.0 needs the site-specific procedure of ASCE 7-16 "
                                 "11.4.8 (exception 1: Fa of site class C may be used)", m.ss),
                     "Ss", specific_fix + std::string(", or the values with Fa of site class C if exception 1 applies"));
  if (m.site == S::E && m.ss > 0.75)
    throw InputError(fmt::format("Table 11.4-1 has no Fa for site class E at Ss = {:g} g: it gives 1.3 at 0.75 g and "
                                 "'see 11.4.8' at 1.0 g, so there is nothing to interpolate toward", m.ss),
                     "Ss", specific_fix);
  const bool d_exception = exception_2 && (m.site == S::D || m.site == S::D_default) && m.s1 >= 0.2;
  if ((m.site == S::D || m.site == S::D_default || m.site == S::E) && m.s1 >= 0.2 && !d_exception)
    throw InputError(
        fmt::format("site class {} with S1 = {:g} g >= 0.2 needs the site-specific procedure of ASCE 7-16 11.4.8 "
                    "(Table 11.4-2 gives Fv there for TS only; {})",
                    to_string(m.site), m.s1,
                    m.site == S::E ? "exception 3: ELF with T <= TS only"
                                   : "exception 2: ELF with Cs by eq. 12.8-2 up to T = 1.5 TS and 1.5 x eqs. 12.8-3/4 "
                                     "beyond"),
        "S1", specific_fix + std::string(", or SDS and SD1 from the tables if you design by the exception"));

  static constexpr std::array<double, 6> ss_cols{0.25, 0.5, 0.75, 1.0, 1.25, 1.5};
  static constexpr std::array<double, 6> s1_cols{0.1, 0.2, 0.3, 0.4, 0.5, 0.6};
  // Table 11.4-1 (E beyond 0.75 g is refused above; its last columns repeat 1.3 only to fill the row)
  static constexpr std::array<std::array<double, 6>, 5> fa{{{0.8, 0.8, 0.8, 0.8, 0.8, 0.8},
                                                             {0.9, 0.9, 0.9, 0.9, 0.9, 0.9},
                                                             {1.3, 1.3, 1.2, 1.2, 1.2, 1.2},
                                                             {1.6, 1.4, 1.2, 1.1, 1.0, 1.0},
                                                             {2.4, 1.7, 1.3, 1.3, 1.3, 1.3}}};
  // Table 11.4-2, Supplement 1 (D, E beyond 0.2 g are refused above)
  static constexpr std::array<std::array<double, 6>, 5> fv{{{0.8, 0.8, 0.8, 0.8, 0.8, 0.8},
                                                             {0.8, 0.8, 0.8, 0.8, 0.8, 0.8},
                                                             {1.5, 1.5, 1.5, 1.5, 1.5, 1.4},
                                                             {2.4, 2.2, 2.0, 1.9, 1.8, 1.7},
                                                             {4.2, 3.3, 2.8, 2.4, 2.2, 2.0}}};
  const std::size_t row = m.site == S::A ? 0 : m.site == S::B ? 1 : m.site == S::C ? 2 : m.site == S::E ? 4 : 3;
  Asce7SiteCoefficients c;
  c.fa = interpolate(ss_cols, fa[row], m.ss);
  if (m.site == S::D_default) c.fa = std::max(c.fa, 1.2);  // 11.4.4
  c.fv = interpolate(s1_cols, fv[row], m.s1);
  c.sms = c.fa * m.ss, c.sm1 = c.fv * m.s1;
  c.sds = 2.0 / 3.0 * c.sms, c.sd1 = 2.0 / 3.0 * c.sm1;
  c.exception_2 = d_exception;
  return c;
}

Asce7Spectrum asce7_from_maps(const Asce7MapValues& m) {
  const Asce7SiteCoefficients c = asce7_site_coefficients(m);
  Asce7Spectrum s{c.sds, c.sd1, m.tl};
  validate(s);
  return s;
}

std::string describe(const Asce7MapValues& m) {
  const Asce7SiteCoefficients c = asce7_site_coefficients(m);
  return fmt::format("Ss = {:g} g, S1 = {:g} g, site class {}: Fa = {:.4g}, Fv = {:.4g} (Tables 11.4-1, 11.4-2), "
                     "SMS = {:.4g} g, SM1 = {:.4g} g",
                     m.ss, m.s1, to_string(m.site), c.fa, c.fv, c.sms, c.sm1);
}

}  // namespace pounding
