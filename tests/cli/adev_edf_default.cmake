# adev's default EDF model follows the data (issue 28): the exact discrete EDF for IMU data, whose
# noise is discrete (bench/results_edf_coverage.md), Greenhall's for clock data and values without
# a unit, as Stable32 prints them. At m = 1 on white noise with n = 1999 terms the discrete EDF is
# 2 n^2 / (3 n - 1) = 1333 and Greenhall's 1565 (tests/test_edf_exact.cpp).
set(edf_white ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv)
set(edf_phase ${PROJECT_SOURCE_DIR}/tests/data/cli/clock_phase_1000.txt)
sigmatau_cli_test(NAME cli_adev_edf_default_gyro EXIT 0
  STDOUT "0\\.1 +1 +1999 +0 +1333 "
  ARGS adev ${edf_white} --time-column t --unit deg/s --taus 0.1 --columns gx)
sigmatau_cli_test(NAME cli_adev_edf_default_gyro_json EXIT 0 STDOUT "\"edf_model\": \"discrete\""
  ARGS adev ${edf_white} --time-column t --gyro-unit deg/s --taus 0.1 --format json)
sigmatau_cli_test(NAME cli_adev_edf_default_gyro_increment EXIT 0 STDOUT "\"edf_model\": \"discrete\""
  ARGS adev ${edf_white} --time-column t --kind increment --unit deg --taus 0.1 --format json)
sigmatau_cli_test(NAME cli_adev_edf_default_no_unit EXIT 0
  STDOUT "0\\.1 +1 +1999 +0 +1565 "
  ARGS adev ${edf_white} --time-column t --taus 0.1 --columns gx)
sigmatau_cli_test(NAME cli_adev_edf_override_greenhall EXIT 0
  STDOUT "0\\.1 +1 +1999 +0 +1565 "
  ARGS adev ${edf_white} --time-column t --unit deg/s --taus 0.1 --columns gx --edf greenhall)
# Stream mode's strided EDF follows Greenhall's algorithm: its default stays greenhall.
sigmatau_cli_test(NAME cli_adev_edf_default_stream EXIT 0 STDOUT "\"edf_model\": \"greenhall\""
  ARGS adev ${edf_white} --time-column t --unit deg/s --taus 0.1 --mode stream --format json)
# Clock data: phase in s, Greenhall's as Stable32 (OADEV m = 1, white FM, N = 1000: 781.2).
sigmatau_cli_test(NAME cli_adev_edf_default_clock EXIT 0
  STDOUT "\"edf_model\": \"greenhall\""
  ARGS adev ${edf_phase} --kind phase --rate 1 --unit s --taus 1 --format json)
# analyze follows the same rule and records it in results.json.
set(edf_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_edf_default)
file(REMOVE_RECURSE ${edf_dir})
sigmatau_cli_test(NAME cli_analyze_edf_default_imu EXIT 0
  ARGS analyze ${PROJECT_SOURCE_DIR}/tests/data/cli/imu6_10Hz.csv --time-column t
       --gyro-unit deg/s --accel-unit g -o ${edf_dir}/imu --force)
add_test(NAME cli_analyze_edf_default_imu_recorded
         COMMAND ${CMAKE_COMMAND} -DFILE=${edf_dir}/imu/results.json
                 "-DPATTERN=\"edf_model\": \"discrete\""
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/expect_in_file.cmake)
set_tests_properties(cli_analyze_edf_default_imu_recorded PROPERTIES
                     DEPENDS cli_analyze_edf_default_imu)
