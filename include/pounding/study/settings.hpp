#pragma once
// Every setting of a Study under its study-file section and key, in one list: the results file stores them
// as /settings/<section>/<key> attributes (settings_of in src/study/make_results.cpp, written by
// src/results/writer.cpp) and the report reads them back (results::Settings), so no
// reader needs the study text. A Study field of study_fields.hpp's lists is stored from its list by its key's store
// rule (store_fields); any other is one line here.
//
// visit_settings(study, v) calls v(section, key, value) with value one of: double, std::int64_t, bool,
// std::string, std::vector<double>, std::vector<std::string>. Section "" is the file's top level.
#include <cstdint>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "pounding/config/study_keys.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/sampling/bridge.hpp"
#include "pounding/study/study.hpp"
#include "pounding/study/study_fields.hpp"

namespace pounding {

// Whether x is the typed default of its key (config::typed_default; a computed default never is).
template <class T>
bool is_key_default(const config::StudyKey& k, const T& x) {
  const config::KeyDefault d = config::typed_default(k);
  if constexpr (std::is_same_v<T, int>) {
    const long* p = std::get_if<long>(&d);
    return p && *p == x;
  } else {
    const T* p = std::get_if<T>(&d);
    return p && *p == x;
  }
}

// One setting by its key's store rule (study_keys.hpp): none, not stored; unless_default, stored where x is not the
// default; as, stored under the rule's attribute; always, under the key. An int is stored as std::int64_t.
template <class T, class V>
void store_setting(const std::string& section, const char* key, const T& x, V& v) {
  const config::StudyKey& k = config::study_key(section, key);
  if (k.store.rule == config::Store::none) return;
  if (k.store.rule == config::Store::unless_default && is_key_default(k, x)) return;
  const std::string name = k.store.rule == config::Store::as ? std::string(k.store.text) : std::string(key);
  if constexpr (std::is_same_v<T, int>) v(section, name, static_cast<std::int64_t>(x));
  else v(section, name, x);
}

// The fields of one of study_fields' lists (of a Study, or of a section's own struct), each by its store rule.
template <class Obj, class Fields, class V>
void store_fields(const Obj& obj, const std::string& section, const Fields& fields, V& v) {
  fields([&](const char* key, auto member) { store_setting(section, key, obj.*member, v); });
}

// [structures.buildingK] as resolved; a distribution as its describe() text.
template <class V>
void visit_building_settings(const StructureModel& m, std::size_t i, V& v) {
  using S = std::string;
  const BuildingModel b = m.row_building(i);
  const S sec = "structures.building" + std::to_string(i + 1);
  v(sec, "periods", b.periods);
  v(sec, "period", b.period_text());
  v(sec, "height", b.height_text());
  v(sec, "mass", b.mass_text());
  v(sec, "zeta", b.zeta_text());
  v(sec, "yield", b.yield_text());
  v(sec, "alpha", b.alpha);
  v(sec, "hysteresis", S(to_string(b.hysteresis)));
  v(sec, "aspect_ratios", b.aspect_ratios);
  v(sec, "rho_mean", b.rho_mean);
  v(sec, "rho_cov", b.rho_cov);
  v(sec, "mbar_mean", b.mbar_mean);
  v(sec, "mbar_cov", b.mbar_cov);
  v(sec, "mbar_min", b.mbar_min);
  v(sec, "mbar_max", b.mbar_max);
  v(sec, "drift", b.drift);
  v(sec, "ductility", b.ductility);
  v(sec, "height_min", b.height_min);
  v(sec, "height_max", b.height_max);
  v(sec, "ct_lower", b.ct_lower);
  v(sec, "ct_upper", b.ct_upper);
  v(sec, "height_exponent", b.height_exponent);
  // the code design factors, where given (sampling/code_factors.hpp)
  const CodeFactors& f = b.code;
  for (const auto& [key, value] : {std::pair<const char*, double>{"asce7_r", f.asce7_r}, {"asce7_cd", f.asce7_cd},
                                   {"asce7_ie", f.asce7_ie}, {"ec8_q", f.ec8_q}, {"s2800_ru", f.s2800_ru},
                                   {"s2800_cd", f.s2800_cd}, {"s2800_importance", f.s2800_importance},
                                   {"storey_height", b.storey_heights.empty() ? f.storey_height : 0.0}})
    if (value > 0) v(sec, key, value);
  if (f.storeys > 0) v(sec, "storeys", static_cast<std::int64_t>(f.storeys));
  if (m.any_shear() || m.row()) {  // the structural model (sampling/building.hpp); absent from SDOF pair studies (their bits)
    v(sec, "model", S(to_string(b.kind)));
    v(sec, "stiffness_profile", S(to_string(b.profile)));
    if (f.storey_height <= 0) v(sec, "storey_height", b.storey_height());
    // a number as before (the bits of every earlier study), an array where one per storey is given
    for (auto [key, x] : {std::pair{"floor_mass", &b.floor_mass}, {"storey_stiffness", &b.storey_stiffness},
                          {"storey_yield", &b.storey_yield}, {"storey_height", &b.storey_heights}}) {
      if (x->size() == 1) v(sec, key, x->front());
      else if (x->size() > 1) v(sec, key, *x);
    }
    if (b.isolated) v(sec, "isolation", b.isolation_text());
    if (b.moat) v(sec, "moat", b.moat_text());
    // Rayleigh's modes where not 1 and 2 (absent otherwise: the bits of every earlier study)
    if (b.shear() && !b.modal_damping && !b.rayleigh_default())
      v(sec, "rayleigh_modes", std::vector<double>{double(b.rayleigh_i), double(b.rayleigh_j)});
    // classical modal damping where chosen (absent with Rayleigh, the default: the bits of every earlier study);
    // modal_zeta where given (without it every mode takes the building's zeta)
    if (b.shear() && b.modal_damping) {
      v(sec, "damping", S("modal"));
      if (!b.modal_zeta.empty()) v(sec, "modal_zeta", b.modal_zeta);
    }
  }
}

// The [structures] settings: the buildings' model (absent from a bridge study, whose StructureModel only numbers
// its samples).
template <class V>
void visit_structure_settings(const StructureModel& m, V& v) {
  using S = std::string;
  v("structures", "periods", m.periods);
  v("structures", "samples_per_pair", m.samples_per_pair);
  v("structures", "aspect_ratios", m.aspect_ratios);
  v("structures", "rho_mean", m.rho_mean);
  v("structures", "rho_cov", m.rho_cov);
  v("structures", "mbar_mean", m.mbar_mean);
  v("structures", "mbar_cov", m.mbar_cov);
  v("structures", "mbar_min", m.mbar_min);
  v("structures", "mbar_max", m.mbar_max);
  v("structures", "zeta", m.zeta);
  v("structures", "hysteresis", S(to_string(m.hysteresis)));
  v("structures", "drift", m.drift);
  v("structures", "ductility", m.ductility);
  v("structures", "alpha", m.alpha);
  v("structures", "height_min", m.height_min);
  v("structures", "height_max", m.height_max);
  v("structures", "ct_lower", m.ct_lower);
  v("structures", "ct_upper", m.ct_upper);
  v("structures", "height_exponent", m.height_exponent);
  v("structures", "code_gap_coefficient", m.code_gap_coefficient);
  v("structures", "contact_density", m.contact_density);
  v("structures", "contact_youngs_modulus", m.contact_youngs_modulus);
  v("structures", "contact_poisson", m.contact_poisson);
  v("structures", "kh", m.kh);
  v("structures", "equal_heights", m.equal_heights);
  v("structures", "heights_specified", m.heights_specified());
  // a row's building count (absent from pair studies: their bits)
  if (m.row()) v("structures", "buildings", static_cast<std::int64_t>(m.building_count()));
  for (std::size_t i = 0; i < m.building_count(); ++i) visit_building_settings(m, i, v);
}

// [records.motions] as resolved (supports as positions, loss as beta, the seed used) and `generator`, the one line
// the report prints (spatial::describe).
template <class V>
void visit_motion_settings(const StudyMotions& m, V&& v) {
  using S = std::string;
  const spatial::Settings& x = m.settings;
  const char* section = "records.motions";
  v(section, "generator", spatial::describe(x));
  v(section, "positions", x.positions);
  v(section, "velocity", x.velocity);
  v(section, "wave_passage", x.wave_passage);
  v(section, "coherency", S(to_string(x.coherency.model)));
  if (x.coherency.model == spatial::CoherencyModel::sobczyk) v(section, "beta", x.coherency.beta);
  if (x.coherency.model == spatial::CoherencyModel::luco_wong) v(section, "luco_wong_a", x.coherency.lw_a);
  if (x.coherency.model == spatial::CoherencyModel::harichandran_vanmarcke) {
    const auto& c = x.coherency;
    v(section, "hv_a", c.hv_a), v(section, "hv_alpha", c.hv_alpha), v(section, "hv_k", c.hv_k);
    v(section, "hv_f0", c.hv_f0), v(section, "hv_b", c.hv_b);
  }
  if (!x.sites.empty()) {  // Der Kiureghian's site response, one entry per support
    std::vector<double> f, z;
    for (const spatial::Site& site : x.sites) f.push_back(site.frequency), z.push_back(site.damping);
    v(section, "site_frequency", f);
    v(section, "site_damping", z);
  }
  std::vector<std::string> targets;
  for (const DesignSpectrum& d : x.targets) targets.push_back(d.describe());
  v(section, "targets", targets);
  v(section, "damping", x.damping);
  v(section, "dt", x.dt);
  v(section, "duration", x.duration);
  v(section, "envelope", std::vector<double>{x.envelope.rise, x.envelope.strong, x.envelope.decay});
  v(section, "f_range", std::vector<double>{x.f_min, x.f_max});
  v(section, "match_periods", x.match_periods);
  v(section, "iterations", static_cast<std::int64_t>(x.iterations));
  v(section, "tolerance", x.tolerance);
  v(section, "first", static_cast<std::int64_t>(m.first + 1));
  v(section, "realisations", static_cast<std::int64_t>(m.count));
  v(section, "seed", static_cast<std::int64_t>(x.seed));
  v(section, "seed_from", S(m.seed_given ? "[records.motions] seed" : "the study's seed"));
  v(section, "uniform", m.uniform);
}

// [target_spectrum] as resolved, with the selection rules of [records] and the code's parameters.
template <class V>
void visit_target_settings(const Study& s, V& v) {
  using S = std::string;
  const TargetSpectrumSection& x = s.target;
  v("target_spectrum", "code", S(to_string(x.spec.code)));
  v("target_spectrum", "description", x.target_text);
  v("target_spectrum", "rule", S(to_string(x.options.rule)));
  v("target_spectrum", "t_min", x.options.t_lo);
  v("target_spectrum", "t_max", x.options.t_hi);
  v("target_spectrum", "range_given", x.range_given);
  store_fields(x.options, "target_spectrum", study_fields::target_spectrum, v);
  v("records", "max_per_event", static_cast<std::int64_t>(s.max_per_event));  // selection rules (with select)
  v("records", "components", S(to_string(s.components)));
  // the code's parameters, so the report can rebuild the design spectrum (code design displacements)
  switch (x.spec.code) {
    case TargetCode::asce7_16:
      v("target_spectrum", "sds", x.spec.asce7.sds);  // the design values, without mcer's 1.5
      v("target_spectrum", "sd1", x.spec.asce7.sd1);
      v("target_spectrum", "tl", x.spec.asce7.tl);
      v("target_spectrum", "mcer", x.spec.mcer);
      if (x.spec.from_maps) {
        v("target_spectrum", "ss", x.spec.maps.ss);
        v("target_spectrum", "s1", x.spec.maps.s1);
        v("target_spectrum", "site_class", S(to_string(x.spec.maps.site)));
      }
      break;
    case TargetCode::ec8:
      v("target_spectrum", "type", static_cast<std::int64_t>(x.spec.ec8.type == Ec8Type::type1 ? 1 : 2));
      v("target_spectrum", "ground", S(1, "ABCDE"[static_cast<int>(x.spec.ec8.ground)]));
      v("target_spectrum", "agr", x.spec.ec8.agr);
      v("target_spectrum", "importance", x.spec.ec8.importance);
      break;
    case TargetCode::iran2800: {
      const char* const soils[] = {"I", "II", "III", "IV"};
      v("target_spectrum", "a", x.spec.iran2800.a);
      v("target_spectrum", "soil", S(soils[static_cast<int>(x.spec.iran2800.soil)]));
      v("target_spectrum", "importance", x.spec.iran2800.importance);
      break;
    }
    case TargetCode::csv: break;
  }
}

// [intensity] and [hazard] of a fragility study (study/intensity.hpp); absent otherwise.
template <class V>
void visit_fragility_settings(const Study& s, V& v) {
  using S = std::string;
  if (s.intensity.enabled) {  // a fragility study (study/intensity.hpp); absent otherwise
    const IntensitySpec& x = s.intensity;
    v("intensity", "measure", S(to_string(x.im.measure)));
    v("intensity", "units", S(im_units(x.im.measure)));
    v("intensity", "description", describe(x.im));
    v("intensity", "periods", x.im.periods);
    v("intensity", "period_pair", x.period_pair);
    v("intensity", "damping", x.im.damping);
    v("intensity", "levels", x.levels);
    v("intensity", "max_scale", x.max_scale);
    v("intensity", "method", S(to_string(x.method)));
    v("intensity", "tolerance", x.tolerance);
  }
  if (s.hazard.enabled) {
    const HazardSpec& h = s.hazard;
    v("hazard", "curve", h.curve);
    v("hazard", "im", h.im);
    v("hazard", "rate", h.rate);
    v("hazard", "k0", h.k0);
    v("hazard", "k", h.k);
    store_fields(h, "hazard", study_fields::hazard, v);
  }
}

template <class V>
void visit_settings(const Study& s, V&& v) {
  using S = std::string;
  v("", "title", s.title);
  v("", "seed", static_cast<std::int64_t>(s.seed));
  v("", "scene", S(to_string(s.scene_requested)));
  v("", "scene_resolved", S(to_string(s.scene)));
  v("", "output", s.output);

  std::vector<std::string> files;
  std::vector<double> file_scales;
  for (const auto& f : s.files) files.push_back(f.path), file_scales.push_back(f.scale);
  v("records", "suite", s.suite);
  v("records", "real_dir", s.real_dir);
  v("records", "directory", s.directory);
  v("records", "files", files);
  v("records", "file_scales", file_scales);
  store_fields(s, "records", study_fields::records, v);
  v("records", "units", S(to_string(s.units)));
  v("records", "dt", s.dt_one_column);
  v("records", "select", static_cast<std::int64_t>(s.select));
  v("records", "polarity", S(to_string(s.polarity)));  // absent in older files: "recorded"
  if (s.supports > 0) v("records", "supports", static_cast<std::int64_t>(s.supports));  // a multi-support bridge
  if (s.motions) visit_motion_settings(*s.motions, v);  // [records.motions]: what the generator was given
  if (s.target.enabled) visit_target_settings(s, v);  // [target_spectrum] (study/target_spectrum.hpp); absent otherwise

  const StructureModel& m = s.structures;
  if (!m.bridge) visit_structure_settings(m, v);  // a bridge study: its frames are [bridge]'s, not these

  if (m.bridge) {  // a bridge study (sampling/bridge.hpp); absent otherwise
    v("bridge", "samples", m.samples_per_pair);
    v("bridge", "period_cov", m.bridge->period_cov);
    v("bridge", "mass_cov", m.bridge->mass_cov);
    v("bridge", "reference_gap", m.bridge->reference_gap);
    v("bridge", "joint_gap_offsets", m.bridge->offsets);
    v("bridge", "description", m.bridge->describe());
  }

  v("gaps", s.gap_metres ? "metres" : "ratios", s.gap_ratios);  // the axis' key names its unit (the report reads it)
  if (!std::isnan(s.existing_gap)) v("gaps", "existing", s.existing_gap);  // absent: the other studies' bits
  v("gaps", "curve_max", s.curve_max);
  store_fields(s, "gaps", study_fields::gaps, v);

  v("contact", "law", S(to_string(s.contact.law)));
  v("contact", "damping_law", S(to_string(s.contact.damping)));
  store_fields(s, "contact", study_fields::contact, v);
  v("contact", "n", s.contact.n);
  v("contact", "v0_min", s.contact.v0_min);
  v("contact", "stiffness", s.contact_stiffness);
  // shear buildings and rows (absent where not given: the other studies' bits)
  store_setting("contact", "levels", S(to_string(s.contact_levels)), v);
  // where the floors meet (the report's code rules per contact level rebuild them); level_tolerance (in the list) and
  // shape_functions are stored unless at their defaults
  store_setting("contact", "shape_functions", S(to_string(s.shape_functions)), v);
  if (!s.gap_offsets.empty()) v("contact", "gap_offsets", s.gap_offsets);
  if (!s.joint_gap_offsets.empty()) v("contact", "joint_gap_offsets", s.joint_gap_offsets);
  if (s.restitution) v("contact", "restitution", s.restitution->describe());  // e(v0); absent: e for every impact

  v("analysis", "stepper", S(to_string(s.stepper)));
  store_fields(s, "analysis", study_fields::analysis, v);
  v("analysis", "max_dt", s.max_dt);
  v("analysis", "batch", static_cast<std::int64_t>(s.batch));
  v("analysis", "coarse", S(to_string(s.coarse)));

  store_fields(s, "report", study_fields::report, v);
  v("report", "fit_min", s.fit_min);
  v("report", "fit_max", s.fit_max);

  store_fields(s, "outputs", study_fields::outputs, v);
  v("outputs", "per_model", s.per_model);
  if (s.stream) v("outputs", "stream", s.stream);  // per_model = "stream" (absent otherwise, as in earlier files)
  if (!s.histories.empty()) v("outputs", "histories", s.histories_text);  // absent without the key (earlier files' bits)

  visit_fragility_settings(s, v);
}

}  // namespace pounding
