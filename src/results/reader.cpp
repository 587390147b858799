// Reads a results file of any format (1, 2, 3) into Results.
#include "pounding/results/reader.hpp"

#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include <fmt/format.h>

#include "pounding/core/error.hpp"
#include "pounding/io/hdf5.hpp"
#include "pounding/results/schema.hpp"

namespace pounding::results {

namespace {

// Readers that leave the default when a file predates the item.
// A dataset that stands for an attribute too large for HDF5's limit (writer.cpp, `stored_attribute`), or "".
std::string stored_attribute_kind(h5::hid g, const std::string& name) {
  if (!h5::exists(g, name) || h5::is_group(g, name)) return "";
  auto ds = h5::open_dataset(g, name);
  return h5::attribute_exists(ds.get(), "stored_attribute") ? h5::read_string_attribute(ds.get(), "stored_attribute") : "";
}

void read_opt(h5::hid obj, const char* name, std::string& v) {
  if (h5::attribute_exists(obj, name)) v = h5::read_string_attribute(obj, name);
  else if (stored_attribute_kind(obj, name) == "string") v = h5::read_strings(obj, name).at(0);
}
void read_opt(h5::hid obj, const char* name, double& v) {
  if (h5::attribute_exists(obj, name)) v = h5::read_double_attribute(obj, name);
}
void read_opt(h5::hid obj, const char* name, std::int64_t& v) {
  if (h5::attribute_exists(obj, name)) v = h5::read_int64_attribute(obj, name);
}
template <class T>
void read_opt(h5::hid g, const char* name, std::vector<T>& v) {
  if (!h5::exists(g, name)) return;
  if constexpr (std::is_same_v<T, std::string>) v = h5::read_strings(g, name);
  else if constexpr (std::is_same_v<T, double>) v = h5::read_doubles(g, name);
  else if constexpr (std::is_same_v<T, std::int64_t>) v = h5::read_int64(g, name);
  else if constexpr (std::is_same_v<T, std::int32_t>) v = h5::read_int32(g, name);
  else v = h5::read_uint8(g, name);
}

Header read_header(h5::hid root) {
  Header h;
  const auto read = [&](const char* name, auto& value) { read_opt(root, name, value); };
  visit_header_start(h, read);
  visit_header_end(h, read);
  return h;
}

void read_section(h5::hid g, const std::string& section, Settings& out) {
  using K = h5::AttributeKind;
  for (const std::string& key : h5::attribute_names(g)) {
    switch (h5::attribute_kind(g, key)) {
      case K::string: out.add(section, key, h5::read_string_attribute(g, key)); break;
      case K::strings: out.add(section, key, h5::read_strings_attribute(g, key)); break;
      case K::number: out.add(section, key, h5::read_double_attribute(g, key)); break;
      case K::numbers: out.add(section, key, h5::read_doubles_attribute(g, key)); break;
      case K::integer: out.add(section, key, h5::read_int64_attribute(g, key)); break;
      case K::integers: out.add(section, key, h5::read_doubles_attribute(g, key)); break;  // never written
      case K::other: break;
    }
  }
  for (const std::string& key : h5::member_names(g)) {  // attributes too large for HDF5's limit, stored as datasets
    const std::string kind = stored_attribute_kind(g, key);
    if (kind == "numbers") out.add(section, key, h5::read_doubles(g, key));
    else if (kind == "string") out.add(section, key, h5::read_strings(g, key).at(0));
    else if (kind == "strings") out.add(section, key, h5::read_strings(g, key));
  }
}

Settings read_settings(h5::hid root) {
  Settings s;
  if (!h5::exists(root, "settings")) return s;
  auto top = h5::open_group(root, "settings");
  read_section(top.get(), "", s);
  for (const std::string& section : h5::member_names(top.get()))
    if (h5::is_group(top.get(), section)) read_section(h5::open_group(top.get(), section).get(), section, s);
  return s;
}

RecordTable read_records(h5::hid root) {
  RecordTable t;
  if (!h5::exists(root, "records")) return t;
  auto g = h5::open_group(root, "records");
  read_opt(g.get(), "id", t.id);
  read_opt(g.get(), "name", t.name);
  read_opt(g.get(), "source", t.source);
  read_opt(g.get(), "note", t.note);
  read_opt(g.get(), "synthetic", t.synthetic);
  read_opt(g.get(), "dt", t.dt);
  read_opt(g.get(), "duration", t.duration);
  read_opt(g.get(), "pga_g", t.pga_g);
  read_opt(g.get(), "npts", t.npts);
  read_opt(g.get(), "polarity", t.polarity);
  return t;
}

// With LoadExtent::report a column outside report_model_columns is probed (h5::read_doubles_if_constant): kept
// when the same for every model, else left empty and named in `varying`.
void read_model_column(h5::hid g, std::string_view name, std::vector<double>& v, LoadExtent extent, ModelTable& t) {
  const std::string n(name);
  const auto& keep = report_model_columns;
  if (extent == LoadExtent::all || std::find(std::begin(keep), std::end(keep), name) != std::end(keep) || !h5::exists(g, n))
    return read_opt(g, n.c_str(), v);
  if (auto c = h5::read_doubles_if_constant(g, n)) v = std::move(*c);
  else t.varying.push_back(n);
}

ModelTable read_models(h5::hid root, LoadExtent extent) {
  ModelTable t;
  if (!h5::exists(root, "models")) return t;
  auto g = h5::open_group(root, "models");
  for (const auto& [name, member] : model_doubles) read_model_column(g.get(), name, t.*member, extent, t);
  read_opt(g.get(), "i1", t.i1);
  read_opt(g.get(), "i2", t.i2);
  read_opt(g.get(), "sample", t.sample);
  read_opt(g.get(), "periods", t.periods);
  read_opt(g.get(), "periods1", t.periods1);
  read_opt(g.get(), "periods2", t.periods2);
  if (t.periods1.empty()) t.periods1 = t.periods;  // written before each building had its grid
  if (t.periods2.empty()) t.periods2 = t.periods;
  read_opt(g.get(), "zeta", t.zeta);
  for (std::size_t K = 3; h5::exists(g.get(), "T" + std::to_string(K)); ++K) {  // a row's buildings 3..n
    ModelTable::RowBuilding b;
    for (const auto& [prefix, member] : row_model_doubles)
      read_opt(g.get(), (std::string(prefix) + std::to_string(K)).c_str(), b.*member);
    t.row.push_back(std::move(b));
  }
  return t;
}

// /gaps, or (a format-1 file) the same table from the study's [gaps] ratios, or the impacts group's gap axis.
GapTable read_gaps(h5::hid root, const Results& r, LoadExtent extent) {
  GapTable t;
  if (h5::exists(root, "gaps")) {
    auto g = h5::open_group(root, "gaps");
    // a metres axis ([gaps] metres): /gaps/axis with the attribute unit = "m"
    t.in_metres = h5::attribute_exists(g.get(), "unit") && h5::read_string_attribute(g.get(), "unit") == "m";
    read_opt(g.get(), t.in_metres ? "axis" : "ratios", t.ratios);
    if (extent == LoadExtent::all) read_opt(g.get(), "metres", t.metres);
    return t;
  }
  if (const SettingValue* v = r.settings.find("gaps", "ratios"); v && std::holds_alternative<std::vector<double>>(*v))
    return gap_table(std::get<std::vector<double>>(*v), r.models.code_gap);
  if (!r.gap_ratios.empty()) return gap_table(r.gap_ratios, r.models.code_gap);
  return t;
}

// Every field of the schema present in the file, in the schema's order; the gap axis with the first
// lane x gap field.
void read_fields(h5::hid root, std::span<const FieldSpec> specs, Results& r) {
  for (const FieldSpec& spec : specs) {
    const std::string group(spec.group), name(spec.name);
    if (!h5::exists(root, group)) continue;
    auto g = h5::open_group(root, group);
    if (!h5::exists(g.get(), name)) continue;
    if (per_gap(spec.extent) && r.gap_ratios.empty()) read_opt(g.get(), "gap_ratios", r.gap_ratios);
    if (per_gap(spec.extent) && r.gap_ratios.empty()) read_opt(g.get(), "gap_axis", r.gap_ratios);  // [gaps] metres
    Column c = make_column(spec, 0);
    std::visit([&](auto& v) { read_opt(g.get(), name.c_str(), v); }, c);
    r.fields.push_back({spec, std::move(c)});
  }
}

// Group `name` under `parent`: its attributes, its datasets, and its sub-groups (their datasets only with
// `child_data`: /histories' series, which the report does not read).
Group read_group(h5::hid parent, const std::string& name, bool data, bool child_data) {
  using K = h5::DatasetKind;
  auto g = h5::open_group(parent, name);
  Group gr{name, {}, {}};
  Settings attrs;
  read_section(g.get(), "", attrs);
  for (auto& a : attrs.entries)
    if (a.key != "module_group") gr.attributes.emplace_back(a.key, std::move(a.value));
  for (const std::string& d : h5::member_names(g.get())) {
    if (h5::is_group(g.get(), d)) {
      gr.children.push_back(read_group(g.get(), d, child_data, child_data));
      continue;
    }
    if (!data || !stored_attribute_kind(g.get(), d).empty()) continue;  // an attribute (read_section has it)
    GroupDataset ds{d, {}, h5::dataset_shape(g.get(), d), {}, {}};
    if (ds.shape.size() <= 1) ds.shape.clear();
    auto h = h5::open_dataset(g.get(), d);
    read_opt(h.get(), "units", ds.units);
    read_opt(h.get(), "description", ds.description);
    switch (h5::dataset_kind(g.get(), d)) {
      case K::strings: ds.data = h5::read_strings(g.get(), d); break;
      case K::f64: ds.data = h5::read_doubles(g.get(), d); break;
      case K::i64: ds.data = h5::read_int64(g.get(), d); break;
      case K::u8: ds.data = h5::read_uint8(g.get(), d); break;
      default: continue;
    }
    gr.datasets.push_back(std::move(ds));
  }
  return gr;
}

// Every group marked `module_group` (results.hpp), in name order.
void read_groups(h5::hid root, Results& r, bool child_data) {
  for (const std::string& name : h5::member_names(root)) {
    if (!h5::is_group(root, name)) continue;
    auto g = h5::open_group(root, name);
    if (!h5::attribute_exists(g.get(), "module_group")) continue;
    r.groups.push_back(read_group(root, name, true, child_data));
  }
}

// Format 3: /system (absent in format 1 and 2: empty).
SystemTable read_system(h5::hid root) {
  SystemTable t;
  if (!h5::exists(root, "system")) return t;
  auto g = h5::open_group(root, "system");
  visit_system(t, [&](const char* name, auto& v) { read_opt(g.get(), name, v); });
  return t;
}

// An HDF5 file that pounding did not write (no integer format_version at its root: h5py's, another program's, an
// empty one) or of a format this build does not know, refused before anything is read from it.
void require_results_file(h5::hid root, const std::string& path) {
  if (!h5::attribute_exists(root, "format_version") ||
      h5::attribute_kind(root, "format_version") != h5::AttributeKind::integer)
    throw InputError(fmt::format("{} is not a pounding results file (an HDF5 file without the integer "
                                 "format_version attribute pounding writes: written by another program)", path),
                     path, "give a results file written by `pounding run STUDY.toml --out R.h5`");
  const std::int64_t v = h5::read_int64_attribute(root, "format_version");
  if (v < 1 || v > format_version)
    throw InputError(
        fmt::format("{} has results format {}; this pounding reads formats 1 to {}", path, v, format_version), path,
        v > format_version ? "read it with the newer pounding that wrote it"
                           : "give a results file written by `pounding run STUDY.toml --out R.h5`");
}

// A results file opened and checked, then read by `read`: an HDF5 or zlib error on the way (a damaged or truncated
// file) becomes an InputError naming the file.
template <class Read>
auto read_results_file(const std::string& path, Read&& read) {
  const h5::Handle f = h5::open_read(path);
  try {
    require_results_file(f.get(), path);
    return read(f.get());
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& e) {  // h5::Error, zlib, an inconsistent /system
    throw InputError(fmt::format("cannot read {}: {}", path, e.what()), path,
                     "the file is damaged or was cut short: rerun the study that wrote it (pounding run), or use an "
                     "intact copy");
  }
}

Results read_results(h5::hid root, const std::string& path, std::span<const FieldSpec> extra, LoadExtent extent);

}  // namespace

Header load_header(const std::string& path) {
  return read_results_file(path, [](h5::hid root) { return read_header(root); });
}

Results load(const std::string& path, std::span<const FieldSpec> extra, LoadExtent extent) {
  return read_results_file(path, [&](h5::hid root) { return read_results(root, path, extra, extent); });
}

namespace {

Results read_results(h5::hid root, const std::string& path, std::span<const FieldSpec> extra, LoadExtent extent) {
  Results r;
  r.path = path;
  r.header = read_header(root);
  r.settings = read_settings(root);
  r.records = read_records(root);
  r.models = read_models(root, extent);
  std::vector<FieldSpec> specs(std::begin(unit_fields), std::end(unit_fields));
  specs.insert(specs.end(), std::begin(derived_fields), std::end(derived_fields));
  specs.push_back(restitution_field);  // [contact] restitution only (absent otherwise: skipped)
  specs.push_back(refine_field);       // [analysis] coarse = "refine" only
  specs.insert(specs.end(), extra.begin(), extra.end());
  r.system = read_system(root);  // format 3: its extents name the per-floor and per-element fields
  if (!r.system.empty()) {
    if (const std::string p = r.system.check(); !p.empty())
      throw std::runtime_error(path + ": /system is inconsistent: " + p);
    const std::vector<FieldSpec> sys = system_fields(r.system.extents(), true);
    specs.insert(specs.end(), sys.begin(), sys.end());
    FieldSpec outside = restitution_element_field;  // [contact] restitution only
    outside.count = static_cast<std::uint32_t>(r.system.extents().elements);
    specs.push_back(outside);
  }
  read_fields(root, specs, r);  // format 1 stored some flat, format 2 with their shape: the values are the same
  r.gaps = read_gaps(root, r, extent);
  if (h5::exists(root, "uncoupled")) {
    auto g = h5::open_group(root, "uncoupled");
    std::int64_t stripes = 0;
    read_opt(g.get(), "stripes", stripes);
    r.stripes = static_cast<std::size_t>(stripes);
  }
  read_groups(root, r, extent == LoadExtent::all);
  return r;
}

}  // namespace

}  // namespace pounding::results
