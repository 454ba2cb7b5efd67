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
                 "-DARGS_B=adev@@${bag_dir}/imu.csv@@--time-column@@t@@--time-unit@@ns@@--gyro-unit@@rad/s@@--accel-unit@@m/s^2@@--format@@csv"
                 -P ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake)
list(APPEND bag_tests cli_bags_adev_same_as_csv)
add_test(NAME cli_bags_unindexed_same_as_csv
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=adev@@${bag_dir}/imu_unindexed.bag@@--columns@@gz,ax@@--format@@csv"
                 "-DARGS_B=adev@@${bag_dir}/imu.csv@@--time-column@@t@@--time-unit@@ns@@--gyro-unit@@rad/s@@--accel-unit@@m/s^2@@--columns@@gz,ax@@--format@@csv"
                 -P ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake)
list(APPEND bag_tests cli_bags_unindexed_same_as_csv)
# ROS 2: MCAP (zstd, CDR LE; lz4, XCDR2 BE, no summary), SQLite .db3 and a rosbag2 folder hold
# the same messages: the same table as the CSV.
foreach(ros2 imu_zstd.mcap imu_lz4.mcap imu.db3 imu_folder)
  string(MAKE_C_IDENTIFIER ${ros2} id)
  add_test(NAME cli_bags_${id}_same_as_csv
           COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                   "-DARGS_A=adev@@${bag_dir}/${ros2}@@--columns@@gy,az@@--format@@csv"
                   "-DARGS_B=adev@@${bag_dir}/imu.csv@@--time-column@@t@@--time-unit@@ns@@--gyro-unit@@rad/s@@--accel-unit@@m/s^2@@--columns@@gy,az@@--format@@csv"
                   -P ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake)
  list(APPEND bag_tests cli_bags_${id}_same_as_csv)
endforeach()
sigmatau_cli_test(NAME cli_bags_mcap_absent_topic EXIT 2
  STDERR "no topic /imu/raw in the bag; its topics: .*/imu/data \\(sensor_msgs/msg/Imu, 20000 messages\\)"
  ARGS psd ${bag_dir}/imu_zstd.mcap --topic /imu/raw)
sigmatau_cli_test(NAME cli_bags_db3_fit EXIT 0 STDOUT "# gx +joint"
  ARGS fit ${bag_dir}/imu.db3 --columns gx --stamp receive)
list(APPEND bag_tests cli_bags_mcap_absent_topic cli_bags_db3_fit)

# The memory estimate of a bag is its index's message count (6 values each), not its size: imu.bag
# (lz4, 1644301 bytes) holds 20000 Imu messages, 120000 values, 3.84 MB at 32 B each; its size
# over 16 B per value (the estimate for a bag without counts) would say 102768 values, which fit
# 3.5 MB.
sigmatau_cli_test(NAME cli_bags_memory_from_index EXIT 0
  STDERR "needs more than --memory 3500000 in memory; computing exactly out of core"
  ARGS adev ${bag_dir}/imu.bag --columns gx --memory 3500000)
list(APPEND bag_tests cli_bags_memory_from_index)
sigmatau_cli_test(NAME cli_bags_adev_topic EXIT 0
  STDOUT "/imu\\.bag: 20000 samples at 200 Hz.*# gx +oadev.*# az +oadev"
  ARGS adev ${bag_dir}/imu.bag --topic /imu/data)
sigmatau_cli_test(NAME cli_bags_auto_topic_unindexed EXIT 0
  STDOUT "/imu_unindexed\\.bag: 20000 samples at 200 Hz"
  ARGS adev ${bag_dir}/imu_unindexed.bag --columns gx)
# Without --topic the choice is named on stderr with the bag's topics, types and counts.
sigmatau_cli_test(NAME cli_bags_auto_topic_listed EXIT 0
  STDERR "note: .*imu\\.bag: reading /imu/data, the only sensor_msgs/Imu topic \\(choose with --topic\\); its topics: /imu/data \\(sensor_msgs/Imu, 20000 messages\\), /tf \\(tf2_msgs/TFMessage, 1000 messages\\)"
  ARGS adev ${bag_dir}/imu.bag --columns gz)
list(APPEND bag_tests cli_bags_auto_topic_listed)
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
# Corrupt bags (issue 10): exit 2 and the byte offset of the damaged record. The offsets come from
# the writers' layouts and make_test_bags checks them (kOffset*): 49 is MCAP's first chunk (after
# the 8-byte magic and the Header record), 4109 ROS 1's first chunk (after the 13-byte magic and
# the 4096-byte bag header record).
sigmatau_cli_test(NAME cli_bags_mcap_bad_crc EXIT 2
  STDERR "bad_crc\\.mcap: chunk at byte offset 49: CRC32 of the uncompressed records is 0x[0-9a-f]+, the chunk states 0x[0-9a-f]+"
  ARGS adev ${bag_dir}/bad_crc.mcap)
sigmatau_cli_test(NAME cli_bags_mcap_unknown_compression EXIT 2
  STDERR "brotli\\.mcap: chunk at byte offset 49: unknown compression \"brotli\""
  ARGS psd ${bag_dir}/brotli.mcap)
sigmatau_cli_test(NAME cli_bags_mcap_bad_length EXIT 2
  STDERR "bad_length\\.mcap: corrupt record at byte offset 185875: content of 1099511627776 bytes runs past"
  ARGS adev ${bag_dir}/bad_length.mcap)
sigmatau_cli_test(NAME cli_bags_ros1_unknown_compression EXIT 2
  STDERR "zz9\\.bag: chunk at byte offset 4109: unknown compression \"zz9\""
  ARGS fit ${bag_dir}/zz9.bag)
# wrong_type.bag is indexed: the connection record read is the index's copy, after the one chunk.
sigmatau_cli_test(NAME cli_bags_wrong_type EXIT 2
  STDERR "wrong_type\\.bag: connection record at byte offset 4449: topic /imu/data has type std_msgs/String, expected sensor_msgs/Imu"
  ARGS adev ${bag_dir}/wrong_type.bag --topic /imu/data)
sigmatau_cli_test(NAME cli_bags_wrong_type_no_topic EXIT 2
  STDERR "wrong_type\\.bag: no sensor_msgs/Imu topic in the bag; its topics: /imu/data \\(std_msgs/String, 1 message\\)"
  ARGS adev ${bag_dir}/wrong_type.bag)
sigmatau_cli_test(NAME cli_bags_not_an_imu_message EXIT 2
  STDERR "short_imu\\.mcap: record at byte offset 884: [0-9]+-byte message on /imu/data is not a sensor_msgs/Imu"
  ARGS adev ${bag_dir}/short_imu.mcap)
list(APPEND bag_tests cli_bags_mcap_bad_crc cli_bags_mcap_unknown_compression
     cli_bags_mcap_bad_length cli_bags_ros1_unknown_compression cli_bags_wrong_type
     cli_bags_wrong_type_no_topic cli_bags_not_an_imu_message)

# Out-of-order stamps (shuffled.bag: message 100 four messages late, 250/251 swapped): sorted within
# the window and reported on stderr; beyond the window refused with the message's byte offset (an
# uncompressed bag names the record; the message stamped 100 is the 105th record of the chunk).
sigmatau_cli_test(NAME cli_bags_reorder_sorted_and_reported EXIT 0
  STDOUT "shuffled\\.bag: 400 samples at 200 Hz"
  STDERR "note: .*shuffled\\.bag: 2 messages arrived out of stamp order and were put back in order \\(the latest 0\\.02 s late; --reorder-window 4 messages\\)"
  ARGS adev ${bag_dir}/shuffled.bag --columns gx --reorder-window 4)
sigmatau_cli_test(NAME cli_bags_reorder_beyond_window EXIT 2
  STDERR "shuffled\\.bag: message at byte offset [0-9]+ .*on /imu/data: its header stamp is 0\\.02 s before the latest stamp seen: .*reorder window \\(3 messages\\).*--reorder-window"
  ARGS adev ${bag_dir}/shuffled.bag --reorder-window 3)
list(APPEND bag_tests cli_bags_reorder_sorted_and_reported cli_bags_reorder_beyond_window)
# --gaps split needs the whole log in memory even when the bag is larger than --memory (out of
# core cannot split): imu_gap.bag (1000 messages missing) with --memory 1K gives the in-memory
# split table, byte for byte.
add_test(NAME cli_bags_gap_split_stays_in_memory
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=adev@@${bag_dir}/imu_gap.bag@@--gaps@@split@@--memory@@1K@@--format@@csv"
                 "-DARGS_B=adev@@${bag_dir}/imu_gap.bag@@--gaps@@split@@--format@@csv"
                 -P ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake)
list(APPEND bag_tests cli_bags_gap_split_stays_in_memory)

# calibrate reads a bag too: a simulated 16-position log converted to a ROS 1 bag (and to CSV with
# the same ns stamps and doubles) gives the same calibration table from either.
set(cal_bag_dir ${bag_dir}/calibrate)
add_test(NAME cli_bags_calibrate_simulate
         COMMAND sigmatau_cli simulate --model "N=0.005 deg/s/sqrt(Hz)"
                 --accel-model "N=100 ug/sqrt(Hz)" --rate 100 --sensors gyro,accel --positions 16
                 --dwell "10 s" --latitude "45 deg" --seed 11 --gyro-scale "0.4 %,-0.6 %,0.25 %"
                 --accel-bias "30 mg,-20 mg,25 mg" --force -o ${cal_bag_dir}/cal.csv)
add_test(NAME cli_bags_calibrate_convert
         COMMAND make_test_bags --from-csv ${cal_bag_dir}/cal.csv ${cal_bag_dir}/cal.bag
                 ${cal_bag_dir}/cal_ns.csv)
set_tests_properties(cli_bags_calibrate_simulate PROPERTIES FIXTURES_SETUP cal_bag_csv)
set_tests_properties(cli_bags_calibrate_convert PROPERTIES FIXTURES_REQUIRED cal_bag_csv
                     FIXTURES_SETUP cal_bag)
add_test(NAME cli_bags_calibrate_same_as_csv
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=calibrate@@${cal_bag_dir}/cal.bag@@--latitude@@45"
                 "-DARGS_B=calibrate@@${cal_bag_dir}/cal_ns.csv@@--time-column@@t@@--time-unit@@ns@@--latitude@@45"
                 -P ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake)
sigmatau_cli_test(NAME cli_bags_calibrate EXIT 0
  STDOUT "16 static intervals.*bias x +\\+29\\.[89]"
  ARGS calibrate ${cal_bag_dir}/cal.bag --topic /imu/data --latitude 45)
set_tests_properties(cli_bags_calibrate_same_as_csv cli_bags_calibrate PROPERTIES
                     FIXTURES_REQUIRED cal_bag)
set_tests_properties(${bag_tests} PROPERTIES FIXTURES_REQUIRED cli_bags)
