# `sigmatau fit` reports beside B the curve's own minimum (value and tau), not only the model's
# floor 0.664 B (review F #6); a K kept where the curve shows no floor is warned about in the
# table, the JSON and on stderr (review F #2); a constant channel's warning is the shared text.
set(example ${PROJECT_SOURCE_DIR}/examples/gyro_static_100Hz.csv.gz)

# gy of the example keeps N,B (its K reads as a floor in 20 min).
sigmatau_cli_test(NAME cli_fit_curve_minimum_table EXIT 0
  STDOUT "B  bias instability .*ADEV floor 0.664 B = [0-9.e+-]+ deg/h, as data sheets print bias stability; curve minimum [0-9.e+-]+ deg/h at tau = [0-9.]+ s\\)"
  ARGS fit ${example} --time-column t --unit deg/s --columns gy)
sigmatau_cli_test(NAME cli_fit_curve_minimum_json EXIT 0
  STDOUT "\"B\": {[^}]*\"adev_min\": [0-9.e+-]+,[^}]*\"tau_min_s\": [0-9.]+,[^}]*\"unit\": \"rad/s\""
  ARGS fit ${example} --time-column t --unit deg/s --columns gy --format json)

# gx keeps N,K with no floor: the table, the JSON and stderr say K cannot be told from B.
sigmatau_cli_test(NAME cli_fit_short_log_table EXIT 0
  STDOUT "K  rate random walk .*\n   warning: gx: K is kept where the curve shows no bias-instability floor"
  STDERR "warning: gx: K is kept where the curve shows no bias-instability floor.*interval held the truth in [0-9]+ %"
  ARGS fit ${example} --time-column t --unit deg/s --columns gx)
sigmatau_cli_test(NAME cli_fit_short_log_json EXIT 0
  STDOUT "\"warnings\": \\[[^]]*gx: K is kept where the curve shows no bias-instability floor"
  ARGS fit ${example} --time-column t --unit deg/s --columns gx --format json)
sigmatau_cli_test(NAME cli_fit_no_short_log_warning EXIT 0
  STDOUT "\"warnings\": \\[\\]"
  ARGS fit ${example} --time-column t --unit deg/s --columns gy --format json)

sigmatau_cli_test(NAME cli_fit_constant_channel_text EXIT 0
  STDERR "channel gy is constant \\(every OADEV value is 0\\): a stuck sensor, or precision lost .*; left out of the fit"
  ARGS fit ${PROJECT_SOURCE_DIR}/tests/data/cli/stuck_axis_10Hz.csv --time-column t)

# analyze reads the fit's warnings: the same K without a floor is warned about there too.
set(fit_minimum_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_fit_minimum)
file(MAKE_DIRECTORY ${fit_minimum_dir})
sigmatau_cli_test(NAME cli_analyze_short_log_warning EXIT 0
  STDERR "warning: gx: K is kept where the curve shows no bias-instability floor"
  ARGS analyze ${example} --time-column t --gyro-unit deg/s --columns gx -o ${fit_minimum_dir}/analyze --force)
