# `sigmatau analyze --memory`: a log that would not fit is analysed in bounded memory (values and
# phase in temporary files) and writes the same files as the in-memory analysis; stdin stays in
# memory. Included by tests/CMakeLists.txt to add the tests; run with -P it is the comparison.
if(CMAKE_SCRIPT_MODE_FILE)
  # cmake -P mode: CMD, ARGS ("@@"-separated), DIR. Runs the analysis in memory (the default
  # --memory) into DIR/memory and with --memory 1K into DIR/bounded; both must exit 0, only the
  # second may say "bounded memory", and every file must be the same once the creation time
  # (the one thing that differs between two runs) is masked.
  string(REPLACE "@@" ";" args "${ARGS}")
  file(REMOVE_RECURSE ${DIR})
  execute_process(COMMAND ${CMD} ${args} -o ${DIR}/memory
                  RESULT_VARIABLE code_a OUTPUT_QUIET ERROR_VARIABLE err_a)
  execute_process(COMMAND ${CMD} ${args} -o ${DIR}/bounded --memory 1K
                  RESULT_VARIABLE code_b OUTPUT_QUIET ERROR_VARIABLE err_b)
  if(NOT code_a EQUAL 0 OR NOT code_b EQUAL 0)
    message(FATAL_ERROR "exit codes ${code_a} and ${code_b}, expected 0\n${err_a}\n${err_b}")
  endif()
  if(err_a MATCHES "bounded memory" OR NOT err_b MATCHES "analysing it in bounded memory")
    message(FATAL_ERROR "expected only the --memory 1K run in bounded memory:\n${err_a}\n---\n${err_b}")
  endif()
  file(GLOB files RELATIVE ${DIR}/memory ${DIR}/memory/*)
  list(LENGTH files count)
  if(count LESS 3)
    message(FATAL_ERROR "only ${count} files in ${DIR}/memory")
  endif()
  foreach(f IN LISTS files)
    if(NOT EXISTS ${DIR}/bounded/${f})
      message(FATAL_ERROR "${f}: written in memory, missing from the bounded run")
    endif()
    file(READ ${DIR}/memory/${f} a)
    file(READ ${DIR}/bounded/${f} b)
    set(stamp "[0-9][0-9][0-9][0-9]-[0-9][0-9]-[0-9][0-9]T[0-9][0-9]:[0-9][0-9]:[0-9][0-9]Z")
    string(REGEX REPLACE "${stamp}" "<created>" a "${a}")
    string(REGEX REPLACE "${stamp}" "<created>" b "${b}")
    if(NOT a STREQUAL b)
      message(FATAL_ERROR "${f} differs between the in-memory and the bounded run (${DIR})")
    endif()
  endforeach()
  file(GLOB extra RELATIVE ${DIR}/bounded ${DIR}/bounded/*)
  list(LENGTH extra count_b)
  if(NOT count_b EQUAL count)
    message(FATAL_ERROR "${count} files in memory, ${count_b} bounded")
  endif()
  return()
endif()

set(analyze_bounded_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_analyze_bounded)
set(example ${PROJECT_SOURCE_DIR}/examples/gyro_static_100Hz.csv.gz)
# Every stage: trim, two statistics, dynamic windows, filter files at two rates, a spec, plots.
add_test(NAME cli_analyze_bounded_same_files
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>" -DDIR=${analyze_bounded_dir}/example
                 "-DARGS=analyze@@${example}@@--time-column@@t@@--gyro-unit@@deg/s@@--stat@@oadev,mdev@@--dynamic@@--rate-out@@100@@--rate-out@@200@@--spec@@adi_adis16465@@--threads@@2"
                 -P ${CMAKE_CURRENT_LIST_FILE})
# A ROS 1 bag (gyro and accelerometer triads, bag stamps), with a fixed trim.
add_test(NAME cli_analyze_bounded_bag_same_files
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>" -DDIR=${analyze_bounded_dir}/bag
                 "-DARGS=analyze@@${CMAKE_CURRENT_BINARY_DIR}/cli_bags/imu.bag@@--topic@@/imu/data@@--trim@@2"
                 -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(cli_analyze_bounded_bag_same_files PROPERTIES FIXTURES_REQUIRED cli_bags)
# A pipe is analysed in memory whatever --memory says (the bounded path would refuse stdin with
# exit 2).
sigmatau_cli_test(NAME cli_analyze_bounded_stdin_in_memory EXIT 0 STDOUT "wrote "
  STDIN ${example}
  ARGS analyze - --time-column t --memory 1K -o ${analyze_bounded_dir}/stdin --force)
sigmatau_cli_test(NAME cli_analyze_bounded_bad_memory EXIT 2 STDERR "--memory must be a size"
  ARGS analyze ${example} --time-column t --memory lots -o ${analyze_bounded_dir}/bad)
