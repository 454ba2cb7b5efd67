# The bad-input catalogue (tests/data/bad/README.md) through the CLI: every file must make
# `sigmatau adev` exit 2 with its message and location on stderr, and leave no output file.
set(bad_dir ${PROJECT_SOURCE_DIR}/tests/data/bad)
set(bad_out ${CMAKE_CURRENT_BINARY_DIR}/cli_bad)
file(MAKE_DIRECTORY ${bad_out})
file(STRINGS ${bad_dir}/README.md bad_rows REGEX "^\\| [^ |-][^|]* \\| [0-9]+ \\|")
foreach(row IN LISTS bad_rows)
  string(REGEX MATCH "^\\| ([^|]+) \\| ([0-9]+) \\| ([0-9]+) \\| ([^|]+) \\| ?([^|]*)\\|" _ "${row}")
  set(file ${CMAKE_MATCH_1})
  set(line ${CMAKE_MATCH_2})
  set(column ${CMAKE_MATCH_3})
  string(STRIP "${CMAKE_MATCH_4}" fragment)
  string(STRIP "${CMAKE_MATCH_5}" options)
  separate_arguments(options UNIX_COMMAND "${options}")
  # The message as a regular expression, with the location prefix the CLI prints.
  string(REGEX REPLACE "([][.*+?^$(){}|\\\\])" "\\\\\\1" fragment_re "${fragment}")
  if(line GREATER 0 AND column GREATER 0)
    set(expected ":${line}:${column}: .*${fragment_re}")
  elseif(line GREATER 0)
    set(expected ":${line}: .*${fragment_re}")
  else()
    set(expected "${fragment_re}")
  endif()
  string(MAKE_C_IDENTIFIER "${file}" id)
  sigmatau_cli_test(NAME cli_bad_${id} EXIT 2 STDERR "${expected}"
    NO_FILE ${bad_out}/${id}.json
    ARGS adev ${bad_dir}/${file} --rate 100 ${options} --format json -o ${bad_out}/${id}.json)
endforeach()

# Options and arguments that are wrong whatever the file holds.
set(good ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv)
sigmatau_cli_test(NAME cli_bad_too_few_samples_for_tau EXIT 2 STDERR "tau|averaging"
  ARGS adev ${good} --time-column t --taus 1000)
sigmatau_cli_test(NAME cli_bad_binary_without_channels EXIT 2 STDERR "--binary needs --channels"
  ARGS adev ${good} --binary f32 --rate 10)
sigmatau_cli_test(NAME cli_bad_unknown_kind EXIT 2 STDERR "kind"
  ARGS adev ${good} --time-column t --kind velocity)
sigmatau_cli_test(NAME cli_bad_unknown_unit EXIT 2 STDERR "furlong"
  ARGS adev ${good} --time-column t --unit furlong/s)
sigmatau_cli_test(NAME cli_bad_negative_rate EXIT 2 STDERR "rate"
  ARGS adev ${good} --rate -5)

# Hostile inputs generated while the test runs (never committed), streamed through stdin under a
# 256 MiB address-space limit (ulimit -v): a 1 GiB line and a header of a million columns must
# stop at the reader's 1 MiB line limit with exit 2 and its message, in bounded memory. A reader
# that buffered the line would exceed the limit and die with another exit code. The generator
# gets SIGPIPE once sigmatau stops reading, so each test takes about a second. The address-space
# limit cannot hold under AddressSanitizer (it reserves terabytes of shadow), hence sanitize_skip.
# Arguments of the script: $1 the CLI, $2 the generator (a shell pipeline), $3 the expected
# message (grep basic regular expression).
set(hostile_check [=[
ulimit -v 262144 || exit 1
err=$(mktemp) || exit 1
eval "$2" | "$1" adev - --rate 100 >/dev/null 2>"$err"
rc=${PIPESTATUS[1]}
msg=$(head -c 400 "$err"); rm -f "$err"
echo "exit $rc (expected 2): $msg"
[ "$rc" = 2 ] && printf '%s' "$msg" | grep -q -- "$3"
]=])
function(sigmatau_hostile_test name generator expected)
  add_test(NAME ${name}
           COMMAND bash -c "${hostile_check}" hostile $<TARGET_FILE:sigmatau_cli> "${generator}"
                   "${expected}")
  set_tests_properties(${name} PROPERTIES LABELS sanitize_skip TIMEOUT 120)
endfunction()
sigmatau_hostile_test(cli_bad_1gib_line
  "head -c 1073741824 /dev/zero | tr '\\0' 1"
  "<stdin>:1: line longer than 1048576 bytes")
sigmatau_hostile_test(cli_bad_million_column_header
  "yes a | head -n 1000000 | paste -sd, -; echo 1"
  "<stdin>:1: line longer than 1048576 bytes")
# A million columns that fit in the line limit (999999 commas: empty names) meet the field limit.
sigmatau_hostile_test(cli_bad_million_columns_in_one_mib
  "head -c 999999 /dev/zero | tr '\\0' ,; echo; echo 1"
  "<stdin>:1: more than 100000 columns")
