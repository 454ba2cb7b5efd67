# CLI cases for the units of a log with both sensors, in adev and psd (review D findings 3, 4):
# --gyro-unit / --accel-unit, a single --unit contradicting a column's name, --out-unit per
# sensor, and ROS bag channels that carry their sensor_msgs/Imu units (rad/s, m/s^2, REP 103).
set(su_imu6 ${PROJECT_SOURCE_DIR}/tests/data/cli/imu6_10Hz.csv)  # gx..gz deg/s, ax..az g
set(su_same ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake)

# One --unit for a 6-axis log: an angular rate cannot be the accelerometer's unit (it used to
# label and convert ax..az as deg/s, silently).
sigmatau_cli_test(NAME cli_adev_unit_contradicts_column EXIT 2
  STDERR "--unit deg/s is an angular rate .*column ax is an accelerometer axis by its name; give each sensor its unit with --gyro-unit and --accel-unit"
  ARGS adev ${su_imu6} --time-column t --unit deg/s --out-unit deg/h --taus 1)
sigmatau_cli_test(NAME cli_psd_unit_contradicts_column EXIT 2
  STDERR "--unit g is an acceleration .*column gx is a gyro axis by its name"
  ARGS psd ${su_imu6} --time-column t --unit g)
# Each sensor in its own unit, and --out-unit one per sensor (the order does not matter).
sigmatau_cli_test(NAME cli_adev_sensor_units EXIT 0
  STDOUT "gx,oadev,deg/h,.*az,oadev,ug,"
  ARGS adev ${su_imu6} --time-column t --gyro-unit deg/s --accel-unit g --out-unit ug,deg/h
       --taus 1 --format csv)
sigmatau_cli_test(NAME cli_psd_sensor_units EXIT 0
  STDOUT "gz +N = [0-9.e+-]+ \\[.*\\] deg/sqrt\\(h\\).*ax +N = [0-9.e+-]+ \\[.*\\] ug/sqrt\\(Hz\\)"
  ARGS psd ${su_imu6} --time-column t --gyro-unit deg/s --accel-unit g
       --out-unit "deg/sqrt(h),ug/sqrt(Hz)")
# The numbers per sensor are those of a run on that sensor's columns with one --unit (computed
# in g and scaled afterwards vs scaled to SI on reading: equal to the 7 printed digits).
add_test(NAME cli_adev_sensor_units_same_as_one_unit
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=adev@@${su_imu6}@@--time-column@@t@@--columns@@ax,az@@--unit@@g@@--out-unit@@ug@@--format@@csv"
                 "-DARGS_B=adev@@${su_imu6}@@--time-column@@t@@--columns@@ax,az@@--accel-unit@@g@@--gyro-unit@@deg/s@@--out-unit@@ug@@--format@@csv"
                 -P ${su_same})
add_test(NAME cli_psd_sensor_units_same_as_one_unit
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=psd@@${su_imu6}@@--time-column@@t@@--columns@@gy@@--unit@@deg/s@@--out-unit@@deg/sqrt(h)"
                 "-DARGS_B=psd@@${su_imu6}@@--time-column@@t@@--columns@@gy@@--gyro-unit@@deg/s@@--out-unit@@deg/sqrt(h)"
                 -P ${su_same})
sigmatau_cli_test(NAME cli_adev_unit_and_sensor_unit EXIT 2
  STDERR "--unit deg/s names one unit for every column; with --gyro-unit / --accel-unit leave it out"
  ARGS adev ${su_imu6} --time-column t --unit deg/s --gyro-unit deg/s)
sigmatau_cli_test(NAME cli_adev_sensor_unit_unnamed_column EXIT 2
  STDERR "column \"t_ms\" is neither a gyro nor an accelerometer by its name"
  ARGS adev ${PROJECT_SOURCE_DIR}/tests/data/cli/stamps_ms_100Hz.csv --rate 100
       --columns t_ms,gx --gyro-unit deg/s)
sigmatau_cli_test(NAME cli_adev_out_unit_fits_no_channel EXIT 2
  STDERR "--out-unit m/s\\^2 is length/time\\^2, but the deviations are angle/time"
  ARGS adev ${su_imu6} --time-column t --columns gx --gyro-unit deg/s --out-unit m/s^2)

# ROS bags: the channels are rad/s and m/s^2 without any --unit (make_test_bags writes them;
# imu.csv holds the same numbers with ns stamps).
set(su_bags ${CMAKE_CURRENT_BINARY_DIR}/cli_bags)
sigmatau_cli_test(NAME cli_bags_units_known EXIT 0
  STDOUT "# gx  oadev  \\[deg/h\\].*# ax  oadev  \\[m/s\\^2\\]"
  ARGS adev ${su_bags}/imu.bag --columns gx,ax --taus 1 --out-unit deg/h)
add_test(NAME cli_bags_units_same_as_csv_with_unit
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=adev@@${su_bags}/imu.bag@@--columns@@gx,gz@@--out-unit@@deg/h@@--format@@csv"
                 "-DARGS_B=adev@@${su_bags}/imu.csv@@--time-column@@t@@--time-unit@@ns@@--columns@@gx,gz@@--unit@@rad/s@@--out-unit@@deg/h@@--format@@csv"
                 -P ${su_same})
sigmatau_cli_test(NAME cli_bags_psd_units_known EXIT 0
  STDOUT "gx +N = .* rad/s/sqrt\\(Hz\\).*az +N = .* m/s\\^2/sqrt\\(Hz\\)"
  ARGS psd ${su_bags}/imu_zstd.mcap)
# A unit that contradicts the message's: refused, even of the same dimension.
sigmatau_cli_test(NAME cli_bags_unit_contradicts EXIT 2
  STDERR "channel gx is rad/s \\(a ROS bag's sensor_msgs/Imu, whose units REP 103 fixes\\), but --unit deg/s says otherwise"
  ARGS adev ${su_bags}/imu.bag --columns gx --unit deg/s)
sigmatau_cli_test(NAME cli_bags_gyro_unit_contradicts EXIT 2
  STDERR "channel gy is rad/s .*but --gyro-unit deg/s says otherwise"
  ARGS psd ${su_bags}/imu.db3 --columns gy,az --gyro-unit deg/s)
sigmatau_cli_test(NAME cli_bags_unit_agrees EXIT 0 STDOUT "# gz  oadev  \\[rad/s\\]"
  ARGS adev ${su_bags}/imu.bag --columns gz --unit rad/s --taus 1)
sigmatau_cli_test(NAME cli_bags_kind_refused EXIT 2 STDERR "messages are rates"
  ARGS adev ${su_bags}/imu.bag --kind increment)
set_tests_properties(cli_bags_units_known cli_bags_units_same_as_csv_with_unit
                     cli_bags_psd_units_known cli_bags_unit_contradicts
                     cli_bags_gyro_unit_contradicts cli_bags_unit_agrees cli_bags_kind_refused
                     PROPERTIES FIXTURES_REQUIRED cli_bags)
# Only one sensor's unit: the other sensor's columns stay in the input unit, and that is said.
sigmatau_cli_test(NAME cli_adev_sensor_unit_one_given EXIT 0
  STDOUT "ax,oadev,,"
  STDERR "no --accel-unit: ax, ay, az left in the input unit"
  ARGS adev ${su_imu6} --time-column t --gyro-unit deg/s --taus 1 --format csv)
# The units are checked from the header, before the log is read: a log whose third row is
# broken gets the unit error, not the row's (a long log would otherwise be read to the end first).
set(su_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_sensor_units)
file(MAKE_DIRECTORY ${su_dir})
file(WRITE ${su_dir}/broken.csv "t,gyro_x,accel_x\n0.0,0.1,0.01\n0.1,0.2,oops\n")
sigmatau_cli_test(NAME cli_adev_unit_checked_before_reading EXIT 2
  STDERR "column accel_x is an accelerometer axis by its name"
  ARGS adev ${su_dir}/broken.csv --time-column t --unit deg/s)
sigmatau_cli_test(NAME cli_psd_unit_checked_before_reading EXIT 2
  STDERR "column accel_x is an accelerometer axis by its name"
  ARGS psd ${su_dir}/broken.csv --time-column t --unit mdps)
# Out of core (--memory 1K) scales each channel by its sensor's unit as the in-memory path does.
add_test(NAME cli_adev_sensor_units_out_of_core
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=adev@@${su_imu6}@@--time-column@@t@@--gyro-unit@@deg/s@@--accel-unit@@g@@--out-unit@@deg/h,ug@@--format@@csv"
                 "-DARGS_B=adev@@${su_imu6}@@--time-column@@t@@--gyro-unit@@deg/s@@--accel-unit@@g@@--out-unit@@deg/h,ug@@--format@@csv@@--memory@@1K"
                 -P ${su_same})
