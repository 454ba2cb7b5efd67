# Extreme values and corrupt inputs (issue 28): each is refused with a clear message, or warned
# about, instead of a crash, an overflow or a silent empty result.
set(extreme_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_extreme)
file(REMOVE_RECURSE ${extreme_dir})
file(MAKE_DIRECTORY ${extreme_dir})
set(extreme_white ${CMAKE_CURRENT_SOURCE_DIR}/data/cli/white_2ch_10Hz.csv)

# Dynamic Allan windows too short to form: 1500 windows over 2000 samples are 2 samples each;
# windows of 16 samples fit 2 x 2000 / 16 - 1 = 249 times. Before: empty windows, no word.
sigmatau_cli_test(NAME cli_extreme_dynamic_windows_too_many EXIT 0
  STDERR "warning: dynamic Allan deviation: none of the 1500 windows asked was formed: over 2000 samples each would hold 2 samples, fewer than the 16 an OADEV curve needs. at most 249 windows fit"
  ARGS analyze ${extreme_white} --time-column t --gyro-unit deg/s --dynamic
       --dynamic-windows 1500 -o ${extreme_dir}/dynamic --force)

# A ROS 1 message on a connection no record declares (make_test_bags: undeclared.bag, message
# 200 of 400): skipped without a word while the topic note counted it. Now a counted warning
# naming the connection and the record, the index's count set against the messages found, and
# the topic note counting what was read.
sigmatau_cli_test(NAME cli_extreme_bag_undeclared_connection EXIT 0
  STDERR "sigmatau: note: .*undeclared.bag: reading /imu/data, the only sensor_msgs/Imu topic \\(choose with --topic\\). its topics: /imu/data \\(sensor_msgs/Imu, 399 messages\\).*warning: .*undeclared.bag: skipped 1 message on connection 9, which no connection record declares \\(the first: record at byte offset [0-9]+ \\(in the chunk at byte offset [0-9]+\\)\\): its topic is unknown.*warning: .*undeclared.bag: the bag states 400 messages on /imu/data, but 399 were found in it and read"
  ARGS adev ${CMAKE_CURRENT_BINARY_DIR}/cli_bags/undeclared.bag --gaps report --stat oadev)
set_tests_properties(cli_extreme_bag_undeclared_connection PROPERTIES FIXTURES_REQUIRED cli_bags)
# Under the default --gaps error the gap the skipped message leaves is the error, which says what
# the reader skipped.
sigmatau_cli_test(NAME cli_extreme_bag_undeclared_gap EXIT 2
  STDERR "time stamp gap of 10 ms .*before data row 200.*. while reading: skipped 1 message on connection 9"
  ARGS adev ${CMAKE_CURRENT_BINARY_DIR}/cli_bags/undeclared.bag --stat oadev)
set_tests_properties(cli_extreme_bag_undeclared_gap PROPERTIES FIXTURES_REQUIRED cli_bags)
