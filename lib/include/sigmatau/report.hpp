#pragma once
/// \file report.hpp
/// The last stage: from results.json (everything in SI) to what people read: summary.md, a
/// self-contained report.html (inline SVG plots, no external requests) and the plots as files.
/// Nothing here computes a statistic: every number shown is read from results.json, and the
/// filter files written beside the report are shown as they were written.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "sigmatau/plot.hpp"

namespace sigmatau {

struct ReportOptions {
  PlotFormat plot_format = PlotFormat::svg;  ///< plot files; the HTML always embeds SVG
  bool plots = true;                          ///< false: no gnuplot at all
};

/// Files of an output directory, by relative name.
struct ReportFiles {
  std::map<std::string, std::string> files;
  std::vector<std::string> warnings;  ///< e.g. "gnuplot not found: plots left out"
};

/// Builds summary.md, report.html and the plots (adev_gyro, adev_accel, psd_gyro, psd_accel,
/// compliance) from the text of results.json. When gnuplot is missing the report is written
/// without plots and a warning says how to install it. Throws Error on a results.json that is
/// not sigmatau's.
/// `filter_files` are the filter files written beside report.html (file name -> text, as
/// AnalysisOutput::filter_files). The report lists the files results.json's "filter" section
/// names for each rate, says what each is for and shows its text; summary.md names them. A named
/// file missing from `filter_files` is marked missing there and becomes a warning (in the report
/// and in ReportFiles::warnings), so leaving them out never goes unsaid.
ReportFiles build_report(const std::string& results_json, const ReportOptions& options,
                         const std::map<std::string, std::string>& filter_files = {});

/// Writes `files` into directory `dir` atomically as a whole (write_directory_atomically,
/// output_file.hpp): built in a fresh sibling directory, marked as sigmatau's, renamed to `dir`
/// at the end. An existing `dir` is an Error unless `overwrite`, and even then unless it is an
/// earlier report of sigmatau's holding no input (check_output_directory); it is replaced only
/// once the new one is complete. Missing parent directories are created.
void write_output_directory(const std::filesystem::path& dir, const ReportFiles& files,
                            bool overwrite);

}  // namespace sigmatau
