# CLI regression cases for `sigmatau convert` (values: THEORY.md section 9).
set(convert_out ${CMAKE_CURRENT_BINARY_DIR}/cli_convert)
file(MAKE_DIRECTORY ${convert_out})

# T1: 0.015 deg/s/sqrt(Hz) at 10 Hz -> 0.00225 (deg/s)^2, sigma 0.0474 deg/s.
sigmatau_cli_test(NAME cli_convert_t1 EXIT 0
  STDOUT "= 0\\.00225 \\(deg/s\\)\\^2.*= 0\\.0474342 deg/s"
  ARGS convert --noise-density "0.015 deg/s/sqrt(Hz)" --rate 10)
sigmatau_cli_test(NAME cli_convert_t1_one_sided EXIT 0
  STDOUT "one-sided.*= 0\\.001125 \\(deg/s\\)\\^2"
  ARGS convert --noise-density "0.015 deg/s/sqrt(Hz)" --rate 10 --density-convention one-sided)
# T2: 3 deg/h after T_ref = 100 s at 100 Hz -> 6.944e-11 (deg/s)^2.
sigmatau_cli_test(NAME cli_convert_t2 EXIT 0
  STDOUT "Q_bb = K\\^2 T_s .* \\(= 6\\.94444e-11 \\(deg/s\\)\\^2\\) per step"
  ARGS convert --bias-stability "3 deg/h" --rate "100 Hz" --tref 100s)
sigmatau_cli_test(NAME cli_convert_gm EXIT 0
  STDOUT "T_c = tau_min / 1\\.892 = 211\\.416 s"
  ARGS convert --bias-stability "3 deg/h" --rate 100 --bias-model gm --tau-min 400s)
sigmatau_cli_test(NAME cli_convert_spec_json EXIT 0
  STDOUT "\"gyro\".*\"white_noise\".*\"rate_hz\": 200"
  ARGS convert --spec tdk_mpu6050 --rate 200 --to json)
# T9: PX4 density 1.5e-3 rad/s/sqrt(Hz) -> EKF2_GYR_NOISE 0.015.
sigmatau_cli_test(NAME cli_convert_px4 EXIT 0 STDOUT "param set EKF2_GYR_NOISE 0\\.015 "
  ARGS convert --noise-density "1.5e-3 rad/s/sqrt(Hz)" --rate 200 --to px4)
sigmatau_cli_test(NAME cli_convert_kalibr_file EXIT 0 STDOUT "wrote .*imu\\.yaml \\(kalibr\\)"
  ARGS convert --spec safran_stim300 --rate 125 --to kalibr --force -o ${convert_out}/imu.yaml)
sigmatau_cli_test(NAME cli_convert_wrong_dimension EXIT 2
  STDERR "--noise-density: expected angle/sqrt\\(time\\)"
  ARGS convert --noise-density "3 deg/h" --rate 100)
sigmatau_cli_test(NAME cli_convert_no_rate EXIT 2 STDERR "--rate is required"
  ARGS convert --noise-density "0.015 deg/s/sqrt(Hz)")
sigmatau_cli_test(NAME cli_convert_bad_format EXIT 2 STDERR "expected kalibr, openvins"
  ARGS convert --noise-density "0.015 deg/s/sqrt(Hz)" --rate 10 --to rovio)
sigmatau_cli_test(NAME cli_convert_gm_from_k EXIT 2 STDERR "use --bias-model rw"
  ARGS convert --random-walk "0.02 deg/h/sqrt(h)" --rate 10 --bias-model gm)
# A sheet with no noise term (a fixture: gyro ranges, accelerometer RMS noise only).
sigmatau_cli_test(NAME cli_convert_nothing EXIT 2
  STDERR "no_noise_terms\\.yaml prints no noise density.*nothing to convert"
  ARGS convert --spec ${PROJECT_SOURCE_DIR}/tests/data/specs/no_noise_terms.yaml --rate 100)
sigmatau_cli_test(NAME cli_convert_no_output_without_force EXIT 2
  STDERR "exists; use --force" NO_FILE ${convert_out}/never.yaml
  ARGS convert --spec safran_stim300 --rate 125 --to kalibr -o ${PROJECT_SOURCE_DIR}/specs/safran_stim300.yaml)

# From a fit result (hand-written: N = 4.363e-5 rad/s/sqrt(Hz) on gx -> Kalibr writes it as is).
# 2.0e-05, not 2e-05: PyYAML (Kalibr) reads an exponent without a decimal point as a string.
sigmatau_cli_test(NAME cli_convert_from_fit EXIT 0 STDOUT "gyroscope_noise_density: 2.0e-05"
  ARGS convert --fit ${PROJECT_SOURCE_DIR}/tests/data/check/fit_pass.json --rate 200 --to kalibr)
# A gyro-only fit cannot fill Kalibr's accelerometer keys: the file says so and so does stderr.
sigmatau_cli_test(NAME cli_convert_incomplete_warns EXIT 0
  STDERR "the kalibr file lacks accelerometer_noise_density, accelerometer_random_walk"
  ARGS convert --fit ${PROJECT_SOURCE_DIR}/tests/data/check/fit_pass.json --rate 200 --to kalibr)
sigmatau_cli_test(NAME cli_convert_two_sources EXIT 2 STDERR "give one of"
  ARGS convert --fit ${PROJECT_SOURCE_DIR}/tests/data/check/fit_pass.json --spec tdk_mpu6050 --rate 200)
# Typed terms without --sensor: the sensor their unit names (an accelerometer's density here).
sigmatau_cli_test(NAME cli_convert_sensor_from_unit EXIT 0 STDOUT "^accel: f_s = 100 Hz"
  ARGS convert --noise-density "70 ug/sqrt(Hz)" --rate 100)
sigmatau_cli_test(NAME cli_convert_sensor_told_wins EXIT 2 STDERR "--noise-density: expected angle"
  ARGS convert --noise-density "70 ug/sqrt(Hz)" --sensor gyro --rate 100)
# A random walk typed per root hour is the Allan N itself: --density-convention one-sided does
# not divide it by sqrt(2) (0.3 deg/sqrt(h) = 0.005 deg/s/sqrt(Hz) exactly), as for a sheet's ARW.
sigmatau_cli_test(NAME cli_convert_arw_ignores_convention EXIT 0
  STDOUT "read as the random walk N itself.*\\(= 0\\.005 deg/s/sqrt\\(Hz\\)\\)"
  ARGS convert --noise-density "0.3 deg/sqrt(h)" --rate 100 --density-convention one-sided)
# The PX4 prediction interval and the Kalibr topic are the user's: EKF2_PREDICT_US = 8000 gives
# EKF2_GYR_NOISE = N / sqrt(0.008 s) = 0.015 x pi/180 / 0.0894427 = 0.002927006 rad/s.
sigmatau_cli_test(NAME cli_convert_px4_predict EXIT 0
  STDOUT "EKF2_PREDICT_US = 8000 us.*param set EKF2_GYR_NOISE 0.002927006 "
  ARGS convert --noise-density "0.015 deg/s/sqrt(Hz)" --rate 100 --to px4 --px4-predict 8000)
sigmatau_cli_test(NAME cli_convert_px4_predict_bad EXIT 2
  STDERR "--px4-predict: expected time \\(e.g. s\\), found 1/time"
  ARGS convert --noise-density "0.015 deg/s/sqrt(Hz)" --rate 100 --to px4 --px4-predict "3 Hz")
sigmatau_cli_test(NAME cli_convert_rostopic EXIT 0 STDOUT "\nrostopic: /imu/data\n"
  ARGS convert --noise-density "0.015 deg/s/sqrt(Hz)" --rate 100 --to kalibr --rostopic /imu/data)
