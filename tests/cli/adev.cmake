# CLI regression cases for `sigmatau adev` (see sigmatau_cli_test in tests/CMakeLists.txt).
set(example ${PROJECT_SOURCE_DIR}/examples/gyro_static_100Hz.csv.gz)
set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_adev)
file(MAKE_DIRECTORY ${out_dir})

sigmatau_cli_test(NAME cli_adev_table EXIT 0
  STDOUT "gx  oadev  \\[deg/h\\].*tau\\[s\\].*ci_low"
  ARGS adev ${example} --time-column t --unit deg/s --out-unit deg/h)

# JSON to a file, then a second run must refuse to overwrite it without --force.
add_test(NAME cli_adev_json_fresh COMMAND ${CMAKE_COMMAND} -E rm -f ${out_dir}/adev.json)
sigmatau_cli_test(NAME cli_adev_json EXIT 0
  ARGS adev ${example} --time-column t --unit deg/s --format json -o ${out_dir}/adev.json)
set_tests_properties(cli_adev_json PROPERTIES DEPENDS cli_adev_json_fresh)
sigmatau_cli_test(NAME cli_adev_no_overwrite EXIT 2 STDERR "exists; use --force"
  ARGS adev ${example} --time-column t --format json -o ${out_dir}/adev.json)
set_tests_properties(cli_adev_no_overwrite PROPERTIES DEPENDS cli_adev_json)
sigmatau_cli_test(NAME cli_adev_force EXIT 0
  ARGS adev ${example} --time-column t --format json -o ${out_dir}/adev.json --force)
set_tests_properties(cli_adev_force PROPERTIES DEPENDS cli_adev_no_overwrite)

sigmatau_cli_test(NAME cli_adev_stdin EXIT 0 STDIN ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv
  STDOUT "\"channel\": \"gy\"" ARGS adev - --time-column t --format json)

# No --rate and no time column (the example's t is found by its name, so a file without one).
file(WRITE ${out_dir}/no_time.csv "gx,gy\n0.1,0.2\n0.3,0.1\n0.2,0.2\n0.1,0.3\n")
sigmatau_cli_test(NAME cli_adev_no_rate EXIT 2 STDERR "rate"
  NO_FILE ${out_dir}/no_rate.json
  ARGS adev ${out_dir}/no_time.csv --columns gx --format json -o ${out_dir}/no_rate.json)
sigmatau_cli_test(NAME cli_adev_unknown_statistic EXIT 2 STDERR "madev"
  ARGS adev ${example} --time-column t --stat oadev,madev)
sigmatau_cli_test(NAME cli_adev_bad_taus EXIT 2 STDERR "--taus|tau"
  ARGS adev ${example} --time-column t --taus sometimes)
sigmatau_cli_test(NAME cli_adev_out_unit_dimension EXIT 2 STDERR "m/s\\^2"
  ARGS adev ${example} --time-column t --unit deg/s --out-unit m/s^2)
sigmatau_cli_test(NAME cli_adev_out_unit_needs_unit EXIT 2 STDERR "--out-unit needs --unit"
  ARGS adev ${example} --time-column t --out-unit deg/h)
sigmatau_cli_test(NAME cli_adev_bad_ci EXIT 2 STDERR "confidence"
  ARGS adev ${example} --time-column t --ci 1.5)
sigmatau_cli_test(NAME cli_adev_missing_file EXIT 2 STDERR "no_such_file.csv"
  ARGS adev ${out_dir}/no_such_file.csv --rate 100)
sigmatau_cli_test(NAME cli_adev_usage EXIT 2 ARGS adev)

# --edf discrete: at m = 1 on white FM (independent rate samples) the exact EDF of the
# n = N - 2 = 1999 overlapping terms is 2 n^2 / (3 n - 1) = 1332.9 (first differences are MA(1)
# with lag-1 correlation -1/2), printed "1333"; Greenhall's default models the phase as averaged
# over tau0 and gives about 18/23 of the samples instead (tests/test_edf_exact.cpp).
sigmatau_cli_test(NAME cli_adev_edf_discrete EXIT 0
  STDOUT "0\\.1 +1 +1999 +0 +1333 "
  ARGS adev ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv --time-column t --taus 0.1
       --edf discrete)
sigmatau_cli_test(NAME cli_adev_edf_json EXIT 0 STDOUT "\"edf_model\": \"discrete\""
  ARGS adev ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv --time-column t --taus 0.1
       --edf discrete --format json)
sigmatau_cli_test(NAME cli_adev_edf_unknown EXIT 2 STDERR "--edf must be greenhall or discrete"
  ARGS adev ${example} --time-column t --edf exact)
sigmatau_cli_test(NAME cli_adev_edf_stream EXIT 2 STDERR "--edf discrete is for exact mode"
  ARGS adev ${example} --time-column t --edf discrete --mode stream)
# The model reaches the out-of-core path (--memory 1K forces it) and the gap-split path.
sigmatau_cli_test(NAME cli_adev_edf_discrete_out_of_core EXIT 0
  STDOUT "0\\.1 +1 +1999 +0 +1333 "
  ARGS adev ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv --time-column t --taus 0.1
       --edf discrete --memory 1K)

# Time stamps and --rate: a rate that overrides stamps measuring another is warned about, and
# stamps in ms read as seconds (0.1 Hz) get a hint to give --time-unit.
sigmatau_cli_test(NAME cli_adev_rate_overrides_stamps EXIT 0
  STDERR "--rate 200 Hz is used, but the time stamps measure 100 Hz"
  ARGS adev ${PROJECT_SOURCE_DIR}/examples/gyro_static_100Hz.csv.gz --time-column t --unit deg/s
       --rate 200 --columns gx)
sigmatau_cli_test(NAME cli_adev_stamps_in_ms_hint EXIT 0
  STDERR "measure 0.1 Hz; if they are in ms, us or ns, give --time-unit"
  ARGS adev ${PROJECT_SOURCE_DIR}/tests/data/cli/stamps_ms_100Hz.csv --time-column t_ms
       --time-unit s --unit deg/s)
# Without --time-unit the name's suffix says ms.
sigmatau_cli_test(NAME cli_adev_stamps_unit_from_name EXIT 0 STDOUT "400 samples at 100 Hz"
  ARGS adev ${PROJECT_SOURCE_DIR}/tests/data/cli/stamps_ms_100Hz.csv --time-column t_ms --unit deg/s)
# --rate takes "10 Hz" as convert does.
sigmatau_cli_test(NAME cli_adev_rate_with_unit EXIT 0 STDOUT "2000 samples at 10 Hz"
  ARGS adev ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv --columns 1 --rate "10 Hz")

# The time column is found by its name (issue 28): `simulate`'s CSV reads without
# --time-column, in adev and in analyze, and a unit suffix sets the unit.
set(found_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_time_found)
file(REMOVE_RECURSE ${found_dir})
file(MAKE_DIRECTORY ${found_dir})
add_test(NAME cli_time_found_simulate COMMAND $<TARGET_FILE:sigmatau_cli> simulate
         --model "N=0.15 deg/sqrt(h)" --rate 100 --duration 2min -o ${found_dir}/sim.csv --force)
sigmatau_cli_test(NAME cli_time_found_adev EXIT 0
  STDOUT "12000 samples at 100 Hz" STDERR "time column \"t\" found by its name"
  ARGS adev ${found_dir}/sim.csv --taus 1)
sigmatau_cli_test(NAME cli_time_found_analyze EXIT 0 STDOUT "wrote "
  ARGS analyze ${found_dir}/sim.csv --gyro-unit rad/s -o ${found_dir}/report --force)
# A fixture, not DEPENDS: `ctest -R cli_time_found_adev` alone also runs the simulation first.
set_tests_properties(cli_time_found_simulate PROPERTIES FIXTURES_SETUP cli_time_found_sim)
set_tests_properties(cli_time_found_adev cli_time_found_analyze PROPERTIES
                     FIXTURES_REQUIRED cli_time_found_sim)
sigmatau_cli_test(NAME cli_time_found_suffix_ns EXIT 0 STDOUT "400 samples at 100 Hz"
  STDERR "time column \"t_ms\" found by its name \\(stamps in ms, from its name"
  ARGS adev ${PROJECT_SOURCE_DIR}/tests/data/cli/stamps_ms_100Hz.csv --unit deg/s)

# A column is never dropped without a word (issue 28): a typo in the first data row of a
# numeric column is an error naming file, line and column (its good rows used to vanish, exit
# 0); a TSV column with decimal commas is an error; a text column is left out with a note.
file(WRITE ${found_dir}/typo.csv "t,gx,gy\n0.00,x1.288185,0.5\n0.01,1.1,0.6\n0.02,1.2,0.4\n0.03,0.9,0.5\n0.04,1.0,0.7\n")
sigmatau_cli_test(NAME cli_column_typo_first_row EXIT 2
  STDERR "typo\\.csv:2:2: expected a number, found \"x1\\.288185\""
  ARGS adev ${found_dir}/typo.csv --taus 0.01)
sigmatau_cli_test(NAME cli_column_typo_first_row_skipped EXIT 0
  STDOUT "4 samples at 100 Hz.*# gx .*# gy "
  STDERR "1 row with a non-finite or non-numeric value skipped \\(--nonfinite skip\\)"
  ARGS adev ${found_dir}/typo.csv --taus 0.01 --nonfinite skip)
file(WRITE ${found_dir}/comma.tsv "t\tgx\tgy\n0.00\t1,288185\t0.5\n0.01\t1,1\t0.6\n0.02\t1,2\t0.4\n")
sigmatau_cli_test(NAME cli_column_decimal_comma EXIT 2
  STDERR "comma\\.tsv:2:2: expected a number, found \"1,288185\" in column \"gx\": a decimal comma"
  ARGS adev ${found_dir}/comma.tsv --taus 0.01)
file(WRITE ${found_dir}/status.csv "t,gx,status\n0.00,1.0,OK\n0.01,1.1,OK\n0.02,0.9,OK\n0.03,1.0,OK\n")
sigmatau_cli_test(NAME cli_column_text_noted EXIT 0
  STDERR "column \"status\" holds text, not numbers \\(line 2: \"OK\"\\), and is not analysed"
  ARGS adev ${found_dir}/status.csv --taus 0.01)
# analyze with --gyro / --accel: a channel they do not name is said to be left out.
file(WRITE ${found_dir}/mag.csv "t,gx,gy,gz,ax,ay,az,mx\n0.00,1,2,3,4,5,6,7\n0.01,1.1,2.1,3,4,5.1,6,7\n0.02,0.9,2,3.1,4.1,5,6,7.1\n0.03,1,1.9,3,4,5,6.1,7\n")
sigmatau_cli_test(NAME cli_analyze_named_channels_note EXIT 0
  STDERR "mx not analysed \\(--gyro / --accel name the channels"
  ARGS analyze ${found_dir}/mag.csv --gyro gx,gy,gz --accel ax,ay,az --taus 0.01
       -o ${found_dir}/mag_report --force)
# Decade taus in stream mode: every such run failed ("tau of 10000000 samples has no power-of-two
# factor"); the grid is held to 4e6 samples and longer factors a log reaches are named
# (test_allan_stream). On this 120000-sample log: 0.01 s to 200 s, no warning.
sigmatau_cli_test(NAME cli_adev_stream_decade EXIT 0
  STDOUT "\n +0\\.01 +1 .*\n +200 +20000 "
  ARGS adev ${example} --time-column t --mode stream --taus decade)
