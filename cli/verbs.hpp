#pragma once
// Each verb file (cli/<verb>.cpp) adds its subcommand to the app. A verb parses options, calls
// lib, formats output; no numerics here.
#include <CLI/CLI.hpp>

namespace sigmatau::cli {

void add_adev_command(CLI::App& app);
void add_psd_command(CLI::App& app);
void add_units_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_specs_command(CLI::App& app);
void add_convert_command(CLI::App& app);

}  // namespace sigmatau::cli
