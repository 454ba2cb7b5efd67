#pragma once
// Each verb file (cli/<verb>.cpp) adds its subcommand to the app. A verb parses options, calls
// lib, formats output; no numerics here.
#include <CLI/CLI.hpp>

#include <string>

namespace sigmatau::cli {

/// The whole of a small text input (a JSON result). Throws Error naming `path` and the reason
/// when it cannot be opened or read (missing, unreadable, a directory).
std::string read_text_file(const std::string& path);

/// Thrown by a verb after its output is complete to end with a non-zero status that is not an
/// error (e.g. `check` exits 1 when a compliance check failed).
struct ExitStatus {
  int code;
};

void add_check_command(CLI::App& app);
void add_analyze_command(CLI::App& app);
void add_demo_command(CLI::App& app);

void add_adev_command(CLI::App& app);
void add_psd_command(CLI::App& app);
void add_units_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_specs_command(CLI::App& app);
void add_convert_command(CLI::App& app);
void add_calibrate_command(CLI::App& app);
void add_fit_command(CLI::App& app);

}  // namespace sigmatau::cli
