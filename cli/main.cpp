// sigmatau: Allan-family deviations, noise terms, data-sheet checks and filter tuning for IMUs.
// Exit codes: 0 ok, 1 a compliance check failed, 2 bad input or usage, 3 internal error.
#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <exception>
#include <iostream>

#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"
#include "verbs.hpp"

namespace {

/// Interrupted (Ctrl-C, kill, hang-up): remove the partial temporary output files, then die of
/// the same signal with its default action, so the shell sees the usual status (130 for SIGINT).
extern "C" void remove_temporaries_and_die(int signal_number) {
  sigmatau::remove_pending_temporaries();
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

/// Installs the handler for SIGINT, SIGTERM and SIGHUP, except where the signal is ignored
/// (`nohup`, a background job of a non-interactive shell): that choice is kept.
void clean_up_outputs_on_interrupt() {
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction current {};
    if (::sigaction(signal_number, nullptr, &current) != 0) continue;
    if (current.sa_handler == SIG_IGN) continue;
    struct sigaction action {};
    action.sa_handler = remove_temporaries_and_die;
    sigemptyset(&action.sa_mask);
    ::sigaction(signal_number, &action, nullptr);
  }
}

/// A write past `ulimit -f` raises SIGXFSZ, whose default action kills the process and leaves
/// the "<path>.tmp-<random>" file behind. Ignored, the write fails with EFBIG instead, and the
/// writer reports "cannot write PATH: File too large" (exit 2) and removes its temporary file,
/// as for a full disk.
void report_file_size_limit_as_error() { std::signal(SIGXFSZ, SIG_IGN); }

}  // namespace

int main(int argc, char** argv) {
  clean_up_outputs_on_interrupt();
  report_file_size_limit_as_error();
  CLI::App app{"sigmatau: how noisy is this IMU, does it meet its data sheet, and what goes into "
               "the filter"};
  app.set_version_flag("--version", std::string("sigmatau ") + SIGMATAU_VERSION);
  app.require_subcommand(1);
  // Registration list: one line per verb.
  sigmatau::cli::add_adev_command(app);
  sigmatau::cli::add_simulate_command(app);
  sigmatau::cli::add_units_command(app);
  sigmatau::cli::add_psd_command(app);
  sigmatau::cli::add_check_command(app);
  sigmatau::cli::add_analyze_command(app);
  sigmatau::cli::add_demo_command(app);
  sigmatau::cli::add_specs_command(app);
  sigmatau::cli::add_convert_command(app);
  sigmatau::cli::add_calibrate_command(app);
  sigmatau::cli::add_fit_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const sigmatau::cli::ExitStatus& status) {
    return status.code;
  } catch (const sigmatau::Error& e) {
    std::cerr << "sigmatau: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "sigmatau: internal error: " << e.what() << "\n";
    return 3;
  }
  return 0;
}
