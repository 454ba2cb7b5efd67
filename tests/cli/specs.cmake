# CLI regression cases for `sigmatau specs`.
set(spec_fixtures ${PROJECT_SOURCE_DIR}/tests/data/specs)

sigmatau_cli_test(NAME cli_specs_list EXIT 0
  STDOUT "tdk_mpu6050 +consumer +0\\.005 º/s/√Hz.*safran_stim300|safran_stim300.*tdk_mpu6050"
  ARGS specs list)
sigmatau_cli_test(NAME cli_specs_list_count EXIT 0 STDOUT "1[2-9] data sheets"
  ARGS specs list)
# `show` prints each value as printed and in SI: 0.005 deg/s/sqrt(Hz) = 8.72665e-05 rad/sqrt(s).
sigmatau_cli_test(NAME cli_specs_show EXIT 0
  STDOUT "typ +0\\.005 º/s/√Hz += 8\\.72665e-05 rad/sqrt\\(s\\).*PS-MPU-6000A-00, rev\\. 3\\.4.*p\\. 12"
  ARGS specs show tdk_mpu6050)
sigmatau_cli_test(NAME cli_specs_show_not_specified EXIT 0
  STDOUT "not specified: .*bias_instability"
  ARGS specs show tdk_mpu6050)
sigmatau_cli_test(NAME cli_specs_show_file EXIT 0 STDOUT "Test T-1"
  ARGS specs show ${spec_fixtures}/good_minimal.yaml)
sigmatau_cli_test(NAME cli_specs_show_unknown EXIT 2 STDERR "no data sheet \"no_such_imu\""
  ARGS specs show no_such_imu)
sigmatau_cli_test(NAME cli_specs_show_bad_unit EXIT 2
  STDERR "unknown_unit\\.yaml:12:16: gyro\\.noise_density\\.typ: unknown unit \"furlong\""
  ARGS specs show ${spec_fixtures}/unknown_unit.yaml)
sigmatau_cli_test(NAME cli_specs_show_typ_above_max EXIT 2
  STDERR "typ_above_max\\.yaml:13:10: gyro\\.bias_instability: found typ 5 deg/h > max 3 deg/h, expected typ <= max"
  ARGS specs show ${spec_fixtures}/typ_above_max.yaml)
# An axis printed apart (`axes:`) is shown under its entry: the BMI088's Z accelerometer density.
sigmatau_cli_test(NAME cli_specs_show_axis_values EXIT 0
  STDOUT "typ     160 µg/√Hz [^\n]*\n    condition: X and Y axes[^\n]*\n    axis z:\n      typ   190 µg/√Hz"
  ARGS specs show bosch_bmi088)
