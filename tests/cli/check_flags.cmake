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
