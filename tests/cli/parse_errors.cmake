# Errors of the command-line parser (CLI11) go out as every other error does: one line
# "sigmatau: error: ..." on stderr naming the --help to read, exit 2. They used to be CLI11's own
# two lines without the prefix, and its list of unexpected arguments was reversed (a review saw
# "The following arguments were not expected: 0.8 --scale" for `simulate ... --scale 0.8`).
set(parse_errors_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_parse_errors)
file(MAKE_DIRECTORY ${parse_errors_dir})

# Unexpected arguments, in the order typed; nothing written.
sigmatau_cli_test(NAME cli_parse_error_unexpected_in_order EXIT 2
  NO_FILE ${parse_errors_dir}/never.csv
  STDERR "^sigmatau: error: The following arguments were not expected: --bogus 0\\.8 \\(see `sigmatau simulate --help`\\)\n$"
  ARGS simulate --rate 100 --duration 1 -o ${parse_errors_dir}/never.csv --bogus 0.8)
sigmatau_cli_test(NAME cli_parse_error_unexpected_positionals EXIT 2
  STDERR "^sigmatau: error: The following arguments were not expected: b c d \\(see `sigmatau adev --help`\\)\n$"
  ARGS adev a b c d)
# An option without its value, a required option left out, a value of the wrong type.
sigmatau_cli_test(NAME cli_parse_error_missing_value EXIT 2
  STDERR "^sigmatau: error: --rate: [^\n]*missing \\(see `sigmatau adev --help`\\)\n$"
  ARGS adev --rate)
sigmatau_cli_test(NAME cli_parse_error_required_option EXIT 2
  STDERR "^sigmatau: error: --output is required \\(see `sigmatau simulate --help`\\)\n$"
  ARGS simulate --rate 100 --duration 1)
sigmatau_cli_test(NAME cli_parse_error_not_a_number EXIT 2
  STDERR "^sigmatau: error: [^\n]*--threads[^\n]*-3 \\(see `sigmatau adev --help`\\)\n$"
  ARGS adev a --threads -3)
# No command, or a first argument that is none: the commands are named.
sigmatau_cli_test(NAME cli_parse_error_unknown_command EXIT 2
  STDERR "^sigmatau: error: expected a command first, got \"nosuch\"; the commands: adev, [^\n]*fit \\(see `sigmatau --help`\\)\n$"
  ARGS nosuch)
sigmatau_cli_test(NAME cli_parse_error_no_command EXIT 2
  STDERR "^sigmatau: error: expected a command first; the commands: adev, [^\n]*simulate[^\n]*\n$")
# --help and --version are still answered on stdout with exit 0.
sigmatau_cli_test(NAME cli_parse_error_help_still_help EXIT 0 STDOUT "Usage: .* simulate"
  ARGS simulate --help)
sigmatau_cli_test(NAME cli_parse_error_version_still_version EXIT 0 STDOUT "^sigmatau [0-9]"
  ARGS --version)
