# `fit --format json` records the log's sample rate ("input": {"rate_hz"}, as adev and analyze
# do), so that `convert --fit FIT.json --rate R` gives analyze's note when R is above it: the
# white level above the log's Nyquist frequency is extrapolated. Fit JSON without the field (older
# results) is still read, without the note.
set(example ${PROJECT_SOURCE_DIR}/examples/gyro_static_100Hz.csv.gz)
set(fit_rate_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_fit_log_rate)
file(MAKE_DIRECTORY ${fit_rate_dir})
set(fit_rate_note "warning: the filter rate 200 Hz is above the log's sample rate 100 Hz: the white-noise level was measured only up to 50 Hz \\(the log's Nyquist frequency\\)")

# From a log: the rate from its time stamps (100 Hz up to the stamps' rounding).
sigmatau_cli_test(NAME cli_fit_log_rate_from_log EXIT 0
  ARGS fit ${example} --time-column t --unit deg/s --columns gx --format json
       -o ${fit_rate_dir}/from_log.json --force)
add_test(NAME cli_fit_log_rate_from_log_json
         COMMAND ${CMAKE_COMMAND} -DDIR=${fit_rate_dir}
                 "-DJSON_MATCH=from_log.json::input rate_hz::^(100|99\\.9999999[0-9]*)$"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/expect_json.cmake)
set_tests_properties(cli_fit_log_rate_from_log_json PROPERTIES DEPENDS cli_fit_log_rate_from_log)
sigmatau_cli_test(NAME cli_fit_log_rate_convert_note EXIT 0 STDERR "${fit_rate_note}"
  STDOUT "# note: the filter rate 200 Hz is above the log's sample rate 100 Hz"
  ARGS convert --fit ${fit_rate_dir}/from_log.json --rate 200 --to kalibr --allow-incomplete)
set_tests_properties(cli_fit_log_rate_convert_note PROPERTIES DEPENDS cli_fit_log_rate_from_log)
# At the log's own rate there is nothing to say.
add_test(NAME cli_fit_log_rate_convert_same_rate
         COMMAND sigmatau_cli convert --fit ${fit_rate_dir}/from_log.json --rate 100 --to kalibr --allow-incomplete)
set_tests_properties(cli_fit_log_rate_convert_same_rate PROPERTIES
                     DEPENDS cli_fit_log_rate_from_log FAIL_REGULAR_EXPRESSION "above the log's")

# From a saved adev result: its input.rate_hz, repeated as written.
sigmatau_cli_test(NAME cli_fit_log_rate_adev_make EXIT 0
  ARGS adev ${example} --time-column t --unit deg/s --columns gx --format json
       -o ${fit_rate_dir}/adev.json --force)
sigmatau_cli_test(NAME cli_fit_log_rate_from_adev EXIT 0
  ARGS fit ${fit_rate_dir}/adev.json --format json -o ${fit_rate_dir}/from_adev.json --force)
set_tests_properties(cli_fit_log_rate_from_adev PROPERTIES DEPENDS cli_fit_log_rate_adev_make)
add_test(NAME cli_fit_log_rate_from_adev_json
         COMMAND ${CMAKE_COMMAND} -DDIR=${fit_rate_dir}
                 "-DJSON_MATCH=from_adev.json::input rate_hz::^(100|99\\.9999999[0-9]*)$"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/expect_json.cmake)
set_tests_properties(cli_fit_log_rate_from_adev_json PROPERTIES DEPENDS cli_fit_log_rate_from_adev)
sigmatau_cli_test(NAME cli_fit_log_rate_from_adev_convert_note EXIT 0 STDERR "${fit_rate_note}"
  ARGS convert --fit ${fit_rate_dir}/from_adev.json --rate 200 --to px4 --allow-incomplete)
set_tests_properties(cli_fit_log_rate_from_adev_convert_note PROPERTIES
                     DEPENDS cli_fit_log_rate_from_adev)

# A fit result without the rate (written before fit recorded it) is still read, without the note.
add_test(NAME cli_fit_log_rate_old_json
         COMMAND sigmatau_cli convert --fit ${PROJECT_SOURCE_DIR}/tests/data/convert/fit_ros_names.json
                 --rate 1000 --to kalibr --allow-incomplete)
set_tests_properties(cli_fit_log_rate_old_json PROPERTIES
                     FAIL_REGULAR_EXPRESSION "above the log's")
