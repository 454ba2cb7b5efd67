// `sigmatau specs list` and `sigmatau specs show NAME`: the shipped IMU data sheets, every value
// as printed and in SI, with its source.
#include <cstdio>
#include <string>
#include <iostream>
#include <sstream>

#include "sigmatau/error.hpp"
#include "sigmatau/resources.hpp"
#include "sigmatau/spec.hpp"
#include "text_columns.hpp"
#include "verbs.hpp"

namespace sigmatau::cli {
namespace {

struct SpecsArguments {
  std::string dir;   // --dir: overrides the shipped specs directory
  std::string name;  // show NAME
};

std::filesystem::path specs_dir(const SpecsArguments& args) {
  if (!args.dir.empty()) {
    if (!std::filesystem::is_directory(args.dir)) {
      throw Error("--dir " + args.dir + " is not a directory");
    }
    return args.dir;
  }
  return resource_dir("specs");
}

std::string si(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

/// "0.005 deg/s/sqrt(Hz) (typ)" for the list table: the nominal value as printed.
std::string brief(const SensorSheet* s, SpecField field) {
  if (!s) return "-";
  const SpecValue* v = s->find(field);
  if (!v || !v->nominal()) return "-";
  const PrintedValue* p = v->nominal();
  return p->text + (v->typ && p == &*v->typ ? "" : (v->max && p == &*v->max ? " max" : " min"));
}

/// Prefers the printed ARW/VRW, else the noise density (what `convert` would use).
std::string white_brief(const SensorSheet* s) {
  if (s && s->find(SpecField::random_walk)) return brief(s, SpecField::random_walk);
  return brief(s, SpecField::noise_density);
}

/// `text` in a column `width` wide with at least one space after it (an overlong cell still
/// stays apart from the next).
std::string cell(const std::string& text, std::size_t width) { return pad(text, width - 1) + " "; }

void run_list(const SpecsArguments& args) {
  const auto dir = specs_dir(args);
  const auto files = list_data_sheets(dir);
  std::cout << "data sheets in " << dir.string() << " (white noise: ARW/VRW if printed, else "
            << "noise density; nominal value, typ unless marked)\n";
  std::cout << cell("name", 16) << cell("grade", 11) << cell("gyro white", 20)
            << cell("gyro bias stab.", 17) << cell("accel white", 19) << "accel bias stab.\n";
  for (const auto& file : files) {
    const DataSheet sheet = load_data_sheet(file);
    const SensorSheet* g = sheet.sensor(Sensor::gyro);
    const SensorSheet* a = sheet.sensor(Sensor::accel);
    std::cout << cell(sheet.name, 16) << cell(sheet.grade, 11) << cell(white_brief(g), 20)
              << cell(brief(g, SpecField::bias_instability), 17) << cell(white_brief(a), 19)
              << brief(a, SpecField::bias_instability) << "\n";
  }
  std::cout << files.size() << " data sheets; `sigmatau specs show NAME` prints one in full\n";
}

std::string source_text(const SpecValue& v) {
  std::string s = v.source.document;
  if (!v.source.revision.empty()) s += ", rev. " + v.source.revision;
  if (!v.page.empty()) s += ", p. " + v.page;
  if (!v.table.empty()) s += ", " + v.table;
  s += v.source.primary ? " [primary]" : " [secondary]";
  return s;
}

void print_value(std::ostream& o, const SpecFieldInfo& info, const SpecValue& v) {
  o << "  " << info.key << " - " << info.description << "\n";
  const std::string si_unit = si_unit_string(info.dimension);
  auto one = [&](const char* what, const PrintedValue& p) {
    o << "    " << what << " " << p.text << "  = " << (p.plus_minus ? "\u00b1" : "")
      << si(p.value_si) << " " << si_unit << "\n";
  };
  if (v.min) one("min    ", *v.min);
  if (v.typ) one("typ    ", *v.typ);
  if (v.max) one("max    ", *v.max);
  for (const auto& p : v.options) one("option ", p);
  if (!v.condition.empty()) o << "    condition: " << v.condition << "\n";
  for (const AxisValue& a : v.axes) {  // printed apart for this axis
    o << "    axis " << a.axis << ":\n";
    if (a.min) one("  min  ", *a.min);
    if (a.typ) one("  typ  ", *a.typ);
    if (a.max) one("  max  ", *a.max);
    if (!a.condition.empty()) o << "      condition: " << a.condition << "\n";
  }
  if (!v.note.empty()) o << "    note: " << v.note << "\n";
  o << "    source: " << source_text(v) << "\n";
}

void run_show(const SpecsArguments& args) {
  const auto file = find_data_sheet(args.name, specs_dir(args));
  const DataSheet sheet = load_data_sheet(file);
  std::ostringstream o;
  o << sheet.manufacturer << " " << sheet.part << " (" << sheet.grade << ")\n";
  o << "file: " << file.string() << " (schema " << sheet.schema << ")\n";
  if (!sheet.description.empty()) o << sheet.description << "\n";
  for (const Sensor sensor : {Sensor::gyro, Sensor::accel}) {
    const SensorSheet* s = sheet.sensor(sensor);
    o << "\n" << to_string(sensor) << (s ? "" : ": not in this data sheet") << "\n";
    if (!s) continue;
    std::string missing;
    for (const auto& info : spec_fields(sensor)) {
      if (const SpecValue* v = s->find(info.field)) {
        print_value(o, info, *v);
      } else {
        missing += (missing.empty() ? "" : ", ") + std::string(info.key);
      }
    }
    if (!missing.empty()) o << "  not specified: " << missing << "\n";
  }
  o << "\nsources:\n";
  for (const auto& [id, source] : sheet.sources) {
    o << "  " << id << ": " << source.document;
    if (!source.revision.empty()) o << ", rev. " << source.revision;
    o << (source.primary ? " [primary]" : " [secondary]");
    if (!source.url.empty()) o << " " << source.url;
    o << "\n";
    if (!source.note.empty()) o << "    " << source.note << "\n";
  }
  if (!sheet.notes.empty()) o << "\nnotes: " << sheet.notes << "\n";
  std::cout << o.str();
}

}  // namespace

void add_specs_command(CLI::App& app) {
  auto args = std::make_shared<SpecsArguments>();
  CLI::App* command =
      app.add_subcommand("specs", "IMU data sheets shipped with sigmatau (values as printed, SI)");
  command->require_subcommand(1);
  command->add_option("--dir", args->dir,
                      "data-sheet directory (default: the installed share/sigmatau/specs, or "
                      "$SIGMATAU_SPECS_DIR)");
  CLI::App* list = command->add_subcommand("list", "one line per data sheet");
  list->callback([args] { run_list(*args); });
  CLI::App* show = command->add_subcommand(
      "show", "every field of one data sheet, as printed and in SI, with its source");
  show->add_option("name", args->name, "data-sheet name (e.g. tdk_mpu6050) or a YAML file")
      ->required();
  show->callback([args] { run_show(*args); });
}

}  // namespace sigmatau::cli
