// The report's "Filter tuning" part: the arithmetic of results.json's "filter" section, laid out
// so that it wraps at the page's width, and the filter files written beside report.html, named,
// said what each is for and shown (collapsed) as written; a file results.json names but the
// report was not given is said to be missing (report_common.hpp).
#include <string>

#include "report_common.hpp"

namespace sigmatau::report_detail {
namespace {

/// Characters a wrapped line of the arithmetic continues past the line's own indentation, so a
/// continuation is not read as a line of its own (the arithmetic indents by 2 per level).
constexpr std::size_t kHangingIndent = 4;

/// What a filter file is for: the first comment line of a YAML, text or params file ("Kalibr
/// imu.yaml (continuous-time densities)"), which filter_export.cpp writes for each format; for
/// the JSON file, which has no comment, what it holds. Empty when neither applies.
std::string file_purpose(const std::string& name, const std::string& text) {
  const auto dot = name.rfind('.');
  if (dot != std::string::npos && name.substr(dot) == ".json") {
    return "sigmatau's JSON: per axis the densities, the discrete covariances Q and the sigma "
           "per sample or step, with their units (for a filter of your own)";
  }
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(begin, end - begin);
    if (line.rfind("# ", 0) == 0) return line.substr(2);
    if (line.rfind('%', 0) != 0) return "";  // "%YAML:1.0" precedes OpenCV's comment
    begin = end + 1;
  }
  return "";
}

/// The anchor of a filter file's text in report.html.
std::string file_anchor(const std::string& name) { return "file-" + name; }

/// The files of one rate ("at 200 Hz") or the files no rate names.
struct FileGroup {
  std::string title;
  std::string arithmetic;  ///< results.json's "explain" text; empty for the leftover group
  std::vector<std::string> names;
};

/// The groups in results.json's order; a file given but named by no rate (a results.json from
/// before the "files" list) comes last, so no file given is left out.
std::vector<FileGroup> file_groups(const json& results,
                                   const std::map<std::string, std::string>& files) {
  std::vector<FileGroup> groups;
  std::map<std::string, bool> named;
  if (results.contains("filter") && results["filter"].is_array()) {
    for (const auto& entry : results["filter"]) {
      FileGroup group{
          "at " + fmt(entry.value("rate_hz", 0.0)) + " Hz", entry.value("explain", ""), {}};
      if (entry.contains("files") && entry["files"].is_array()) {
        for (const auto& name : entry["files"]) {
          if (!name.is_string()) continue;
          group.names.push_back(name.get<std::string>());
          named[group.names.back()] = true;
        }
      }
      groups.push_back(std::move(group));
    }
  }
  FileGroup rest{"files results.json does not name", "", {}};
  for (const auto& [name, text] : files) {
    if (!named.count(name)) rest.names.push_back(name);
  }
  if (!rest.names.empty()) groups.push_back(std::move(rest));
  return groups;
}

/// Said where a file results.json names was not given to the report.
constexpr const char* kMissingText =
    "missing: results.json names it, but the report was not given it";

}  // namespace

std::string html_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string wrapped_lines_html(const std::string& text, const std::string& css_class) {
  std::string out = "<pre class=\"lines " + css_class + "\">";
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    end = end == std::string::npos ? text.size() : end + 1;  // the line with its newline
    const std::string line = text.substr(begin, end - begin);
    const std::size_t first = line.find_first_not_of(' ');
    const std::size_t indent = first == std::string::npos ? 0 : first;
    // The text stays as it is (a copy gives the file back): the padding minus the same negative
    // indent puts the line at the margin and its continuations past its indentation.
    const std::string hang = std::to_string(indent + kHangingIndent);
    out += "<span style=\"padding-left:" + hang + "ch;text-indent:-" + hang + "ch\">" +
           html_escape(line) + "</span>";
    begin = end;
  }
  return out + "</pre>\n";
}

std::vector<std::string> missing_filter_files(const json& results,
                                              const std::map<std::string, std::string>& files) {
  std::vector<std::string> missing;
  for (const FileGroup& group : file_groups(results, files)) {
    for (const auto& name : group.names) {
      if (!files.count(name)) {
        missing.push_back("filter file " + name + " (" + group.title +
                          ") is named in results.json "
                          "but was not given to the report: report.html and summary.md cannot "
                          "show it");
      }
    }
  }
  return missing;
}

std::string filter_section_html(const json& results,
                                const std::map<std::string, std::string>& files) {
  const auto groups = file_groups(results, files);
  if (groups.empty()) return "";
  std::string h =
      "<h2 id=\"filter\">Filter tuning</h2>\n<p class=\"muted\">For each rate, the "
      "filter files written in the same directory as this report (take the one your "
      "filter reads, at the rate it runs; click a name to show the file as written, "
      "its comment lines saying what the values rest on), then how their values were "
      "worked out.</p>\n";
  for (const FileGroup& group : groups) {
    h += "<h3>" + html_escape(group.title) + "</h3>\n";
    if (!group.names.empty()) h += "<div class=\"files\">\n";
    for (const auto& name : group.names) {
      const auto it = files.find(name);
      if (it == files.end()) {
        h += "<p class=\"file missing\"><code>" + html_escape(name) + "</code>: " + kMissingText +
             "</p>\n";
        continue;
      }
      const std::string purpose = file_purpose(name, it->second);
      h += "<details class=\"file\" id=\"" + html_escape(file_anchor(name)) + "\"><summary><code>" +
           html_escape(name) + "</code>" + (purpose.empty() ? "" : ": " + html_escape(purpose)) +
           " <span class=\"muted\">(" + std::to_string(it->second.size()) +
           " bytes)</span></summary>" + wrapped_lines_html(it->second, "file") + "</details>\n";
    }
    if (!group.names.empty()) h += "</div>\n";
    if (group.arithmetic.empty()) continue;
    h += "<p class=\"muted\">How the values " +
         std::string(group.names.empty() ? "" : "in these files ") + "were worked out:</p>\n" +
         wrapped_lines_html(group.arithmetic, "arith");
  }
  return h;
}

std::string filter_files_line_html(const json& results,
                                   const std::map<std::string, std::string>& files) {
  std::string links;
  for (const FileGroup& group : file_groups(results, files)) {
    for (const auto& name : group.names) {
      links += std::string(links.empty() ? "" : ", ") + "<a href=\"#" +
               html_escape(file_anchor(name)) + "\"><code>" + html_escape(name) + "</code></a>" +
               (files.count(name) ? "" : " <strong>(missing)</strong>");
    }
  }
  if (links.empty()) return "";
  return "<p id=\"filter-files\">Filter files, beside this report (shown under <a "
         "href=\"#filter\">Filter "
         "tuning</a>): " +
         links + ".</p>\n";
}

std::string filter_section_markdown(const json& results,
                                    const std::map<std::string, std::string>& files) {
  const auto groups = file_groups(results, files);
  bool any = false;
  for (const FileGroup& group : groups) any = any || !group.names.empty();
  if (!any) return "";
  std::string md =
      "\n## Filter files\n\nWritten beside this summary (their text and arithmetic "
      "are in report.html, \"Filter tuning\"); take the one your filter reads, at the "
      "rate it runs.\n";
  for (const FileGroup& group : groups) {
    if (group.names.empty()) continue;
    md += "\n" + group.title + ":\n";
    for (const auto& name : group.names) {
      const auto it = files.find(name);
      const std::string what = it == files.end() ? std::string("**") + kMissingText + "**"
                                                 : file_purpose(name, it->second);
      md += "- `" + name + "`" + (what.empty() ? "" : ": " + what) + "\n";
    }
  }
  return md;
}

}  // namespace sigmatau::report_detail
