#include "pounding/results/writer.hpp"

#include <map>
#include <type_traits>

#include "pounding/io/hdf5.hpp"

namespace pounding::results {

namespace {

void write_header_start(h5::hid root, const Header& h) {
  visit_header_start(h, [&](const char* name, const auto& value) { h5::write_attribute(root, name, value); });
}

void write_header_end(h5::hid root, const Header& h) {
  visit_header_end(h, [&](const char* name, const auto& value) { h5::write_attribute(root, name, value); });
}

void write_settings(h5::hid root, const Settings& settings) {
  auto top = h5::create_group(root, "settings");
  std::map<std::string, h5::Handle> sections;
  for (const Setting& s : settings.entries) {
    h5::hid g = top.get();
    if (!s.section.empty()) {
      auto it = sections.find(s.section);
      if (it == sections.end()) it = sections.emplace(s.section, h5::create_group(top.get(), s.section)).first;
      g = it->second.get();
    }
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, std::vector<double>>) h5::write_attribute(g, s.key, std::span<const double>(v));
          else h5::write_attribute(g, s.key, v);
        },
        s.value);
  }
}

void write_records(h5::hid root, const RecordTable& t) {
  auto g = h5::create_group(root, "records");
  h5::write_strings(g.get(), "id", t.id);
  h5::write_strings(g.get(), "name", t.name);
  h5::write_strings(g.get(), "source", t.source);
  h5::write_strings(g.get(), "note", t.note);
  h5::write_dataset(g.get(), "synthetic", t.synthetic);
  h5::write_dataset(g.get(), "dt", t.dt);
  h5::write_dataset(g.get(), "duration", t.duration);
  h5::write_dataset(g.get(), "pga_g", t.pga_g);
  h5::write_dataset(g.get(), "npts", t.npts);
}

void write_models(h5::hid root, const ModelTable& t) {
  auto g = h5::create_group(root, "models");
  for (const auto& [name, member] : model_doubles) h5::write_dataset(g.get(), std::string(name), t.*member);
  h5::write_dataset(g.get(), "i1", t.i1);
  h5::write_dataset(g.get(), "i2", t.i2);
  h5::write_dataset(g.get(), "sample", t.sample);
  h5::write_dataset(g.get(), "periods", t.periods);
  h5::write_dataset(g.get(), "periods1", t.periods1);
  h5::write_dataset(g.get(), "periods2", t.periods2);
  h5::write_attribute(g.get(), "zeta", t.zeta);
}

// A field group starts with its shape (and, for lane x gap fields, its gap axis) when first met.
h5::hid field_group(h5::hid root, const Results& r, const FieldSpec& spec, std::map<std::string, h5::Handle>& groups) {
  const std::string name(spec.group);
  if (auto it = groups.find(name); it != groups.end()) return it->second.get();
  auto g = h5::create_group(root, name);
  const bool gaps = spec.extent == Extent::lane_gap;
  h5::write_attribute(g.get(), "shape", std::string(gaps ? "[records, models, gaps]" : "[records, models]"));
  if (gaps) h5::write_dataset(g.get(), "gap_ratios", r.gap_ratios);
  return groups.emplace(name, std::move(g)).first->second.get();
}

void write_fields(h5::hid root, const Results& r) {
  std::map<std::string, h5::Handle> groups;
  for (const Field& f : r.fields) {
    const h5::hid g = field_group(root, r, f.spec, groups);
    const std::string name(f.spec.name);
    std::visit(
        [&](const auto& v) {
          using T = typename std::decay_t<decltype(v)>::value_type;
          if constexpr (std::is_same_v<T, double>) {
            if (f.spec.matrix) return h5::write_dataset(g, name, v, r.record_count(), r.model_count());
          }
          h5::write_dataset(g, name, std::span<const T>(v));
        },
        f.data);
  }
}

}  // namespace

void write(const std::string& path, const Results& r) {
  h5::AtomicFile f(path);
  const auto root = f.root();
  write_header_start(root, r.header);
  write_settings(root, r.settings);
  write_header_end(root, r.header);
  write_records(root, r.records);
  write_models(root, r.models);
  write_fields(root, r);
  f.commit();
}

}  // namespace pounding::results
