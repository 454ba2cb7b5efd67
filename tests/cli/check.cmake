# `sigmatau check`: exit 0 when nothing fails, 1 when a check fails, 2 on bad input.
set(check_data ${PROJECT_SOURCE_DIR}/tests/data/check)
sigmatau_cli_test(NAME cli_check_pass EXIT 0 STDOUT "gyro white_noise x +pass.*RESULT: no check failed"
  ARGS check --spec adi_adis16465 ${check_data}/fit_pass.json)
sigmatau_cli_test(NAME cli_check_fail EXIT 1 STDOUT "gyro white_noise x +fail.*RESULT: FAIL"
  ARGS check --spec adi_adis16465 ${check_data}/fit_fail.json)
sigmatau_cli_test(NAME cli_check_json EXIT 0 STDOUT "\"verdict\": \"pass\""
  ARGS check --spec adi_adis16465 ${check_data}/fit_pass.json --format json)
sigmatau_cli_test(NAME cli_check_unknown_spec EXIT 2 STDERR "no_such_imu"
  ARGS check --spec no_such_imu ${check_data}/fit_pass.json)
sigmatau_cli_test(NAME cli_check_not_a_result EXIT 2 STDERR "not a sigmatau"
  ARGS check --spec adi_adis16465 ${check_data}/not_a_result.json)
