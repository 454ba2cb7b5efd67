# CLI regression cases for `sigmatau fit` (see sigmatau_cli_test in tests/CMakeLists.txt).
set(example ${PROJECT_SOURCE_DIR}/examples/gyro_static_100Hz.csv.gz)
set(fit_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_fit)
file(MAKE_DIRECTORY ${fit_dir})

# The example is N = 0.3 deg/sqrt(h), K = 30 deg/h/sqrt(h) per axis (examples/make_gyro_static.py).
sigmatau_cli_test(NAME cli_fit_table EXIT 0
  STDOUT "gx  joint  model N,K.*angle random walk.*deg/sqrt\\(h\\).*gyro triad"
  ARGS fit ${example} --time-column t --unit deg/s)
sigmatau_cli_test(NAME cli_fit_json EXIT 0
  STDOUT "\"quantity\": \"angular_rate\".*\"unit\": \"rad/s/sqrt\\(Hz\\)\".*\"upper_bound\""
  ARGS fit ${example} --time-column t --unit deg/s --columns gx --format json --method both)
sigmatau_cli_test(NAME cli_fit_forced_terms EXIT 0
  STDOUT "\"model_terms\": .[^A-Z]*\"N\",[^A-Z]*\"B\",[^A-Z]*\"K\""
  ARGS fit ${example} --time-column t --unit deg/s --columns gx --format json --terms N,B,K)

# From a saved adev result, detected by content.
add_test(NAME cli_fit_adev_json_fresh COMMAND ${CMAKE_COMMAND} -E rm -f ${fit_dir}/adev.json)
sigmatau_cli_test(NAME cli_fit_adev_json_make EXIT 0
  ARGS adev ${example} --time-column t --unit deg/s --columns gx,gy --format json -o ${fit_dir}/adev.json)
set_tests_properties(cli_fit_adev_json_make PROPERTIES DEPENDS cli_fit_adev_json_fresh)
sigmatau_cli_test(NAME cli_fit_from_adev_json EXIT 0
  STDOUT "gx  joint  model .*gy  joint  model "
  ARGS fit ${fit_dir}/adev.json)
set_tests_properties(cli_fit_from_adev_json PROPERTIES DEPENDS cli_fit_adev_json_make)

sigmatau_cli_test(NAME cli_fit_wrong_json EXIT 2 STDERR "wrong_shape.json: not a saved .*missing \"input\""
  ARGS fit ${PROJECT_SOURCE_DIR}/tests/data/fit/wrong_shape.json)
sigmatau_cli_test(NAME cli_fit_bad_terms EXIT 2 STDERR "--terms \"N,X\": unknown term \"X\""
  ARGS fit ${example} --time-column t --terms N,X)
sigmatau_cli_test(NAME cli_fit_bad_method EXIT 2 STDERR "--method"
  ARGS fit ${example} --time-column t --method best)
sigmatau_cli_test(NAME cli_fit_too_short EXIT 2 STDERR "usable OADEV points, need at least"
  ARGS fit ${PROJECT_SOURCE_DIR}/tests/data/fit/short.csv --time-column t)
sigmatau_cli_test(NAME cli_fit_unknown_sensor EXIT 2 STDERR "gyro or an accelerometer"
  NO_FILE ${fit_dir}/unknown.json
  ARGS fit ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv --columns t --rate 10 -o ${fit_dir}/unknown.json)

# The tau range (--tau-min / --tau-max): a reversed range is refused; the table reports the
# goodness of fit of the points fitted (8 of the 15 octave points from 1 s on, N and K: 6 degrees of freedom).
sigmatau_cli_test(NAME cli_fit_tau_range_reversed EXIT 2 STDERR "--tau-min / --tau-max: expected"
  ARGS fit ${example} --time-column t --unit deg/s --tau-min 10 --tau-max 1)
sigmatau_cli_test(NAME cli_fit_tau_range EXIT 0
  STDOUT "\"dof\": 6,.*\"p_value\":.*\"points\": 8,"
  ARGS fit ${example} --time-column t --unit deg/s --columns gx --format json --tau-min 1)
sigmatau_cli_test(NAME cli_fit_goodness_table EXIT 0
  STDOUT "goodness of fit: chi-squared [0-9.e+]+ for [0-9]+ degrees of freedom, p = "
  ARGS fit ${example} --time-column t --unit deg/s --columns gx)
# Without --unit the values are SI, and stderr says so.
sigmatau_cli_test(NAME cli_fit_no_unit_note EXIT 0 STDERR "no --unit: the values are taken as SI"
  ARGS fit ${example} --time-column t --columns gx)
# A constant channel (a stuck axis) has nothing to fit: it is left out with a warning that says
# why, and the other axes are fitted (the whole run used to stop, advising a longer log).
sigmatau_cli_test(NAME cli_fit_constant_channel EXIT 0
  STDOUT "# gx  joint.*# gz  joint.*gyro triad \\(gx,gz\\)"
  STDERR "channel gy is constant \\(every OADEV value is 0"
  ARGS fit ${PROJECT_SOURCE_DIR}/tests/data/cli/stuck_axis_10Hz.csv --time-column t)
sigmatau_cli_test(NAME cli_fit_every_channel_constant EXIT 2
  STDERR "every channel is constant: nothing to fit"
  ARGS fit ${PROJECT_SOURCE_DIR}/tests/data/cli/stuck_axis_10Hz.csv --time-column t --columns gy)
# B beside the Allan floor 0.664 B, which is what a data sheet prints as bias stability (a
# STIM300 at its typical 0.5 deg/h fits as B = 0.75 deg/h): the table gives both.
sigmatau_cli_test(NAME cli_fit_b_with_floor EXIT 0
  STDOUT "B  bias instability .* deg/h  \\(ADEV floor 0.664 B [=<] [0-9.]+ deg/h, as data sheets print bias stability"
  ARGS fit ${example} --time-column t --unit deg/s --columns gx --terms N,B,K)
