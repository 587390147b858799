#pragma once
// A small Results built in memory (no run): 2 records x 4 models (periods 0.5 and 1.0, one sample per pair),
// the impacts scene with 2 gap ratios, one excluded uncoupled analysis and one excluded coupled one, and
// every kind of setting, and /gaps. Used by the results round trip and the report golden test.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "pounding/results/results.hpp"

namespace pounding::testdata {

inline results::Results sample_results() {
  using namespace pounding::results;
  Results r;
  r.path = "sample.h5";
  Header& h = r.header;
  h.program_version = "0.1.0", h.git_commit = "abcdef123456", h.date = "2026-01-02T03:04:05Z";
  h.seed = 42, h.study_text = "title = \"sample\"\nseed = 42\n", h.study_path = "sample.toml";
  h.title = "sample results", h.scene = "impacts", h.scene_reason = "asked for in the study file";
  h.contact_law = "hertzdamp", h.damping_law = "lankarani-nikravesh", h.restitution = 0.65;
  h.stepper = "central-difference", h.substeps = 2, h.max_dt = 0.0025, h.ranks = 2, h.build = "test build";
  h.excluded_analyses = 2, h.total_analyses = 24, h.max_excluded_fraction = 0.5, h.exclusion_warning = "";
  h.wall_time_s = 1.25;
  h.host = "sample-host", h.cpu_model = "Test CPU @ 1.00GHz", h.cpu_cores = 4;

  r.settings.add("", "title", std::string("sample results"));
  r.settings.add("", "seed", std::int64_t{42});
  r.settings.add("records", "files", std::vector<std::string>{"a.AT2", "b.AT2"});
  r.settings.add("records", "synthetic_only", std::int64_t{1});
  r.settings.add("structures", "periods", std::vector<double>{0.5, 1.0});
  r.settings.add("structures", "code_gap_coefficient", 0.008);
  r.settings.add("gaps", "ratios", std::vector<double>{0.2, 0.5, 1.0});
  r.settings.add("gaps", "curve_max", 1.5);
  r.settings.add("gaps", "curve_step", 0.1);
  r.settings.add("report", "targets", std::vector<double>{50, 10});
  r.settings.add("report", "confidence", 0.9);
  r.settings.add("report", "bootstrap", std::int64_t{200});
  r.settings.add("report", "fit_min", 0.1);
  r.settings.add("report", "fit_max", 1.0);
  r.settings.add("outputs", "empty", std::vector<double>{});

  RecordTable& t = r.records;
  t.id = {"EQ1", "EQ2"}, t.name = {"first", "second"}, t.source = {"synthetic", "a.AT2"}, t.note = {"stand-in", ""};
  t.synthetic = {1, 0}, t.dt = {0.01, 0.005}, t.duration = {20.0, 30.5}, t.pga_g = {0.35, 0.512}, t.npts = {2000, 6100};

  ModelTable& m = r.models;
  m.periods = {0.5, 1.0}, m.zeta = 0.05;
  m.i1 = {0, 0, 1, 1}, m.i2 = {0, 1, 0, 1}, m.sample = {0, 0, 0, 0};
  for (const auto& [name, member] : model_doubles) (m.*member) = {1.0, 2.0, 3.0, 4.0};
  m.T1 = {0.5, 0.5, 1.0, 1.0}, m.T2 = {0.5, 1.0, 0.5, 1.0};
  m.code_gap = {0.1, 0.2, 0.3, 0.4};
  m.zeta1 = m.zeta2 = {0.05, 0.05, 0.05, 0.05}, m.alpha1 = m.alpha2 = {0.05, 0.05, 0.05, 0.05};
  m.periods1 = m.periods2 = m.periods;

  r.gap_ratios = {0.2, 0.5};
  r.gaps = gap_table(r.gap_ratios, m.code_gap);
  // [records x models]: peak closing / code gap z = 0.05 ... 1.25; record 2, model 3 diverged
  const std::vector<double> z = {0.05, 0.35, 0.62, 1.25, 0.15, 0.45, 0.95, 0.0};
  std::vector<std::uint8_t> status = {0, 0, 0, 0, 0, 0, 0, 1};
  std::vector<double> pu1(8), pu2(8), pc(8);
  for (std::size_t q = 0; q < 8; ++q) {
    pc[q] = z[q] * m.code_gap[q % 4];
    pu1[q] = 0.01 * static_cast<double>(q + 1), pu2[q] = 0.02 * static_cast<double>(q + 2);
  }
  pc[7] = pu1[7] = pu2[7] = NAN;
  r.fields.push_back({unit_fields[0], status});
  r.fields.push_back({unit_fields[1], pu1});
  r.fields.push_back({unit_fields[2], pu2});
  r.fields.push_back({unit_fields[3], pc});
  // [records x models x gaps]: impacts where z > gap ratio; record 1, model 2, gap 2 non-finite
  std::vector<std::uint8_t> is(16, 0);
  std::vector<std::int32_t> count(16);
  std::vector<double> force(16), ipu1(16), ipu2(16), first(16);
  for (std::size_t q = 0; q < 8; ++q)
    for (std::size_t g = 0; g < 2; ++g) {
      const std::size_t k = q * 2 + g;
      const bool hit = z[q] > r.gap_ratios[g];
      count[k] = hit ? static_cast<std::int32_t>(1 + q % 3) : 0;
      force[k] = hit ? 1e6 * static_cast<double>(q + 1) : 0.0;
      ipu1[k] = pu1[q] * (hit ? 1.1 : 1.0), ipu2[k] = pu2[q] * (hit ? 0.9 : 1.0);
      first[k] = hit ? 0.5 * static_cast<double>(q) : NAN;
    }
  is[2 * 2 + 1] = 2;
  r.fields.push_back({unit_fields[4], is});
  r.fields.push_back({unit_fields[5], count});
  r.fields.push_back({unit_fields[6], force});
  r.fields.push_back({unit_fields[7], ipu1});
  r.fields.push_back({unit_fields[8], ipu2});
  r.fields.push_back({unit_fields[9], first});
  add_derived_fields(r);
  return r;
}

// The /system of a 3-storey building (left) beside a 5-storey one, storeys of 3.2 m, written out by hand from
// model::shear_buildings' numbering (level-major: floor k of every building left to right; spring d under DOF d;
// one element per common level 1-3 in the study-gap group "pounding"): DOFs 0 2 4 are building 1's floors 1-3,
// 1 3 5 6 7 building 2's floors 1-5.
inline results::SystemTable sample_system_table() {
  results::SystemTable t;
  t.building_label = {"building1", "building2"};
  t.building_floors = {3, 5};
  t.building_isolated = {0, 0};
  t.dof_building = {0, 1, 0, 1, 0, 1, 1, 1};
  t.dof_floor = {1, 1, 2, 2, 3, 3, 4, 5};
  t.dof_height = {3.2, 3.2, 6.4, 6.4, 9.600000000000001, 9.600000000000001, 12.8, 16.0};
  t.spring_i = {-1, -1, 0, 1, 2, 3, 5, 6};
  t.spring_j = {0, 1, 2, 3, 4, 5, 6, 7};
  t.spring_building = {0, 1, 0, 1, 0, 1, 1, 1};
  t.spring_storey = {1, 1, 2, 2, 3, 3, 4, 5};
  t.spring_role = std::vector<std::string>(8, "storey");
  t.spring_law = std::vector<std::string>(8, "bilinear");
  t.element_left_kind = t.element_right_kind = {"point", "point", "point"};
  t.element_left_dof = {0, 2, 4}, t.element_right_dof = {1, 3, 5};
  t.element_left_dof2 = t.element_right_dof2 = {-1, -1, -1};
  t.element_left_xi = t.element_right_xi = {0.0, 0.0, 0.0};
  t.element_level = {1, 2, 3};
  t.element_level_height = {3.2, 6.4, 9.600000000000001};
  t.element_group = {0, 0, 0};
  t.element_gap_offset = {0.0, 0.0, 0.0};
  t.element_label = {"level 1", "level 2", "level 3"};
  t.group_name = {"pounding"}, t.group_law = {"hertzdamp"}, t.group_damping_law = {"lankarani-nikravesh"};
  t.group_study_gap = {1}, t.group_elements = {3};
  return t;
}

// sample_results() as a format-3 file of that system: every per-floor and per-element field, each value naming
// its place (1000 x field + flat index; the i32 counts the flat index), and building 2 of model 1 a 4-storey
// sample in the 5-floor extent: its floor 5 is NaN in every per-floor field of building 2.
inline double system_value(std::size_t field, std::size_t k) {
  return 1000.0 * static_cast<double>(field) + 0.25 * static_cast<double>(k);
}
inline results::Results sample_system_results() {
  using namespace pounding::results;
  Results r = sample_results();
  r.header.format_version = format_version;
  r.system = sample_system_table();
  const std::size_t R = r.record_count(), M = r.model_count(), G = r.gap_ratios.size();
  const std::vector<FieldSpec> specs = system_fields(r.system.extents(), true);
  for (std::size_t f = 0; f < specs.size(); ++f) {
    const FieldSpec& s = specs[f];
    const std::size_t per = per_lane(s, G), n = R * M * per;
    if (s.dtype == Dtype::i32) {
      std::vector<std::int32_t> v(n);
      for (std::size_t k = 0; k < n; ++k) v[k] = static_cast<std::int32_t>(k);
      r.fields.push_back({s, std::move(v)});
      continue;
    }
    std::vector<double> v(n);
    for (std::size_t k = 0; k < n; ++k) v[k] = system_value(f, k);
    if (per_floor(s.extent) && s.building == 2)  // model 1: 4 storeys (at every gap)
      for (std::size_t rec = 0; rec < R; ++rec)
        for (std::size_t at = 4; at < per; at += s.count) v[(rec * M + 1) * per + at] = NAN;
    r.fields.push_back({s, std::move(v)});
  }
  return r;
}

}  // namespace pounding::testdata
