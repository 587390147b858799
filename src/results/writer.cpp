// Writes Results to an HDF5 file (format 3 with /system, else format 2), built in a temporary and renamed.
#include "pounding/results/writer.hpp"

#include <cstring>
#include <map>
#include <stdexcept>
#include <type_traits>

#include <fmt/format.h>

#include "pounding/io/hdf5.hpp"
#include "pounding/results/describe.hpp"

namespace pounding::results {

namespace {

// HDF5 keeps an attribute in its object's header, at most 64 KiB: a hazard table of 8,200 rows, 9,000 levels or gap
// ratios, a long study text do not fit. Such a value is written as a dataset of the same name in the same group,
// marked with the attribute `stored_attribute` (its kind: "numbers", "string", "strings"); the reader puts it back
// among the attributes (reader.cpp). Smaller values stay attributes, as in every earlier file.
constexpr std::size_t attribute_limit = 16 << 10;  // bytes; well below 64 KiB with the message's own overhead

void mark_stored_attribute(h5::hid g, const std::string& key, const char* kind) {
  auto ds = h5::open_dataset(g, key);
  h5::write_attribute(ds.get(), "stored_attribute", std::string(kind));
  h5::write_attribute(ds.get(), "units", std::string("those of the setting or attribute it holds"));
  h5::write_attribute(ds.get(), "description",
                      std::string("an attribute too large for HDF5's 64 KiB attribute limit, stored as a dataset"));
}

void write_value(h5::hid g, const std::string& key, const SettingValue& value) {
  std::visit(
      [&](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::vector<double>>) {
          if (v.size() * sizeof(double) > attribute_limit) {
            h5::write_dataset(g, key, std::span<const double>(v));
            mark_stored_attribute(g, key, "numbers");
          } else {
            h5::write_attribute(g, key, std::span<const double>(v));
          }
        } else if constexpr (std::is_same_v<T, std::string>) {
          if (v.size() > attribute_limit) {
            h5::write_strings(g, key, std::vector<std::string>{v});
            mark_stored_attribute(g, key, "string");
          } else {
            h5::write_attribute(g, key, v);
          }
        } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
          std::size_t n = 0;
          for (const auto& s : v) n += s.size() + 16;
          if (n > attribute_limit) {
            h5::write_strings(g, key, v);
            mark_stored_attribute(g, key, "strings");
          } else {
            h5::write_attribute(g, key, v);
          }
        } else {
          h5::write_attribute(g, key, v);
        }
      },
      value);
}

// `version`: the layout written (format 2 for an SDOF pair, 3 with /system), whatever the Header says.
void write_header_start(h5::hid root, const Header& h, std::int64_t version) {
  visit_header_start(h, [&](const char* name, const auto& value) {
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, std::int64_t>)
      if (std::string_view(name) == "format_version") {
        h5::write_attribute(root, name, version);
        return;
      }
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, std::string>) write_value(root, name, value);  // long texts
    else h5::write_attribute(root, name, value);
  });
}

void write_header_end(h5::hid root, const Header& h) {
  visit_header_end(h, [&](const char* name, const auto& value) {
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, std::string>) write_value(root, name, value);
    else h5::write_attribute(root, name, value);
  });
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
    write_value(g, s.key, s.value);
  }
}

// The dataset's `units` and `description`; a dataset without them is a programming error (describe.hpp).
void label(h5::hid g, std::string_view group, const std::string& name, const Description& d) {
  if (d.units.empty() || d.description.empty())
    throw std::logic_error(fmt::format("results: /{}/{} has no units or description: give it a row in "
                                       "src/results/describe.cpp (or its schema row)",
                                       group, name));
  auto ds = h5::open_dataset(g, name);
  h5::write_attribute(ds.get(), "units", std::string(d.units));
  h5::write_attribute(ds.get(), "description", std::string(d.description));
}
void label(h5::hid g, std::string_view group, const std::string& name) {
  label(g, group, name, describe(group, name).value_or(Description{}));
}

// Every dataset of /<group>, labelled from the group's table after it is written: a dataset added to the group
// without a row in describe.cpp is refused.
// A metres axis' /gaps/metres has its own description (describe_metres_axis).
void label_group(h5::hid root, std::string_view group, bool metres_axis = false) {
  auto g = h5::open_group(root, std::string(group));
  for (const std::string& name : h5::member_names(g.get()))
    if (metres_axis && group == "gaps") label(g.get(), group, name, describe_metres_axis(name).value_or(Description{}));
    else label(g.get(), group, name);
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
  if (!t.polarity.empty()) h5::write_dataset(g.get(), "polarity", t.polarity);
}

void write_models(h5::hid root, const ModelTable& t) {
  auto g = h5::create_group(root, "models");
  // [outputs] per_model = false: no per-model values, only the period grids below
  for (const auto& [name, member] : model_doubles)
    if (!(t.*member).empty()) h5::write_dataset(g.get(), std::string(name), t.*member);
  if (!t.i1.empty()) {
    h5::write_dataset(g.get(), "i1", t.i1);
    h5::write_dataset(g.get(), "i2", t.i2);
    h5::write_dataset(g.get(), "sample", t.sample);
  }
  h5::write_dataset(g.get(), "periods", t.periods);
  h5::write_dataset(g.get(), "periods1", t.periods1);
  h5::write_dataset(g.get(), "periods2", t.periods2);
  h5::write_attribute(g.get(), "zeta", t.zeta);
  for (std::size_t b = 0; b < t.row.size(); ++b)  // a row's buildings 3..n
    for (const auto& [prefix, member] : row_model_doubles)
      h5::write_dataset(g.get(), std::string(prefix) + std::to_string(b + 3), t.row[b].*member);
}

// /gaps/ratios [gaps] (a metres axis: /gaps/axis and the attribute unit = "m") and /gaps/metres [models, gaps].
void write_gaps(h5::hid root, const GapTable& t, std::size_t models) {
  if (t.ratios.empty()) return;
  auto g = h5::create_group(root, "gaps");
  if (t.in_metres) h5::write_attribute(g.get(), "unit", std::string("m"));
  h5::write_dataset(g.get(), t.in_metres ? "axis" : "ratios", t.ratios);
  if (models == 0) return;  // [outputs] per_model = false: no models, no metres
  const std::size_t dims[] = {models, t.ratios.size()};
  h5::write_dataset(g.get(), "metres", std::span<const double>(t.metres), dims);
}

// [outputs] per_model = "stream": /models' per-model datasets and /gaps/metres from Results::model_rows, every
// dataset a window of models at a time (each model drawn once), the same datasets write_models and write_gaps give.
void write_streamed_models(h5::hid root, const Results& r) {
  const std::size_t M = r.streamed_models, G = r.gaps.ratios.size();
  const auto models = h5::open_group(root, "models");
  std::vector<h5::RowsDataset> sets;
  for (const auto& [name, member] : model_doubles) sets.push_back({models.get(), std::string(name), h5::Type::f64, {M}});
  sets.push_back({models.get(), "i1", h5::Type::i32, {M}});
  sets.push_back({models.get(), "i2", h5::Type::i32, {M}});
  sets.push_back({models.get(), "sample", h5::Type::i64, {M}});
  h5::Handle gaps;
  if (G) {
    gaps = h5::open_group(root, "gaps");
    sets.push_back({gaps.get(), "metres", h5::Type::f64, {M, G}});
  }
  h5::write_datasets(sets, [&](std::size_t first, std::size_t n, std::span<void* const> out) {
    ModelTable t;
    r.model_rows(first, n, t);
    std::size_t k = 0;
    const auto put = [&](const auto& v) {
      if (v.size() != n) throw std::logic_error("results: model_rows filled a column with the wrong count");
      std::memcpy(out[k++], v.data(), n * sizeof(v[0]));
    };
    for (const auto& [name, member] : model_doubles) put(t.*member);
    put(t.i1), put(t.i2), put(t.sample);
    if (!G) return;
    auto* metres = static_cast<double*>(out[k]);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t g = 0; g < G; ++g)  // as gap_table
        metres[i * G + g] = r.gaps.in_metres ? r.gaps.ratios[g] : r.gaps.ratios[g] * t.code_gap[i];
  });
}

// The axes of a format-3 field, its dataset's `axes` attribute; "" for the [records, models(, gaps)] extents,
// which the group's `shape` attribute names.
std::string axes(const FieldSpec& s, bool stripes) {
  const char* lead = stripes ? "[stripes, records, models" : "[records, models";
  switch (s.extent) {
    case Extent::lane:
    case Extent::lane_gap: return "";
    case Extent::lane_floor: return fmt::format("{}, floors of building {} (bottom first)]", lead, s.building);
    case Extent::lane_element: return fmt::format("{}, elements]", lead);
    case Extent::lane_gap_element: return fmt::format("{}, gaps, elements]", lead);
    case Extent::lane_gap_floor:
      return fmt::format("{}, gaps, floors of building {} (bottom first)]", lead, s.building);
  }
  return "";
}

// A field group starts with its shape (and, for lane x gap fields, its gap axis) when first met.
h5::hid field_group(h5::hid root, const Results& r, const FieldSpec& spec, std::map<std::string, h5::Handle>& groups) {
  const std::string name(spec.group);
  if (auto it = groups.find(name); it != groups.end()) return it->second.get();
  auto g = h5::create_group(root, name);
  const bool gaps = per_gap(spec.extent);
  const char* lead = r.stripes ? "[stripes, records, models" : "[records, models";
  h5::write_attribute(g.get(), "shape", fmt::format("{}{}]", lead, gaps ? ", gaps" : ""));
  if (r.stripes) h5::write_attribute(g.get(), "stripes", static_cast<std::int64_t>(r.stripes));
  if (gaps) {  // a metres axis ([gaps] metres): gap_axis, in metres
    const char* axis = r.gaps.in_metres ? "gap_axis" : "gap_ratios";
    h5::write_dataset(g.get(), axis, r.gap_ratios);
    label(g.get(), spec.group, axis);
  }
  return groups.emplace(name, std::move(g)).first->second.get();
}

// Every field with the shape of its extent, [records, models] or [records, models, gaps], after [stripes] in a
// fragility study.
void write_fields(h5::hid root, const Results& r) {
  std::map<std::string, h5::Handle> groups;
  for (const Field& f : r.fields) {
    const h5::hid g = field_group(root, r, f.spec, groups);
    const std::string name(f.spec.name);
    std::vector<std::size_t> shape;
    if (r.stripes) shape.push_back(r.stripes);
    shape.insert(shape.end(), {r.record_count(), r.model_count()});
    if (per_gap(f.spec.extent)) shape.push_back(r.gap_ratios.size());
    if (f.spec.extent != Extent::lane && f.spec.extent != Extent::lane_gap) shape.push_back(f.spec.count);
    std::visit(
        [&](const auto& v) {
          using T = typename std::decay_t<decltype(v)>::value_type;
          if (!f.source) return h5::write_dataset(g, name, std::span<const T>(v), std::span<const std::size_t>(shape));
          constexpr h5::Type type = std::is_same_v<T, double>         ? h5::Type::f64
                                    : std::is_same_v<T, std::int64_t> ? h5::Type::i64
                                    : std::is_same_v<T, std::int32_t> ? h5::Type::i32
                                                                      : h5::Type::u8;
          h5::write_dataset(g, name, type, std::span<const std::size_t>(shape), f.source);
        },
        f.data);
    label(g, f.spec.group, name, {f.spec.units, f.spec.description});
    if (const std::string a = axes(f.spec, r.stripes > 0); !a.empty())
      h5::write_attribute(h5::open_dataset(g, name).get(), "axes", a);
  }
}

// Format 3: /system, every dataset labelled from describe.cpp's table.
void write_system(h5::hid root, const SystemTable& t) {
  auto g = h5::create_group(root, "system");
  h5::write_attribute(g.get(), "buildings", static_cast<std::int64_t>(t.building_label.size()));
  h5::write_attribute(g.get(), "elements", static_cast<std::int64_t>(t.element_label.size()));
  visit_system(t, [&](const char* name, const auto& v) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    if constexpr (std::is_same_v<T, std::string>) h5::write_strings(g.get(), name, v);
    else h5::write_dataset(g.get(), name, std::span<const T>(v));
  });
  label_group(root, "system");
}

// The writer's refusal (std::logic_error, before any file exists): a SystemTable that contradicts itself,
// per-floor or per-element fields without one, or whose floors or elements differ from it.
void check_system(const Results& r) {
  const SystemTable& t = r.system;
  if (!t.empty())
    if (const std::string p = t.check(); !p.empty()) throw std::logic_error("results: /system is inconsistent: " + p);
  const Extents x = t.extents();
  for (const Field& f : r.fields) {
    const FieldSpec& s = f.spec;
    if (s.extent == Extent::lane || s.extent == Extent::lane_gap) continue;
    const std::string where = fmt::format("results: /{}/{}", s.group, s.name);
    if (t.empty())
      throw std::logic_error(where + " is per floor or per element but the Results has no /system (SystemTable)");
    if (per_floor(s.extent)) {
      if (s.building < 1 || s.building > x.floors.size())
        throw std::logic_error(fmt::format("{} is for building {} but /system has {} buildings", where, s.building,
                                           x.floors.size()));
      if (s.count != x.floors[s.building - 1])
        throw std::logic_error(fmt::format("{} has {} floors but /system gives building {} {}", where, s.count,
                                           s.building, x.floors[s.building - 1]));
    } else if (s.count != x.elements) {
      throw std::logic_error(fmt::format("{} has {} elements but /system has {}", where, s.count, x.elements));
    }
  }
}

// A module group (results.hpp): marked, its attributes, its datasets with their shapes, units and descriptions, then
// its sub-groups (not marked: the reader finds them under their module group).
void write_group(h5::hid root, const Group& gr, const std::string& path = "") {
  auto g = h5::create_group(root, gr.name);
  const std::string name = path.empty() ? gr.name : path + "/" + gr.name;
  if (path.empty()) h5::write_attribute(g.get(), "module_group", std::int64_t{1});
  for (const auto& [key, value] : gr.attributes) write_value(g.get(), key, value);
  for (const GroupDataset& d : gr.datasets) {
    std::visit(
        [&](const auto& v) {
          using T = typename std::decay_t<decltype(v)>::value_type;
          if constexpr (std::is_same_v<T, std::string>) {
            h5::write_strings(g.get(), d.name, v);
          } else {
            const std::vector<std::size_t> shape = d.shape.empty() ? std::vector<std::size_t>{v.size()} : d.shape;
            h5::write_dataset(g.get(), d.name, std::span<const T>(v), std::span<const std::size_t>(shape));
          }
        },
        d.data);
    label(g.get(), name, d.name, {d.units, d.description});
  }
  for (const Group& child : gr.children) write_group(g.get(), child, name);
}

}  // namespace

Writer::Writer(const std::string& path, const Results& r, bool on_disk) {
  check_system(r);
  file_ = std::make_unique<h5::AtomicFile>(path, on_disk ? h5::AtomicFile::Storage::disk : h5::AtomicFile::Storage::memory);
  const auto root = file_->root();
  try {
    write_header_start(root, r.header, r.system.empty() ? pair_format_version : format_version);
    write_settings(root, r.settings);
    write_records(root, r.records);
    write_models(root, r.models);
    write_gaps(root, r.gaps, r.models.size());
    if (r.model_rows) write_streamed_models(root, r);
    for (const char* group : {"records", "models", "gaps"})
      if (h5::exists(root, group)) label_group(root, group, r.gaps.in_metres);
    write_fields(root, r);  // labelled from their schema rows
    if (!r.system.empty()) write_system(root, r.system);
  } catch (...) {  // on disk (a full disk): the temporary closed and removed now, the OS error named
    file_->fail(std::current_exception());
  }
}

Writer::~Writer() = default;
Writer::Writer(Writer&&) noexcept = default;
Writer& Writer::operator=(Writer&&) noexcept = default;

void Writer::finish(const Results& r) {
  if (!file_) throw std::logic_error("results::Writer::finish called twice");
  const auto root = file_->root();
  try {
    write_header_end(root, r.header);
    for (const Group& g : r.groups) write_group(root, g);
  } catch (...) {
    file_->fail(std::current_exception());
  }
  file_->commit();
  file_.reset();
}

void write(const std::string& path, const Results& r) {
  Writer w(path, r);
  w.finish(r);
}

}  // namespace pounding::results
