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
# T9: PX4 density 1.5e-3 rad/s/sqrt(Hz) -> EKF2_GYR_NOISE 0.015 (gyro alone: --allow-incomplete).
sigmatau_cli_test(NAME cli_convert_px4 EXIT 0 STDOUT "param set EKF2_GYR_NOISE 0\\.015 "
  ARGS convert --noise-density "1.5e-3 rad/s/sqrt(Hz)" --rate 200 --to px4 --allow-incomplete)
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
  ARGS convert --fit ${PROJECT_SOURCE_DIR}/tests/data/check/fit_pass.json --rate 200 --to kalibr
       --allow-incomplete)
# A gyro-only fit cannot fill Kalibr's accelerometer keys: refused (exit 2), naming the keys,
# the terms and how to give them; with --allow-incomplete written, and stderr says what lacks.
sigmatau_cli_test(NAME cli_convert_incomplete_refused EXIT 2
  STDERR "the kalibr file needs accelerometer_noise_density, accelerometer_random_walk, which noise-term fit .*fit_pass.json does not give \\(accelerometer white noise and bias; Kalibr stops on a missing key\\)\\. Give them with --noise-density, --random-walk or --bias-stability.*--allow-incomplete"
  ARGS convert --fit ${PROJECT_SOURCE_DIR}/tests/data/check/fit_pass.json --rate 200 --to kalibr)
sigmatau_cli_test(NAME cli_convert_incomplete_warns EXIT 0
  STDERR "the kalibr file lacks accelerometer_noise_density, accelerometer_random_walk \\(not in the input; written with --allow-incomplete\\)"
  STDOUT "^# Kalibr imu.yaml [^\n]*\n# WARNING: incomplete: accelerometer_noise_density"
  ARGS convert --fit ${PROJECT_SOURCE_DIR}/tests/data/check/fit_pass.json --rate 200 --to kalibr
       --allow-incomplete)
# The README's old quick-start case (issue 28): the BMI088 sheet prints noise densities only, so
# Kalibr's two random walks are missing. It used to exit 0 with a file Kalibr stops on.
sigmatau_cli_test(NAME cli_convert_sheet_incomplete EXIT 2 NO_FILE ${convert_out}/bmi088.yaml
  STDERR "the kalibr file needs accelerometer_random_walk, gyroscope_random_walk, which data sheet .*bosch_bmi088.yaml does not give \\(accelerometer bias, gyroscope bias"
  ARGS convert --spec bosch_bmi088 --rate 200 --to kalibr -o ${convert_out}/bmi088.yaml)
# Every consumer format is held to it; JSON, where a sensor not given is absent, is not.
foreach(format openvins vins-fusion gtsam px4)
  sigmatau_cli_test(NAME cli_convert_sheet_incomplete_${format} EXIT 2
    STDERR "the ${format} file needs .*--allow-incomplete"
    ARGS convert --spec bosch_bmi088 --rate 200 --to ${format})
endforeach()
sigmatau_cli_test(NAME cli_convert_sheet_incomplete_json EXIT 0 STDOUT "\"gyro\""
  ARGS convert --spec bosch_bmi088 --rate 200 --to json)
# The missing terms typed beside the sheet, each for the sensor its unit names: complete, and the
# file says where each came from. (Values are placeholders for the test, not the BMI088's.)
sigmatau_cli_test(NAME cli_convert_sheet_with_typed_terms EXIT 0
  STDOUT "from data sheet .*bosch_bmi088.yaml and command-line terms.*accelerometer_noise_density: 0.00147099[0-9]*.*accelerometer_random_walk: 0.0003 .*gyroscope_noise_density: 0.00024434[0-9]*.*gyroscope_random_walk: 1.0e-05"
  ARGS convert --spec bosch_bmi088 --rate 200 --to kalibr --noise-density "150 ug/sqrt(Hz)"
       --random-walk "3e-4 m/s^2/sqrt(s)" --random-walk "1e-5 rad/s^2/sqrt(Hz)")
sigmatau_cli_test(NAME cli_convert_typed_twice EXIT 2
  STDERR "--random-walk is given twice for the gyro"
  ARGS convert --spec bosch_bmi088 --rate 200 --random-walk "1e-5 rad/s^2/sqrt(Hz)"
       --random-walk "2e-5 rad/s^2/sqrt(Hz)")
sigmatau_cli_test(NAME cli_convert_two_sources EXIT 2 STDERR "give one of --spec FILE\\|NAME or --fit"
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
# The PX4 prediction interval and the Kalibr topic are the user's. EKF2 predicts every whole
# number of IMU intervals nearest to EKF2_PREDICT_US (ImuDownSampler): at 200 Hz, 8000 us is
# 1.6 intervals, so 2, dt = 10 ms, and EKF2_GYR_NOISE = N / sqrt(0.010 s)
# = 0.015 x pi/180 / 0.1 = 0.002617994 rad/s (it was N / sqrt(0.008 s) = 0.002927006, 12 % high).
sigmatau_cli_test(NAME cli_convert_px4_predict EXIT 0
  STDOUT "EKF2_PREDICT_US = 8000 us at 200 Hz gives 2 intervals, dt = 0.01 s.*param set EKF2_GYR_NOISE 0.002617994 "
  ARGS convert --noise-density "0.015 deg/s/sqrt(Hz)" --rate 200 --to px4 --px4-predict 8000
       --allow-incomplete)
# At 100 Hz, 5000 us is half an interval: EKF2 takes one, 10 ms (it was 5 ms: 41 % high).
sigmatau_cli_test(NAME cli_convert_px4_predict_100hz EXIT 0
  STDOUT "EKF2_PREDICT_US = 5000 us at 100 Hz gives 1 interval, dt = 0.01 s.*param set EKF2_GYR_NOISE 0.002617994 "
  ARGS convert --noise-density "0.015 deg/s/sqrt(Hz)" --rate 100 --to px4 --px4-predict "5 ms"
       --allow-incomplete)
# Above PX4's documented maximum (20000 us) or not whole microseconds: refused.
sigmatau_cli_test(NAME cli_convert_px4_predict_above_max EXIT 2
  STDERR "--px4-predict: PX4 prediction interval EKF2_PREDICT_US: found 25000 us, expected 1000 to 20000 us"
  ARGS convert --noise-density "0.015 deg/s/sqrt(Hz)" --rate 200 --to px4 --px4-predict 25000)
sigmatau_cli_test(NAME cli_convert_px4_predict_fraction EXIT 2
  STDERR "--px4-predict: .*found 8000.5 us, expected a whole number of microseconds"
  ARGS convert --noise-density "0.015 deg/s/sqrt(Hz)" --rate 200 --to px4 --px4-predict 8000.5)
sigmatau_cli_test(NAME cli_convert_px4_predict_bad EXIT 2
  STDERR "--px4-predict: expected time \\(e.g. s\\), found 1/time"
  ARGS convert --noise-density "0.015 deg/s/sqrt(Hz)" --rate 100 --to px4 --px4-predict "3 Hz")
sigmatau_cli_test(NAME cli_convert_rostopic EXIT 0 STDOUT "\nrostopic: /imu/data\n"
  ARGS convert --noise-density "0.015 deg/s/sqrt(Hz)" --rate 100 --to kalibr --rostopic /imu/data
       --allow-incomplete)
# The BMI088 prints its accelerometer density per axis (160 µg/√Hz on X and Y, 190 on Z: specs/
# bosch_bmi088.yaml `axes:`): a filter file with one value per sensor gets Z's, 190 µg/√Hz =
# 0.001863 m/s²/√Hz, and its header says the axes differ.
sigmatau_cli_test(NAME cli_convert_sheet_axis_values EXIT 0
  STDOUT "accelerometer noise density: axes differ, the largest axis is written.*accelerometer_noise_density: 0\\.0018632"
  ARGS convert --spec bosch_bmi088 --rate 200 --to kalibr --allow-incomplete)
