# `sigmatau calibrate --memory`: a log with more samples than --memory keeps them in a temporary
# file and gives the same calibration, byte for byte, as the log held in memory: CSV with a
# temperature column, increments, a ROS 1 bag and stdin. Included by tests/CMakeLists.txt to add
# the tests; run with -P it is the comparison.
if(CMAKE_SCRIPT_MODE_FILE)
  # cmake -P mode: CMD, ARGS ("@@"-separated), STDIN (optional file fed to both runs). Runs the
  # calibration to JSON with the default --memory and with --memory 1K; both must exit 0, only
  # the second may say it keeps the samples in a temporary file, and the outputs must be equal.
  string(REPLACE "@@" ";" args "${ARGS}")
  set(stdin_args)
  if(NOT "${STDIN}" STREQUAL "")
    set(stdin_args INPUT_FILE ${STDIN})
  endif()
  execute_process(COMMAND ${CMD} ${args} --format json ${stdin_args}
                  RESULT_VARIABLE code_a OUTPUT_VARIABLE out_a ERROR_VARIABLE err_a)
  execute_process(COMMAND ${CMD} ${args} --format json --memory 1K ${stdin_args}
                  RESULT_VARIABLE code_b OUTPUT_VARIABLE out_b ERROR_VARIABLE err_b)
  if(NOT code_a EQUAL 0 OR NOT code_b EQUAL 0)
    message(FATAL_ERROR "exit codes ${code_a} and ${code_b}, expected 0\n${err_a}\n${err_b}")
  endif()
  if(err_a MATCHES "temporary file" OR NOT err_b MATCHES "keeping them in a temporary file")
    message(FATAL_ERROR "expected only the --memory 1K run to use a temporary file:\n${err_a}\n---\n${err_b}")
  endif()
  if(NOT out_a MATCHES "\"accelerometer\"")
    message(FATAL_ERROR "no calibration in the output:\n${out_a}")
  endif()
  if(NOT out_a STREQUAL out_b)
    message(FATAL_ERROR "the in-memory and the bounded calibration differ\n--- memory ---\n${out_a}\n--- bounded ---\n${out_b}")
  endif()
  return()
endif()

set(cal_bounded_dir ${CMAKE_CURRENT_BINARY_DIR}/calibrate_bounded)
file(MAKE_DIRECTORY ${cal_bounded_dir})
set(cal_csv ${CMAKE_CURRENT_BINARY_DIR}/calibrate_cli/cal.csv)  # written by cli_calibrate_simulate
# Rate samples with a temperature ramp (the bias temperature models are fitted).
add_test(NAME cli_calibrate_bounded_same_json
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS=calibrate@@${cal_csv}@@--time-column@@t@@--latitude@@45"
                 -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(cli_calibrate_bounded_same_json PROPERTIES DEPENDS cli_calibrate_simulate)
# A pipe cannot be read twice: its samples go to the temporary file as they arrive.
add_test(NAME cli_calibrate_bounded_stdin_same_json
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS=calibrate@@-@@--time-column@@t@@--latitude@@45" -DSTDIN=${cal_csv}
                 -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(cli_calibrate_bounded_stdin_same_json PROPERTIES DEPENDS cli_calibrate_simulate)
# Increments (delta angle and velocity per sample) at 200 Hz.
sigmatau_cli_test(NAME cli_calibrate_bounded_increments_sim EXIT 0 WORKING_DIRECTORY ${cal_bounded_dir}
  STDOUT "wrote inc\\.csv"
  ARGS simulate --model "N=0.005 deg/s/sqrt(Hz)" --accel-model "N=100 ug/sqrt(Hz)" --rate 200
       --kind increment --sensors gyro,accel --positions 18 --dwell "6 s" --latitude "45 deg"
       --seed 3 --gyro-scale "0.4 %,-0.6 %,0.25 %" --accel-bias "30 mg,-20 mg,25 mg"
       --force -o inc.csv)
add_test(NAME cli_calibrate_bounded_increments_same_json
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS=calibrate@@${cal_bounded_dir}/inc.csv@@--time-column@@t@@--kind@@increment@@--latitude@@45"
                 -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(cli_calibrate_bounded_increments_same_json PROPERTIES
                     DEPENDS cli_calibrate_bounded_increments_sim)
# The 16-position ROS 1 bag of bags.cmake.
add_test(NAME cli_calibrate_bounded_bag_same_json
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS=calibrate@@${CMAKE_CURRENT_BINARY_DIR}/cli_bags/calibrate/cal.bag@@--topic@@/imu/data@@--latitude@@45"
                 -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(cli_calibrate_bounded_bag_same_json PROPERTIES FIXTURES_REQUIRED cal_bag)
sigmatau_cli_test(NAME cli_calibrate_bad_memory EXIT 2 STDERR "--memory must be a size"
  ARGS calibrate ${cal_csv} --time-column t --memory lots)
# A single static position (the common mistake: a static noise log given to calibrate) is refused
# with the count of orientations and the gravity directions never visited.
sigmatau_cli_test(NAME cli_calibrate_one_position EXIT 2 WORKING_DIRECTORY ${cal_bounded_dir}
  STDERR "1 static interval but only 1 distinct orientation \\(need >= 9\\); gravity was never near"
  ARGS calibrate static.csv --time-column t --memory 1K)
sigmatau_cli_test(NAME cli_calibrate_one_position_sim EXIT 0 WORKING_DIRECTORY ${cal_bounded_dir}
  STDOUT "wrote static\\.csv"
  ARGS simulate --model "N=0.005 deg/s/sqrt(Hz)" --accel-model "N=100 ug/sqrt(Hz)" --rate 100
       --sensors gyro,accel --duration "60 s" --force -o static.csv)
set_tests_properties(cli_calibrate_one_position PROPERTIES DEPENDS cli_calibrate_one_position_sim)
# Options checked whether or not the log needs them (bad-input audit): a temperature unit that is
# no temperature, on a log without a temperature column, and an orientation count below one, were
# both accepted silently.
sigmatau_cli_test(NAME cli_calibrate_temp_unit_without_column EXIT 2 WORKING_DIRECTORY ${cal_bounded_dir}
  STDERR "--temp-unit: expected temperature \\(e\\.g\\. K\\), found length/time"
  ARGS calibrate static.csv --time-column t --temp-unit m/s)
sigmatau_cli_test(NAME cli_calibrate_min_orientations_range EXIT 2 WORKING_DIRECTORY ${cal_bounded_dir}
  STDERR "--min-orientations -1: must be 9 to 1000"
  ARGS calibrate static.csv --time-column t --min-orientations -1)
set_tests_properties(cli_calibrate_temp_unit_without_column cli_calibrate_min_orientations_range
                     PROPERTIES DEPENDS cli_calibrate_one_position_sim)
