#pragma once
// Bit-for-bit comparison of two Results (NaN equals NaN; settings in any order), for the round-trip tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <tuple>

#include "pounding/results/results.hpp"

namespace pounding::testdata {

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

inline void expect_same_header(const results::Header& a, const results::Header& b, bool same_version = true) {
  if (same_version) {
    EXPECT_EQ(a.format_version, b.format_version);
  }
  EXPECT_EQ(std::tie(a.program_version, a.git_commit, a.date, a.study_text, a.study_path, a.title, a.scene),
            std::tie(b.program_version, b.git_commit, b.date, b.study_text, b.study_path, b.title, b.scene));
  EXPECT_EQ(std::tie(a.scene_reason, a.contact_law, a.damping_law, a.stepper, a.build, a.exclusion_warning),
            std::tie(b.scene_reason, b.contact_law, b.damping_law, b.stepper, b.build, b.exclusion_warning));
  EXPECT_EQ(std::tie(a.host, a.cpu_model, a.cpu_cores), std::tie(b.host, b.cpu_model, b.cpu_cores));
  EXPECT_EQ(std::tie(a.seed, a.substeps, a.ranks, a.excluded_analyses, a.total_analyses),
            std::tie(b.seed, b.substeps, b.ranks, b.excluded_analyses, b.total_analyses));
  EXPECT_EQ(std::tie(a.restitution, a.max_dt, a.max_excluded_fraction, a.wall_time_s),
            std::tie(b.restitution, b.max_dt, b.max_excluded_fraction, b.wall_time_s));
}

inline void expect_same_tables(const results::Results& a, const results::Results& b) {
  const auto& x = a.records;
  const auto& y = b.records;
  EXPECT_EQ(std::tie(x.id, x.name, x.source, x.note, x.synthetic, x.npts),
            std::tie(y.id, y.name, y.source, y.note, y.synthetic, y.npts));
  EXPECT_TRUE(same_bits(x.dt, y.dt) && same_bits(x.duration, y.duration) && same_bits(x.pga_g, y.pga_g));
  for (const auto& [name, member] : results::model_doubles)
    EXPECT_TRUE(same_bits(a.models.*member, b.models.*member)) << "/models/" << name;
  EXPECT_EQ(std::tie(a.models.i1, a.models.i2, a.models.sample), std::tie(b.models.i1, b.models.i2, b.models.sample));
  EXPECT_TRUE(same_bits(a.models.periods, b.models.periods));
  EXPECT_EQ(a.models.zeta, b.models.zeta);
  EXPECT_TRUE(same_bits(a.gap_ratios, b.gap_ratios));
  EXPECT_TRUE(same_bits(a.gaps.ratios, b.gaps.ratios) && same_bits(a.gaps.metres, b.gaps.metres)) << "/gaps";
}

inline void expect_same_settings(results::Settings a, results::Settings b) {
  auto by_name = [](const results::Setting& p, const results::Setting& q) {
    return std::tie(p.section, p.key) < std::tie(q.section, q.key);
  };
  std::sort(a.entries.begin(), a.entries.end(), by_name);
  std::sort(b.entries.begin(), b.entries.end(), by_name);
  EXPECT_EQ(a.entries, b.entries);
}

// Every field of `a` is in `b` with the same type and bits, and `b` has no other.
inline void expect_same_fields(const results::Results& a, const results::Results& b) {
  EXPECT_EQ(a.fields.size(), b.fields.size());
  for (const results::Field& f : a.fields) {
    const results::Field* g = b.find(f.spec.group, f.spec.name);
    ASSERT_NE(g, nullptr) << "/" << f.spec.group << "/" << f.spec.name << " not read back";
    EXPECT_EQ(f.spec.dtype, g->spec.dtype);
    EXPECT_TRUE(std::visit(
        [&](const auto& v) {
          using V = std::decay_t<decltype(v)>;
          const auto* w = std::get_if<V>(&g->data);
          return w && same_bits(v, *w);
        },
        f.data))
        << "/" << f.spec.group << "/" << f.spec.name << " differs";
  }
}

// same_version = false: b was rewritten from a file of an older format (the writer writes the current one).
inline void expect_same_results(const results::Results& a, const results::Results& b, bool same_version = true) {
  expect_same_header(a.header, b.header, same_version);
  expect_same_settings(a.settings, b.settings);
  expect_same_tables(a, b);
  expect_same_fields(a, b);
}

}  // namespace pounding::testdata
