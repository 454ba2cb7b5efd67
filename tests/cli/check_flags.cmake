# What a `check` verdict rests on (review F findings 1, 4): a verdict from a rejected fit is
# marked in the note column and explained beside RESULT, and results JSON says so; the exit
# status is unchanged (a fail is a fail).
set(flags_data ${PROJECT_SOURCE_DIR}/tests/data/check)
sigmatau_cli_test(NAME cli_check_fit_rejected EXIT 1
  STDOUT "gyro white_noise x +fail .* +fit rejected, p = 0\n.*# note: fit rejected: no model of the noise terms describes.*RESULT: FAIL"
  ARGS check --spec adi_adis16465 ${flags_data}/fit_rejected.json)
sigmatau_cli_test(NAME cli_check_fit_rejected_json EXIT 1
  STDOUT "\"fit_p_value\": 0\\.0,[^}]*\"fit_rejected\": true,[^}]*\"within_uncertainty\": false"
  ARGS check --spec adi_adis16465 ${flags_data}/fit_rejected.json --format json)
# A clear fail is not marked within uncertainty; a pass from an accepted fit carries no note.
sigmatau_cli_test(NAME cli_check_no_note_on_clear_rows EXIT 0
  STDOUT "gyro white_noise x +pass [^\n]*0\\.481.\ngyro bias_instability x +pass [^\n]*0\\.411.\n"
  ARGS check --spec adi_adis16465 ${flags_data}/fit_pass.json)

# analyze --spec on a log no noise-term model describes (a 0.05 Hz sinusoid of 200 deg/h over
# white noise): summary.md (printed) opens with the warning banner naming the rejected fits, and
# the compliance row built on gx's fit is marked (its verdict itself is unchanged).
set(flags_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_check_flags)
file(MAKE_DIRECTORY ${flags_dir})
sigmatau_cli_test(NAME cli_check_flags_simulate_sinusoid EXIT 0 WORKING_DIRECTORY ${flags_dir}
  STDOUT "wrote sinusoid\\.csv"
  ARGS simulate --model "N=0.15 deg/sqrt(h), SIN=200 deg/h @ 0.05 Hz" --rate 100 --duration 10min
       --seed 2 -o sinusoid.csv --force)
set_tests_properties(cli_check_flags_simulate_sinusoid PROPERTIES FIXTURES_SETUP check_flags_sinusoid)
sigmatau_cli_test(NAME cli_analyze_fit_rejected_marked EXIT 0 WORKING_DIRECTORY ${flags_dir}
  STDOUT "# sigmatau report\n\n> \\*\\*Warning:\\*\\* [0-9]+ warnings; fit rejected for gx, gy, gz: .*\\| gyro white noise x \\| [a-z]+ \\(fit rejected, p = [0-9.e-]+\\) \\|"
  ARGS analyze sinusoid.csv --time-column t --gyro-unit rad/s --spec safran_stim300 --ci 0.95
       -o analyze_sinusoid --force)
set_tests_properties(cli_analyze_fit_rejected_marked PROPERTIES FIXTURES_REQUIRED check_flags_sinusoid)
