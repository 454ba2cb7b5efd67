// sigmatau: Allan-family deviations, noise terms, data-sheet checks and filter tuning for IMUs.
// Exit codes: 0 ok, 1 a compliance check failed, 2 bad input or usage, 3 internal error.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <string_view>
#include <vector>

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

/// The options that name what a verb writes; every other option's value and every positional
/// argument that names an existing file or directory is something the verb reads.
constexpr std::string_view kOutputOptions[] = {"--output", "--plot"};

/// Records, before the chosen verb runs, every existing file or directory its command line names
/// outside its output options (the log, a saved result, a data sheet, a truth file, a rosbag2
/// folder) as an input, so that no output of the run replaces one or, for a report directory,
/// holds one (note_input). Done here once for every verb; naming a file that is not read
/// (never the case today) only makes its outputs' checks stricter.
void note_inputs_of(const CLI::App& app) {
  for (const CLI::App* verb : app.get_subcommands()) {
    for (const CLI::Option* option : verb->get_options()) {
      if (std::any_of(
              std::begin(kOutputOptions), std::end(kOutputOptions),
              [&](std::string_view output) { return option->check_name(std::string(output)); })) {
        continue;
      }
      for (const std::string& value : option->results()) {
        // "-" is stdin, which may be a file (`adev - < log.csv -o log.csv`).
        sigmatau::note_input(value == "-" ? std::string("/dev/stdin") : value);
      }
    }
  }
}

/// "sigmatau: error: MESSAGE (see `sigmatau VERB --help`)": a CLI11 parse error in the form of
/// every other error, on one line. An ExtrasError's arguments are listed as typed; without a
/// command, the first argument (which is none) is named with the commands (CLI11 says only "A
/// subcommand is required").
std::string parse_error_line(const CLI::App& app, const CLI::ParseError& e) {
  std::string message = e.what();
  // The arguments CLI11 could not place, the root's and the chosen command's, in the order they
  // were typed (CLI11 2.1's ExtrasError message lists them reversed).
  const std::vector<std::string> extras = app.remaining(true);
  const std::vector<CLI::App*> chosen = app.get_subcommands();
  if (chosen.empty()) {
    message = "expected a command first" +
              (extras.empty() ? std::string() : ", got \"" + extras.front() + "\"") +
              "; the commands:";
    std::string separator = " ";
    for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
      message += separator + command->get_name();
      separator = ", ";
    }
  } else if (dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr && !extras.empty()) {
    message = extras.size() > 1 ? "The following arguments were not expected:"
                                : "The following argument was not expected:";
    for (const std::string& argument : extras) message += " " + argument;
  }
  const std::string help =
      chosen.empty() ? "sigmatau --help" : "sigmatau " + chosen.back()->get_name() + " --help";
  return "sigmatau: error: " + message + " (see `" + help + "`)";
}

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
  // The root's parse-complete callback runs before the chosen verb's own callback.
  app.parse_complete_callback([&app] { note_inputs_of(app); });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" of exit code 0 that CLI11 prints itself.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    std::cerr << parse_error_line(app, e) << "\n";
    return 2;
  } catch (const sigmatau::cli::ExitStatus& status) {
    return status.code;
  } catch (const sigmatau::Error& e) {
    std::cerr << "sigmatau: error: " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    // Not a bug: an input larger than memory where its size could not be told first (a pipe,
    // which exact mode holds whole).
    std::cerr << "sigmatau: error: out of memory: the input needs more memory than this machine "
                 "gives; if it comes from a pipe, save it to a file (then --memory applies) or "
                 "use a bounded mode (adev --mode stream)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "sigmatau: internal error: " << e.what() << "\n";
    return 3;
  }
  return 0;
}
