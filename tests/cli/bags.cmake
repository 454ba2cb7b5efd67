# CLI regression cases for ROS bags (issue 10). The bags are written at test time by
# make_test_bags (tests/support/make_test_bags.cpp lists them) into ${bag_dir}.
set(bag_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_bags)
add_test(NAME cli_bags_make COMMAND make_test_bags ${bag_dir})
set_tests_properties(cli_bags_make PROPERTIES FIXTURES_SETUP cli_bags)
set(bag_tests)

# A bag and the same data as CSV (integer ns stamps, 17-digit values) give the same table, byte
# for byte (CSV output carries no file name).
add_test(NAME cli_bags_adev_same_as_csv
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=adev@@${bag_dir}/imu.bag@@--topic@@/imu/data@@--format@@csv"
                 "-DARGS_B=adev@@${bag_dir}/imu.csv@@--time-column@@t@@--time-unit@@ns@@--format@@csv"
                 -P ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake)
list(APPEND bag_tests cli_bags_adev_same_as_csv)
add_test(NAME cli_bags_unindexed_same_as_csv
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=adev@@${bag_dir}/imu_unindexed.bag@@--columns@@gz,ax@@--format@@csv"
                 "-DARGS_B=adev@@${bag_dir}/imu.csv@@--time-column@@t@@--time-unit@@ns@@--columns@@gz,ax@@--format@@csv"
                 -P ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake)
list(APPEND bag_tests cli_bags_unindexed_same_as_csv)
# ROS 2: MCAP (zstd, CDR LE; lz4, XCDR2 BE, no summary), SQLite .db3 and a rosbag2 folder hold
# the same messages: the same table as the CSV.
foreach(ros2 imu_zstd.mcap imu_lz4.mcap imu.db3 imu_folder)
  string(MAKE_C_IDENTIFIER ${ros2} id)
  add_test(NAME cli_bags_${id}_same_as_csv
           COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                   "-DARGS_A=adev@@${bag_dir}/${ros2}@@--columns@@gy,az@@--format@@csv"
                   "-DARGS_B=adev@@${bag_dir}/imu.csv@@--time-column@@t@@--time-unit@@ns@@--columns@@gy,az@@--format@@csv"
                   -P ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake)
  list(APPEND bag_tests cli_bags_${id}_same_as_csv)
endforeach()
sigmatau_cli_test(NAME cli_bags_mcap_absent_topic EXIT 2
  STDERR "no topic /imu/raw in the bag; its topics: .*/imu/data \\(sensor_msgs/msg/Imu, 20000 messages\\)"
  ARGS psd ${bag_dir}/imu_zstd.mcap --topic /imu/raw)
sigmatau_cli_test(NAME cli_bags_db3_fit EXIT 0 STDOUT "# gx +joint"
  ARGS fit ${bag_dir}/imu.db3 --columns gx --stamp receive)
list(APPEND bag_tests cli_bags_mcap_absent_topic cli_bags_db3_fit)

sigmatau_cli_test(NAME cli_bags_adev_topic EXIT 0
  STDOUT "/imu\\.bag: 20000 samples at 200 Hz.*# gx +oadev.*# az +oadev"
  ARGS adev ${bag_dir}/imu.bag --topic /imu/data)
sigmatau_cli_test(NAME cli_bags_auto_topic_unindexed EXIT 0
  STDOUT "/imu_unindexed\\.bag: 20000 samples at 200 Hz"
  ARGS adev ${bag_dir}/imu_unindexed.bag --columns gx)
sigmatau_cli_test(NAME cli_bags_stamp_receive EXIT 0 STDOUT "20000 samples at 200 Hz"
  ARGS adev ${bag_dir}/imu.bag --stamp receive --columns ax --reorder-window 0)
sigmatau_cli_test(NAME cli_bags_two_imu_topics EXIT 2
  STDERR "2 sensor_msgs/Imu topics; choose one with --topic; its topics: /imu/a \\(sensor_msgs/Imu, 100 messages\\), /imu/b \\(sensor_msgs/Imu, 100 messages\\)"
  ARGS adev ${bag_dir}/two_imu.bag)
sigmatau_cli_test(NAME cli_bags_absent_topic EXIT 2
  STDERR "no topic /imu/raw in the bag; its topics: /imu/data \\(sensor_msgs/Imu, 20000 messages\\), /tf \\(tf2_msgs/TFMessage, 1000 messages\\)"
  ARGS adev ${bag_dir}/imu.bag --topic /imu/raw)
# The first chunk follows the 13-byte magic and the 4096-byte bag header record: offset 4109.
sigmatau_cli_test(NAME cli_bags_truncated EXIT 2
  STDERR "truncated\\.bag: truncated record at byte offset 4109"
  ARGS adev ${bag_dir}/truncated.bag)
sigmatau_cli_test(NAME cli_bags_unknown_channel EXIT 2
  STDERR "unknown channel \"wx\" for a sensor_msgs/Imu topic \\(available: gx, gy, gz, ax, ay, az\\)"
  ARGS adev ${bag_dir}/imu.bag --columns wx)
sigmatau_cli_test(NAME cli_bags_bad_stamp EXIT 2 STDERR "unknown bag stamp \"sensor\""
  ARGS adev ${bag_dir}/imu.bag --stamp sensor)
sigmatau_cli_test(NAME cli_bags_time_column_refused EXIT 2
  STDERR "--time-column and --time-unit are for text logs"
  ARGS adev ${bag_dir}/imu.bag --time-column t)
sigmatau_cli_test(NAME cli_bags_binary_refused EXIT 2
  STDERR "--binary, --channels, --big-endian and --skip-bytes are for raw binary logs"
  ARGS adev ${bag_dir}/imu.bag --binary f64 --channels 6)
sigmatau_cli_test(NAME cli_bags_topic_on_text_refused EXIT 2
  STDERR "--topic, --stamp and --reorder-window are for ROS bags"
  ARGS adev ${bag_dir}/imu.csv --time-column t --topic /imu/data)
sigmatau_cli_test(NAME cli_bags_negative_window EXIT 2 STDERR "--reorder-window must be >= 0"
  ARGS adev ${bag_dir}/imu.bag --reorder-window -1)
# The other log-reading verbs take a bag.
sigmatau_cli_test(NAME cli_bags_psd EXIT 0 STDOUT "gx +N = 7\\.[0-9]+e-05"
  ARGS psd ${bag_dir}/imu.bag --topic /imu/data)
sigmatau_cli_test(NAME cli_bags_fit EXIT 0 STDOUT "# gy +joint"
  ARGS fit ${bag_dir}/imu.bag --columns gx,gy)
sigmatau_cli_test(NAME cli_bags_analyze EXIT 0 STDOUT "wrote"
  ARGS analyze ${bag_dir}/imu_unindexed.bag --columns gx,gy,gz -o ${bag_dir}/analyze_out --force)
list(APPEND bag_tests cli_bags_adev_topic cli_bags_auto_topic_unindexed cli_bags_stamp_receive
     cli_bags_two_imu_topics cli_bags_absent_topic cli_bags_truncated cli_bags_unknown_channel
     cli_bags_bad_stamp cli_bags_time_column_refused cli_bags_binary_refused
     cli_bags_topic_on_text_refused cli_bags_negative_window cli_bags_psd cli_bags_fit
     cli_bags_analyze)
set_tests_properties(${bag_tests} PROPERTIES FIXTURES_REQUIRED cli_bags)
