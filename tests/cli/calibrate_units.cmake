# `sigmatau calibrate` takes --gyro-unit / --accel-unit by the rules adev, psd, fit and analyze
# share (cli/channel_units): its own copy took a ROS bag's rad/s as deg/s when told so, read a
# bag's rates as increments under --kind increment, and never checked --gyro-unit on a log
# without gyro columns.
set(CAL_UNITS_DIR ${CMAKE_CURRENT_BINARY_DIR}/calibrate_units_cli)
file(MAKE_DIRECTORY ${CAL_UNITS_DIR})

# A ROS bag's units are fixed (REP 103): a contradicting --gyro-unit is refused before the log is
# read (it used to be applied, and only the rotation check tripped, blaming the gyro columns).
# The bag is the one tests/cli/bags.cmake writes (fixture cal_bag).
set(cal_units_bag ${CMAKE_CURRENT_BINARY_DIR}/cli_bags/calibrate/cal.bag)
sigmatau_cli_test(NAME cli_calibrate_bag_gyro_unit_refused EXIT 2
  STDERR "cal\\.bag: channel gx is rad/s \\(a ROS bag's sensor_msgs/Imu, whose units REP 103 fixes\\), but --gyro-unit deg/s says otherwise"
  ARGS calibrate ${cal_units_bag} --latitude 45 --gyro-unit deg/s)
# The same unit as the bag's is accepted (and gives the calibration).
sigmatau_cli_test(NAME cli_calibrate_bag_same_unit EXIT 0
  STDOUT "16 static intervals"
  ARGS calibrate ${cal_units_bag} --latitude 45 --gyro-unit rad/s --accel-unit m/s^2)
# A bag's messages are rates: --kind increment is refused (it used to read them as increments).
sigmatau_cli_test(NAME cli_calibrate_bag_kind_increment_refused EXIT 2
  STDERR "cal\\.bag: a ROS bag's sensor_msgs/Imu messages are rates \\(rad/s, m/s\\^2\\): leave out --kind increment"
  ARGS calibrate ${cal_units_bag} --latitude 45 --kind increment)
set_tests_properties(cli_calibrate_bag_gyro_unit_refused cli_calibrate_bag_same_unit
                     cli_calibrate_bag_kind_increment_refused PROPERTIES FIXTURES_REQUIRED cal_bag)

# --gyro-unit is checked on an accelerometer-only log too, as --temp-unit is without a
# temperature column (an acceleration given as the gyro's unit used to pass unnoticed, exit 0).
sigmatau_cli_test(NAME cli_calibrate_units_accel_only_sim EXIT 0 WORKING_DIRECTORY ${CAL_UNITS_DIR}
  STDOUT "wrote acc\\.csv"
  ARGS simulate --accel-model "N=100 ug/sqrt(Hz)" --rate 100 --sensors accel --positions 12
       --dwell "5 s" --seed 3 --force -o acc.csv)
set_tests_properties(cli_calibrate_units_accel_only_sim PROPERTIES
                     FIXTURES_SETUP cal_units_accel_only)
sigmatau_cli_test(NAME cli_calibrate_gyro_unit_checked_without_gyro EXIT 2
  WORKING_DIRECTORY ${CAL_UNITS_DIR}
  STDERR "--gyro-unit: expected angle/time \\(e\\.g\\. rad/s\\), found length/time\\^2 \\(g\\)"
  ARGS calibrate acc.csv --time-column t --gyro-unit g)
# The accelerometer-only log calibrates with its own unit given (the check is not in the way).
sigmatau_cli_test(NAME cli_calibrate_accel_only_unit EXIT 0 WORKING_DIRECTORY ${CAL_UNITS_DIR}
  STDOUT "12 static intervals"
  ARGS calibrate acc.csv --time-column t --accel-unit m/s^2 --gyro-unit deg/s)
set_tests_properties(cli_calibrate_gyro_unit_checked_without_gyro cli_calibrate_accel_only_unit
                     PROPERTIES FIXTURES_REQUIRED cal_units_accel_only)

# --gaps fill reads the log whole before the columns are chosen: the temperature column there
# is neither sensor and must not be asked for a unit (the shared rules would refuse it).
sigmatau_cli_test(NAME cli_calibrate_units_fill_temp_sim EXIT 0 WORKING_DIRECTORY ${CAL_UNITS_DIR}
  STDOUT "wrote temp\\.csv"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --accel-model "N=60 ug/sqrt(Hz)" --rate 100
       --sensors gyro,accel --positions 12 --seed 5 --out-unit "deg/s, mg"
       --temperature "15 degC @ 0 s, 35 degC @ 5 min" --force -o temp.csv)
set_tests_properties(cli_calibrate_units_fill_temp_sim PROPERTIES FIXTURES_SETUP cal_units_temp)
sigmatau_cli_test(NAME cli_calibrate_units_gaps_fill EXIT 0 WORKING_DIRECTORY ${CAL_UNITS_DIR}
  STDOUT "12 static intervals"
  ARGS calibrate temp.csv --time-column t --gaps fill --accel-unit mg --gyro-unit deg/s)
set_tests_properties(cli_calibrate_units_gaps_fill PROPERTIES FIXTURES_REQUIRED cal_units_temp)
