// Data-sheet YAML files: strict parsing (schema version, known keys, units, dimensions, ranges)
// with every error located at its file, line and column.
#include "sigmatau/spec.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

// Dimensions not in units.hpp's dim:: list.
constexpr Dimension kAngularRatePerKelvin{2, 0, -2, -2, 0};   // rad/s/K
constexpr Dimension kAccelerationPerKelvin{0, 2, -4, -2, 0};  // m/s^2/K
constexpr Dimension kPerKelvin{0, 0, 0, -2, 0};               // 1/K
constexpr Dimension kRatePerAcceleration{2, -2, 2, 0, 0};     // (rad/s)/(m/s^2)

constexpr std::array<SpecFieldInfo, 17> kGyroFields{{
    {SpecField::noise_density, "noise_density", "rate noise density (spectrum ASD as printed)",
     dim::angle_random_walk, true},
    {SpecField::random_walk, "angle_random_walk", "angle random walk (Allan N)",
     dim::angle_random_walk, true},
    {SpecField::bias_instability, "bias_instability", "in-run bias stability (ADEV floor)",
     dim::angular_rate, true},
    {SpecField::rate_random_walk, "rate_random_walk", "rate random walk K",
     dim::gyro_rate_random_walk, true},
    {SpecField::rms_noise, "rms_noise", "total RMS noise in the stated band", dim::angular_rate,
     true},
    {SpecField::initial_bias, "initial_bias", "initial bias / zero-rate offset", dim::angular_rate,
     false},
    {SpecField::bias_over_temperature, "bias_over_temperature",
     "bias variation over the temperature range", dim::angular_rate, false},
    {SpecField::bias_temperature_coefficient, "bias_temperature_coefficient",
     "bias temperature coefficient", kAngularRatePerKelvin, false},
    {SpecField::sensitivity_error, "sensitivity_error", "sensitivity / scale-factor error",
     dim::dimensionless, false},
    {SpecField::sensitivity_temperature_coefficient, "sensitivity_temperature_coefficient",
     "sensitivity temperature coefficient", kPerKelvin, false},
    {SpecField::cross_axis_sensitivity, "cross_axis_sensitivity", "cross-axis sensitivity",
     dim::dimensionless, false},
    {SpecField::misalignment, "misalignment", "axis misalignment", dim::angle, false},
    {SpecField::nonlinearity, "nonlinearity", "nonlinearity", dim::dimensionless, false},
    {SpecField::g_sensitivity, "g_sensitivity", "linear-acceleration sensitivity",
     kRatePerAcceleration, false},
    {SpecField::full_scale, "full_scale", "full-scale range", dim::angular_rate, true},
    {SpecField::output_data_rate, "output_data_rate", "output data rate", dim::frequency, true},
    {SpecField::bandwidth, "bandwidth", "bandwidth", dim::frequency, true},
}};

constexpr std::array<SpecFieldInfo, 16> kAccelFields{{
    {SpecField::noise_density, "noise_density", "acceleration noise density (spectrum ASD)",
     dim::velocity_random_walk, true},
    {SpecField::random_walk, "velocity_random_walk", "velocity random walk (Allan N)",
     dim::velocity_random_walk, true},
    {SpecField::bias_instability, "bias_instability", "in-run bias stability (ADEV floor)",
     dim::acceleration, true},
    {SpecField::rate_random_walk, "rate_random_walk", "acceleration random walk K",
     dim::accel_rate_random_walk, true},
    {SpecField::rms_noise, "rms_noise", "total RMS noise in the stated band", dim::acceleration,
     true},
    {SpecField::initial_bias, "initial_bias", "initial bias / zero-g offset", dim::acceleration,
     false},
    {SpecField::bias_over_temperature, "bias_over_temperature",
     "bias variation over the temperature range", dim::acceleration, false},
    {SpecField::bias_temperature_coefficient, "bias_temperature_coefficient",
     "bias temperature coefficient", kAccelerationPerKelvin, false},
    {SpecField::sensitivity_error, "sensitivity_error", "sensitivity / scale-factor error",
     dim::dimensionless, false},
    {SpecField::sensitivity_temperature_coefficient, "sensitivity_temperature_coefficient",
     "sensitivity temperature coefficient", kPerKelvin, false},
    {SpecField::cross_axis_sensitivity, "cross_axis_sensitivity", "cross-axis sensitivity",
     dim::dimensionless, false},
    {SpecField::misalignment, "misalignment", "axis misalignment", dim::angle, false},
    {SpecField::nonlinearity, "nonlinearity", "nonlinearity", dim::dimensionless, false},
    {SpecField::full_scale, "full_scale", "full-scale range", dim::acceleration, true},
    {SpecField::output_data_rate, "output_data_rate", "output data rate", dim::frequency, true},
    {SpecField::bandwidth, "bandwidth", "bandwidth", dim::frequency, true},
}};

/// The largest magnitude a printed value may have in SI. No sensor quantity comes near it (a
/// full scale of 1e5 deg/s is 2e3 rad/s, an output rate of 1e6 Hz), while the conversions square
/// values and multiply them by rates and times: a 1e308 typed by mistake became inf and null in
/// the filter files. A value above it is a typo or a unit slip.
constexpr double kLargestValueSi = 1e100;

constexpr std::array<std::string_view, 4> kGrades{"consumer", "industrial", "tactical",
                                                  "navigation"};

/// Parsing context: the file name and helpers that throw located errors.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& message) const {
    const YAML::Mark mark = node.Mark();
    fail_at(mark.line + 1, mark.column + 1, message);
  }
  [[noreturn]] void fail_at(std::int64_t line, std::int64_t column,
                            const std::string& message) const {
    throw ParseError(file_, line, column, message);
  }

  /// The keys of a map node, checked against `allowed` (unknown and repeated keys are errors).
  void check_keys(const YAML::Node& map, const std::string& where,
                  const std::vector<std::string_view>& allowed) const {
    std::set<std::string> seen;
    for (const auto& item : map) {
      // A key that is itself a list or map (found by fuzzing) is a schema error, not a crash.
      if (!item.first.IsScalar()) fail(item.first, prefix(where) + "found a non-text key, expected a field name");
      const std::string key = item.first.as<std::string>();
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        std::string list;
        for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        fail(item.first, prefix(where) + "found unknown key \"" + key + "\", expected one of " +
                             list);
      }
      if (!seen.insert(key).second) {
        fail(item.first, prefix(where) + "found key \"" + key + "\" twice, expected it once");
      }
    }
  }

  static std::string prefix(const std::string& where) { return where.empty() ? "" : where + ": "; }

  std::string scalar(const YAML::Node& node, const std::string& field) const {
    if (!node.IsScalar()) fail(node, field + ": found a " + kind(node) + ", expected a scalar");
    return node.Scalar();
  }

  static std::string kind(const YAML::Node& node) {
    if (node.IsMap()) return "map";
    if (node.IsSequence()) return "list";
    if (node.IsNull()) return "empty value";
    return "scalar";
  }

  PrintedValue printed(const YAML::Node& node, const SpecFieldInfo& info,
                       const std::string& field) const {
    PrintedValue v;
    v.text = scalar(node, field);
    const YAML::Mark mark = node.Mark();
    v.line = mark.line + 1;
    v.column = mark.column + 1;
    std::string_view rest = v.text;
    auto trim_front = [&rest] {
      while (!rest.empty() && (rest.front() == ' ' || rest.front() == '\t')) rest.remove_prefix(1);
    };
    trim_front();
    constexpr std::string_view kPlusMinus = "\u00b1";  // ±
    std::int64_t skipped_columns = 0;
    if (rest.starts_with(kPlusMinus)) {
      v.plus_minus = true;
      rest.remove_prefix(kPlusMinus.size());
      skipped_columns = 1;
    } else if (rest.starts_with("+-")) {
      v.plus_minus = true;
      rest.remove_prefix(2);
      skipped_columns = 2;
    }
    trim_front();
    const std::string body(rest);
    // The number as printed, then the unit text after it.
    const char* begin = body.c_str();
    char* end = nullptr;
    errno = 0;
    const double number = std::strtod(begin, &end);
    if (end == begin || !(std::isfinite(number))) {
      fail_at(v.line, v.column, field + ": found \"" + v.text +
                                    "\", expected a number with its unit as printed (e.g. \"" +
                                    example(info) + "\")");
    }
    v.number = number;
    std::string unit(end);
    const auto first = unit.find_first_not_of(" \t");
    unit = first == std::string::npos ? "" : unit.substr(first);
    while (!unit.empty() && (unit.back() == ' ' || unit.back() == '\t')) unit.pop_back();
    v.unit = unit;
    if (unit.empty()) {
      fail_at(v.line, v.column, field + ": found \"" + v.text +
                                    "\" without a unit, expected a number with its unit as "
                                    "printed (e.g. \"" +
                                    example(info) + "\")");
    }
    try {
      v.value_si = parse_quantity_as(body, info.dimension, field);
    } catch (const UnitError& e) {
      // body is a suffix of the text; the ± sign is two bytes but one column.
      const auto prefix_bytes = static_cast<std::int64_t>(v.text.size() - body.size());
      const std::int64_t prefix_columns = prefix_bytes - (skipped_columns == 1 ? 1 : 0);
      const std::int64_t column =
          e.column() > 0 ? v.column + prefix_columns + static_cast<std::int64_t>(e.column()) - 1
                         : v.column;
      fail_at(v.line, column, e.what());
    }
    if (!(v.number >= 0) || !(v.value_si >= 0)) {
      fail_at(v.line, v.column, field + ": found " + v.text +
                                    ", expected a magnitude >= 0 (write a symmetric bound as ±X)");
    }
    if (info.positive && !(v.value_si > 0)) {
      fail_at(v.line, v.column, field + ": found " + v.text + ", expected a value > 0");
    }
    if (!std::isfinite(v.value_si)) {
      fail_at(v.line, v.column, field + ": found " + v.text + ", expected a finite value");
    }
    if (!(v.value_si <= kLargestValueSi)) {
      char limit[32];
      std::snprintf(limit, sizeof limit, "%g", kLargestValueSi);
      fail_at(v.line, v.column,
              field + ": found " + v.text + ", expected a value below " + limit + " " +
                  si_unit_string(info.dimension) +
                  " (no sensor comes near it: a typo or a unit slip?)");
    }
    return v;
  }

  static std::string example(const SpecFieldInfo& info) {
    if (info.dimension == dim::dimensionless) return "0.5 %";
    return "1 " + si_unit_string(info.dimension);
  }

 private:
  std::string file_;
};

SpecSource parse_source(const Reader& r, const std::string& id, const YAML::Node& node) {
  const std::string where = "sources." + id;
  if (!node.IsMap()) r.fail(node, where + ": found a " + Reader::kind(node) + ", expected a map");
  r.check_keys(node, where, {"document", "revision", "kind", "url", "note"});
  SpecSource s;
  s.id = id;
  if (!node["document"]) r.fail(node, where + ": found no document, expected document: TITLE");
  s.document = r.scalar(node["document"], where + ".document");
  if (!node["kind"]) r.fail(node, where + ": found no kind, expected kind: primary | secondary");
  const std::string kind = r.scalar(node["kind"], where + ".kind");
  if (kind == "primary") {
    s.primary = true;
  } else if (kind != "secondary") {
    r.fail(node["kind"], where + ".kind: found \"" + kind + "\", expected primary or secondary");
  }
  if (node["revision"]) s.revision = r.scalar(node["revision"], where + ".revision");
  if (s.primary && s.revision.empty()) {
    r.fail(node, where + ": found a primary source without revision, expected revision: REV");
  }
  if (node["url"]) s.url = r.scalar(node["url"], where + ".url");
  if (node["note"]) s.note = r.scalar(node["note"], where + ".note");
  return s;
}

SpecValue parse_value(const Reader& r, const YAML::Node& key, const YAML::Node& node,
                      const SpecFieldInfo& info, const std::string& where,
                      const std::map<std::string, SpecSource>& sources) {
  if (!node.IsMap()) {
    r.fail(node, where + ": found a " + Reader::kind(node) +
                     ", expected a map with typ / max / min / options and source");
  }
  r.check_keys(node, where, {"min", "typ", "max", "options", "condition", "note", "source", "page",
                             "table", "axes"});
  SpecValue v;
  v.line = key.Mark().line + 1;
  if (node["min"]) v.min = r.printed(node["min"], info, where + ".min");
  if (node["typ"]) v.typ = r.printed(node["typ"], info, where + ".typ");
  if (node["max"]) v.max = r.printed(node["max"], info, where + ".max");
  if (const auto options = node["options"]) {
    if (!options.IsSequence() || options.size() == 0) {
      r.fail(options, where + ".options: found a " + Reader::kind(options) +
                          ", expected a non-empty list of values");
    }
    for (std::size_t i = 0; i < options.size(); ++i) {
      v.options.push_back(
          r.printed(options[i], info, where + ".options[" + std::to_string(i) + "]"));
    }
  }
  if (!v.min && !v.typ && !v.max && v.options.empty()) {
    r.fail(node, where + ": found no value, expected at least one of typ, max, min, options");
  }
  auto order = [&](const std::optional<PrintedValue>& low, const std::optional<PrintedValue>& high,
                   std::string_view low_name, std::string_view high_name) {
    if (low && high && !(low->value_si <= high->value_si)) {
      r.fail_at(high->line, high->column,
                where + ": found " + std::string(low_name) + " " + low->text + " > " +
                    std::string(high_name) + " " + high->text + ", expected " +
                    std::string(low_name) + " <= " + std::string(high_name));
    }
  };
  order(v.typ, v.max, "typ", "max");
  order(v.min, v.typ, "min", "typ");
  order(v.min, v.max, "min", "max");
  if (const auto axes = node["axes"]) {
    if (!axes.IsMap() || axes.size() == 0) {
      r.fail(axes, where + ".axes: found a " + Reader::kind(axes) +
                       ", expected a map of x / y / z to the values printed for that axis");
    }
    r.check_keys(axes, where + ".axes", {"x", "y", "z"});
    for (const auto& item : axes) {
      AxisValue a;
      a.axis = item.first.as<std::string>();
      const std::string at = where + ".axes." + a.axis;
      if (!item.second.IsMap()) {
        r.fail(item.second, at + ": found a " + Reader::kind(item.second) +
                                ", expected a map with typ / max / min (and condition)");
      }
      r.check_keys(item.second, at, {"min", "typ", "max", "condition"});
      if (item.second["min"]) a.min = r.printed(item.second["min"], info, at + ".min");
      if (item.second["typ"]) a.typ = r.printed(item.second["typ"], info, at + ".typ");
      if (item.second["max"]) a.max = r.printed(item.second["max"], info, at + ".max");
      if (!a.min && !a.typ && !a.max) {
        r.fail(item.second, at + ": found no value, expected at least one of typ, max, min");
      }
      order(a.typ, a.max, "typ", "max");
      order(a.min, a.typ, "min", "typ");
      order(a.min, a.max, "min", "max");
      if (item.second["condition"])
        a.condition = r.scalar(item.second["condition"], at + ".condition");
      v.axes.push_back(std::move(a));
    }
  }
  if (node["condition"]) v.condition = r.scalar(node["condition"], where + ".condition");
  if (node["note"]) v.note = r.scalar(node["note"], where + ".note");
  if (node["page"]) v.page = r.scalar(node["page"], where + ".page");
  if (node["table"]) v.table = r.scalar(node["table"], where + ".table");
  if (!node["source"]) {
    r.fail(key, where + ": found no source, expected source: ID (a key of sources:)");
  }
  const std::string id = r.scalar(node["source"], where + ".source");
  const auto it = sources.find(id);
  if (it == sources.end()) {
    std::string list;
    for (const auto& [k, s] : sources) list += (list.empty() ? "" : ", ") + k;
    r.fail(node["source"], where + ".source: found \"" + id + "\", expected one of the sources (" +
                               list + ")");
  }
  v.source = it->second;
  if (v.source.primary && v.page.empty() && v.table.empty()) {
    r.fail(key, where + ": found a primary source without page or table, expected page: N or "
                        "table: NAME");
  }
  return v;
}

SensorSheet parse_sensor(const Reader& r, const YAML::Node& node, Sensor sensor,
                         const std::map<std::string, SpecSource>& sources) {
  const std::string name(to_string(sensor));
  if (!node.IsMap()) r.fail(node, name + ": found a " + Reader::kind(node) + ", expected a map");
  std::vector<std::string_view> keys;
  for (const auto& info : spec_fields(sensor)) keys.push_back(info.key);
  r.check_keys(node, name, keys);
  SensorSheet sheet;
  for (const auto& item : node) {
    const std::string key = item.first.as<std::string>();
    const auto fields = spec_fields(sensor);
    const auto info = std::find_if(fields.begin(), fields.end(),
                                   [&](const SpecFieldInfo& f) { return f.key == key; });
    sheet.values[info->field] =
        parse_value(r, item.first, item.second, *info, name + "." + key, sources);
  }
  return sheet;
}

}  // namespace

SpecValue SpecValue::for_axis(std::string_view axis) const {
  SpecValue v = *this;
  v.axes.clear();
  for (const AxisValue& a : axes) {
    if (a.axis != axis) continue;
    v.min = a.min;
    v.typ = a.typ;
    v.max = a.max;
    if (!a.condition.empty()) v.condition = a.condition;
  }
  return v;
}

const PrintedValue* SpecValue::limit() const {
  if (max) return &*max;
  if (typ) return &*typ;
  return nullptr;
}

const PrintedValue* SpecValue::nominal() const {
  if (typ) return &*typ;
  if (max) return &*max;
  if (min) return &*min;
  return nullptr;
}

std::span<const SpecFieldInfo> spec_fields(Sensor sensor) {
  if (sensor == Sensor::gyro) return kGyroFields;
  return kAccelFields;
}

const SpecFieldInfo* spec_field_info(Sensor sensor, SpecField field) {
  for (const auto& info : spec_fields(sensor)) {
    if (info.field == field) return &info;
  }
  return nullptr;
}

const SpecValue* SensorSheet::find(SpecField field) const {
  const auto it = values.find(field);
  return it == values.end() ? nullptr : &it->second;
}

const SensorSheet* DataSheet::sensor(Sensor which) const {
  const auto& s = which == Sensor::gyro ? gyro : accel;
  return s ? &*s : nullptr;
}

std::string DataSheet::label() const {
  return "data sheet " + name + " (" + manufacturer + " " + part + ")";
}

DataSheet parse_data_sheet(std::string_view yaml_text, const std::string& file) {
  const Reader r(file);
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml_text));
  } catch (const YAML::Exception& e) {
    r.fail_at(e.mark.line + 1, e.mark.column + 1, "not valid YAML: " + e.msg);
  }
  if (!root.IsMap()) {
    r.fail_at(1, 0, "found a " + Reader::kind(root) +
                        ", expected a map with schema, manufacturer, part, grade, sources, gyro, "
                        "accel");
  }
  r.check_keys(root, "", {"schema", "manufacturer", "part", "grade", "description", "notes",
                          "sources", "gyro", "accel"});
  DataSheet sheet;
  sheet.file = file;
  sheet.name = std::filesystem::path(file).stem().string();
  const auto schema = root["schema"];
  if (!schema) {
    r.fail_at(1, 0, "schema: found no schema key, expected schema: " +
                        std::to_string(kSpecSchemaVersion));
  }
  const std::string version = r.scalar(schema, "schema");
  if (version != std::to_string(kSpecSchemaVersion)) {
    r.fail(schema, "schema: found version \"" + version + "\", expected " +
                       std::to_string(kSpecSchemaVersion) +
                       " (the only version this sigmatau reads)");
  }
  auto required = [&](const char* key) {
    if (!root[key]) {
      r.fail_at(1, 0, std::string(key) + ": found no " + key + " key, expected " + key + ": TEXT");
    }
    return r.scalar(root[key], key);
  };
  sheet.manufacturer = required("manufacturer");
  sheet.part = required("part");
  sheet.grade = required("grade");
  if (std::find(kGrades.begin(), kGrades.end(), sheet.grade) == kGrades.end()) {
    r.fail(root["grade"], "grade: found \"" + sheet.grade +
                              "\", expected consumer, industrial, tactical or navigation");
  }
  if (root["description"]) sheet.description = r.scalar(root["description"], "description");
  if (root["notes"]) sheet.notes = r.scalar(root["notes"], "notes");
  const auto sources = root["sources"];
  if (!sources || !sources.IsMap() || sources.size() == 0) {
    if (sources) r.fail(sources, "sources: found a " + Reader::kind(sources) + ", expected a map");
    r.fail_at(1, 0, "sources: found no sources key, expected a map of ID: {document, kind, ...}");
  }
  {
    std::set<std::string> seen;
    for (const auto& item : sources) {
      const std::string id = item.first.as<std::string>();
      if (!seen.insert(id).second) {
        r.fail(item.first, "sources: found key \"" + id + "\" twice, expected it once");
      }
      sheet.sources[id] = parse_source(r, id, item.second);
    }
  }
  if (root["gyro"]) sheet.gyro = parse_sensor(r, root["gyro"], Sensor::gyro, sheet.sources);
  if (root["accel"]) sheet.accel = parse_sensor(r, root["accel"], Sensor::accel, sheet.sources);
  if (!sheet.gyro && !sheet.accel) {
    r.fail_at(1, 0, "found neither gyro nor accel, expected at least one sensor section");
  }
  return sheet;
}

DataSheet load_data_sheet(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error("cannot open data sheet " + file.string());
  std::ostringstream text;
  text << in.rdbuf();
  return parse_data_sheet(text.str(), file.string());
}

std::vector<std::filesystem::path> list_data_sheets(const std::filesystem::path& directory) {
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(directory, ec)) {
    if (entry.is_regular_file() && entry.path().extension() == ".yaml") {
      files.push_back(entry.path());
    }
  }
  if (ec) throw Error("cannot list data sheets in " + directory.string() + ": " + ec.message());
  std::sort(files.begin(), files.end());
  return files;
}

std::filesystem::path find_data_sheet(std::string_view name_or_path,
                                      const std::filesystem::path& directory) {
  const std::filesystem::path direct{std::string(name_or_path)};
  std::error_code ec;
  if (std::filesystem::is_regular_file(direct, ec)) return direct;
  for (const auto& candidate :
       {directory / direct, directory / (std::string(name_or_path) + ".yaml")}) {
    if (std::filesystem::is_regular_file(candidate, ec)) return candidate;
  }
  throw Error("no data sheet \"" + std::string(name_or_path) + "\" (looked for the file and for " +
              (directory / (std::string(name_or_path) + ".yaml")).string() +
              "; `sigmatau specs list` shows the names)");
}

}  // namespace sigmatau
