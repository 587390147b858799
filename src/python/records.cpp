// Ground-motion records, response spectra and code design spectra: the engine's readers and formulas
// (motion/records.hpp, spectrum.hpp, design_spectrum.hpp), not copies.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common.hpp"
#include "pounding/core/error.hpp"
#include "pounding/motion/asce7_site.hpp"
#include "pounding/motion/design_spectrum.hpp"
#include "pounding/motion/records.hpp"
#include "pounding/motion/spectrum.hpp"

namespace pounding::python {
namespace {

// units None: g, unless an AT2 header names its units (as the CLI's --units default); given: the file's values
// are in those units, an AT2 header that names others still wins (as the CLI).
Record read_record_py(const std::string& path, const std::optional<std::string>& units, double dt) {
  ReadOptions ro;
  if (units) ro.units = parse_units(*units);
  ro.dt = dt;
  py::gil_scoped_release unlocked;
  return read_record(path, ro);
}

py::dict measures_dict(const Record& r) {
  const Measures m = measure(r);
  py::dict d;
  d["pga"] = m.pga, d["pgv"] = m.pgv, d["pgd"] = m.pgd, d["arias"] = m.arias;
  d["t05"] = m.t05, d["t45"] = m.t45, d["t95"] = m.t95, d["d5_95"] = m.d5_95();
  return d;
}

py::dict spectrum_py(const Record& r, const py::handle& periods, double zeta) {
  const std::vector<double> t = to_vector(periods, "periods");
  for (double p : t)
    if (!(p > 0) || !std::isfinite(p)) throw py::value_error("periods: every period must be finite and > 0 s");
  if (!(zeta >= 0 && zeta < 1)) throw py::value_error("zeta: the damping ratio must be in [0, 1)");
  Spectrum s;
  run_interruptible([&](const std::atomic<bool>& stop) { s = response_spectrum(r, t, zeta, &stop); });  // Ctrl-C
  py::dict d;
  d["period"] = to_numpy(s.periods), d["sd"] = to_numpy(s.sd), d["psv"] = to_numpy(s.psv), d["psa"] = to_numpy(s.psa);
  std::vector<double> g(s.psa);
  for (double& v : g) v /= g_accel;
  d["sa_g"] = to_numpy(g);
  return d;
}

double number(const py::dict& p, const char* key, std::optional<double> def = {}) {
  if (p.contains(key)) return to_number(p[key], std::string("design_spectrum: ") + key);
  if (def) return *def;
  throw py::value_error(std::string("design_spectrum: the parameter '") + key + "' is missing");
}

std::string text(const py::dict& p, const char* key, const char* def) {
  return p.contains(key) ? py::str(p[key]).cast<std::string>() : std::string(def);
}

template <class E, std::size_t N>
E one_of(const std::string& value, const char* const (&names)[N], const char* what) {
  for (std::size_t i = 0; i < N; ++i)
    if (value == names[i]) return static_cast<E>(i);
  std::string all;
  for (std::size_t i = 0; i < N; ++i) all += (i ? ", " : "") + std::string(names[i]);
  throw py::value_error(std::string("design_spectrum: ") + what + " '" + value + "' is not one of " + all);
}

DesignSpectrum::Params asce7_params(const py::dict& p) {
  if (p.contains("ss") || p.contains("s1")) {
    Asce7MapValues m;
    m.ss = number(p, "ss"), m.s1 = number(p, "s1"), m.tl = number(p, "tl", 8.0);
    m.site = parse_asce7_site_class(text(p, "site_class", "D-default"), "design_spectrum(site_class=...)");
    return asce7_from_maps(m);
  }
  return Asce7Spectrum{number(p, "sds"), number(p, "sd1"), number(p, "tl", 8.0)};
}

// The parameters each code takes: any other is a TypeError naming it and these (issue 44 item 10: TL=4 was ignored,
// leaving tl at its default).
void check_parameters(const std::string& code, const py::dict& p) {
  static const std::map<std::string, std::vector<std::string>> taken{
      {"asce7-16", {"sds", "sd1", "tl", "ss", "s1", "site_class"}},
      {"ec8", {"type", "ground", "agr", "importance", "damping_percent"}},
      {"2800", {"a", "importance", "soil"}},
      {"nzs1170", {"site", "z", "r"}},
      {"table", {"table_periods", "table_sa", "file"}}};
  const auto keys = taken.find(code);
  if (keys == taken.end()) return;  // an unknown code: spectrum_params names the codes
  for (const auto& kv : p) {
    const std::string name = py::str(kv.first).cast<std::string>();
    if (std::find(keys->second.begin(), keys->second.end(), name) != keys->second.end()) continue;
    std::string lower = name;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const bool close = std::find(keys->second.begin(), keys->second.end(), lower) != keys->second.end();
    throw py::type_error(fmt::format("design_spectrum(\"{}\"): unknown parameter '{}'{}; it takes {}", code, name,
                                     close ? fmt::format(" (did you mean '{}'?)", lower) : "",
                                     fmt::format("{}", fmt::join(keys->second, ", "))));
  }
}

DesignSpectrum::Params spectrum_params(const std::string& code, const py::dict& p) {
  check_parameters(code, p);
  if (code == "asce7-16") return asce7_params(p);
  if (code == "ec8") {
    const char* const grounds[] = {"A", "B", "C", "D", "E"};
    Ec8Spectrum s;
    s.type = number(p, "type", 1.0) == 1.0 ? Ec8Type::type1 : Ec8Type::type2;
    s.ground = one_of<Ec8Ground>(text(p, "ground", "A"), grounds, "ground");
    s.agr = number(p, "agr"), s.importance = number(p, "importance", 1.0);
    s.damping_percent = number(p, "damping_percent", 5.0);
    return s;
  }
  if (code == "2800") {
    const char* const soils[] = {"I", "II", "III", "IV"};
    Iran2800Spectrum s;
    s.a = number(p, "a"), s.importance = number(p, "importance", 1.0);
    s.soil = one_of<Iran2800Soil>(text(p, "soil", "II"), soils, "soil");
    return s;
  }
  if (code == "nzs1170") {
    Nzs1170Spectrum s;
    const auto site = parse_nzs1170_site(text(p, "site", "C"));
    if (!site) throw py::value_error("design_spectrum: site '" + text(p, "site", "") + "' is not one of A, B, C, D, E");
    s.site = *site, s.z = number(p, "z"), s.r = number(p, "r", 1.0);
    return s;
  }
  if (code == "table") {
    if (p.contains("file")) return read_tabulated_spectrum(text(p, "file", ""));
    TabulatedSpectrum s;
    s.periods = to_vector(p["table_periods"], "table_periods"), s.sa = to_vector(p["table_sa"], "table_sa");
    return s;
  }
  throw py::value_error("design_spectrum: unknown code '" + code + "' (asce7-16, ec8, 2800, nzs1170, table)");
}

py::tuple design_spectrum_py(const std::string& code, const py::handle& periods, const py::dict& params,
                             bool mcer) {
  DesignSpectrum ds(spectrum_params(code, params));  // validate(): InputError naming the parameter and its range
  if (mcer && code != "asce7-16") throw py::value_error("design_spectrum: mcer=True is ASCE 7-16's (1.5 x design)");
  const std::vector<double> t = to_vector(periods, "periods");
  std::vector<double> sa(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) sa[i] = ds.sa(t[i]) * (mcer ? 1.5 : 1.0);
  return py::make_tuple(to_numpy(sa), ds.describe());
}

Record record_from_arrays(const py::handle& acc_g, double dt, const std::string& name) {
  Record r;
  r.name = name, r.source = "python:" + name, r.dt = dt;
  r.acc = to_vector(acc_g, "acc_g");
  if (r.acc.size() < 2)
    throw InputError(fmt::format("Record: acc_g holds {} value(s)", r.acc.size()), "Record(acc_g=)",
                     "give at least 2 accelerations (g), one per step dt");
  if (!(dt >= record_dt_min && dt <= record_dt_max))
    throw py::value_error(fmt::format("Record: dt = {:g} s is outside [1e-4, 0.1] s", dt));
  for (double& a : r.acc) {
    if (!std::isfinite(a)) throw py::value_error("Record: acc_g holds a value that is not a finite number");
    a *= g_accel;
  }
  return r;
}

}  // namespace

void bind_records(py::module_& m) {
  py::class_<Record>(m, "Record", "A ground-motion record: dt (s), acc (m/s^2), acc_g (g), meta (format, units, ...)")
      .def(py::init(&record_from_arrays), py::arg("acc_g"), py::arg("dt"), py::arg("name") = "record",
           "a record from accelerations in g at step dt (s)")
      .def_readonly("name", &Record::name)
      .def_readonly("source", &Record::source)
      .def_readonly("dt", &Record::dt)
      .def_readonly("meta", &Record::meta)
      .def_property_readonly("acc", [](const Record& r) { return to_numpy(r.acc); }, "acceleration, m/s^2")
      .def_property_readonly("acc_g", [](const Record& r) {
        std::vector<double> g(r.acc);
        for (double& v : g) v /= g_accel;
        return to_numpy(g);
      }, "acceleration, g")
      .def_property_readonly("npts", [](const Record& r) { return r.acc.size(); })
      .def_property_readonly("duration", &Record::duration, "(npts - 1) dt, s")
      .def_property_readonly("pga_g", [](const Record& r) { return r.pga() / g_accel; })
      .def("measures", &measures_dict, "PGA (m/s^2), PGV (m/s), PGD (m), Arias (m/s), t05/t45/t95, d5_95 (s)")
      .def("__repr__", [](const Record& r) {
        return fmt::format("<pounding.Record {}: {} points, dt {:g} s, PGA {:.4g} g>", r.name, r.acc.size(), r.dt,
                           r.pga() / g_accel);
      });
  m.def("read_record", &read_record_py, py::arg("path"), py::arg("units") = py::none(), py::arg("dt") = 0.0,
        "Reads a record (PEER AT2 NGA-West2/West1, the 4-line El Centro variant, two-column time/acc text, "
        "one-column text with dt=...), as `pounding records show` does; units 'g' (default), 'm/s2', 'cm/s2' "
        "(an AT2 header that names its units wins). Bad files raise ValueError with the CLI's message.");
  m.def("spectrum", &spectrum_py, py::arg("record"), py::arg("periods"), py::arg("zeta") = 0.05,
        "Elastic response spectrum (exact for acceleration linear between samples): period, sd (m), psv (m/s), "
        "psa (m/s^2), sa_g (g).");
  m.def("design_spectrum", &design_spectrum_py, py::arg("code"), py::arg("periods"), py::arg("params"),
        py::arg("mcer") = false, "(Sa in g at the periods, the code's description); use pounding.design_spectrum");
}

}  // namespace pounding::python
