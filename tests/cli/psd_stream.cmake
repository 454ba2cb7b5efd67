# CLI regression cases for `sigmatau psd` reading a log segment by segment (issues 3 and 10):
# the streamed PSD is the in-memory one, bit for bit (the JSON prints every double to 17
# significant digits). The in-memory reference is --gaps fill on a log without gaps: that policy
# reads the whole log into memory (fill_gaps) and calls welch_psd on it.
set(example ${PROJECT_SOURCE_DIR}/examples/gyro_static_100Hz.csv.gz)
set(psd_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_psd_stream)
file(MAKE_DIRECTORY ${psd_dir})

# A cmake -P helper like support/expect_same_output.cmake, for outputs that may differ only in
# lines matching DROP (the input path, the channel names): runs CMD with ARGS_A (stdin from
# STDIN_A when set) and ARGS_B, both must exit 0 and print the same stdout otherwise.
set(psd_same ${psd_dir}/expect_same_but.cmake)
file(WRITE ${psd_same} [=[
string(REPLACE "@@" ";" a "${ARGS_A}")
string(REPLACE "@@" ";" b "${ARGS_B}")
if(STDIN_A)
  execute_process(COMMAND ${CMD} ${a} INPUT_FILE ${STDIN_A} RESULT_VARIABLE code_a
                  OUTPUT_VARIABLE out_a ERROR_VARIABLE err_a)
else()
  execute_process(COMMAND ${CMD} ${a} RESULT_VARIABLE code_a OUTPUT_VARIABLE out_a
                  ERROR_VARIABLE err_a)
endif()
execute_process(COMMAND ${CMD} ${b} RESULT_VARIABLE code_b OUTPUT_VARIABLE out_b ERROR_VARIABLE err_b)
if(NOT code_a EQUAL 0 OR NOT code_b EQUAL 0)
  message(FATAL_ERROR "exit codes ${code_a} and ${code_b}, expected 0\n${err_a}\n${err_b}")
endif()
string(REGEX REPLACE "[^\n]*(${DROP})[^\n]*\n" "" kept_a "${out_a}")
string(REGEX REPLACE "[^\n]*(${DROP})[^\n]*\n" "" kept_b "${out_b}")
string(LENGTH "${kept_a}" length)
if(length LESS 1000)
  message(FATAL_ERROR "too little output to compare from ${CMD} ${a}:\n${out_a}")
endif()
if(NOT kept_a STREQUAL kept_b)
  message(FATAL_ERROR "outputs differ\n--- ${a} ---\n${out_a}\n--- ${b} ---\n${out_b}")
endif()
]=])

function(psd_stream_same name args_a args_b)
  add_test(NAME ${name}
           COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>" "-DARGS_A=${args_a}"
                   "-DARGS_B=${args_b}" -P ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake)
endfunction()

# 120000 rows, --rate given: --memory 1K holds one block of 65536 rows, then the gzip file is
# counted in a first pass and the rest is streamed.
psd_stream_same(cli_psd_stream_counted_same_as_memory
  "psd@@${example}@@--time-column@@t@@--rate@@100@@--unit@@deg/s@@--memory@@1K@@--format@@json"
  "psd@@${example}@@--time-column@@t@@--rate@@100@@--unit@@deg/s@@--gaps@@fill@@--format@@json")
# The rate from the time column is final after 100001 stamps; with the default --memory the
# whole log is held and its length read off.
psd_stream_same(cli_psd_stream_measured_rate_same_as_memory
  "psd@@${example}@@--time-column@@t@@--format@@json"
  "psd@@${example}@@--time-column@@t@@--gaps@@fill@@--format@@json")
# Phase is differenced across block boundaries (one fewer sample chooses the segment length).
psd_stream_same(cli_psd_stream_phase_same_as_memory
  "psd@@${example}@@--time-column@@t@@--rate@@100@@--kind@@phase@@--unit@@deg@@--memory@@1K@@--format@@json"
  "psd@@${example}@@--time-column@@t@@--rate@@100@@--kind@@phase@@--unit@@deg@@--gaps@@fill@@--format@@json")
# --segment given: streamed from the first block; every option of the estimator carried through.
psd_stream_same(cli_psd_stream_options_same_as_memory
  "psd@@${example}@@--time-column@@t@@--rate@@100@@--kind@@increment@@--unit@@deg@@--segment@@1000@@--overlap@@0.3@@--window@@blackman-harris@@--detrend@@linear@@--memory@@1K@@--format@@json"
  "psd@@${example}@@--time-column@@t@@--rate@@100@@--kind@@increment@@--unit@@deg@@--segment@@1000@@--overlap@@0.3@@--window@@blackman-harris@@--detrend@@linear@@--gaps@@fill@@--format@@json")

# Raw binary states its row count (file size): streamed from the first block, the same as the
# same values written as CSV (17 significant digits, so the doubles are exact) read in memory.
add_test(NAME cli_psd_stream_make
         COMMAND ${CMAKE_COMMAND} -E chdir ${psd_dir} sh -c
                 "$<TARGET_FILE:sigmatau_cli> simulate --model 'N=0.15 deg/sqrt(h)' --rate 100 --duration 2000 --format f64 -o sim.f64 --force && $<TARGET_FILE:sigmatau_cli> simulate --model 'N=0.15 deg/sqrt(h)' --rate 100 --duration 2000 --format csv -o sim.csv --force")
set_tests_properties(cli_psd_stream_make PROPERTIES FIXTURES_SETUP cli_psd_stream)
add_test(NAME cli_psd_stream_binary_same_as_memory
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=psd@@${psd_dir}/sim.f64@@--binary@@f64@@--channels@@3@@--rate@@100@@--memory@@1K@@--format@@json"
                 "-DARGS_B=psd@@${psd_dir}/sim.csv@@--time-column@@t@@--rate@@100@@--gaps@@fill@@--format@@json"
                 "-DDROP=\"path\"|\"channel\"" -P ${psd_same})
# A pipe: with --segment it streams from the first block, the same as the file in memory.
add_test(NAME cli_psd_stream_stdin_same_as_memory
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>" "-DSTDIN_A=${psd_dir}/sim.csv"
                 "-DARGS_A=psd@@-@@--time-column@@t@@--rate@@100@@--segment@@4096@@--memory@@1K@@--format@@json"
                 "-DARGS_B=psd@@${psd_dir}/sim.csv@@--time-column@@t@@--rate@@100@@--segment@@4096@@--gaps@@fill@@--format@@json"
                 "-DDROP=\"path\"" -P ${psd_same})
set_tests_properties(cli_psd_stream_binary_same_as_memory cli_psd_stream_stdin_same_as_memory
                     PROPERTIES FIXTURES_REQUIRED cli_psd_stream)
# Without --segment a pipe longer than --memory cannot be sized: exit 2 with the way out.
sigmatau_cli_test(NAME cli_psd_stream_stdin_needs_segment EXIT 2
  STDIN ${example} STDERR "<stdin>: more than --memory holds.*give --segment N"
  ARGS psd - --time-column t --rate 100 --memory 1K)
sigmatau_cli_test(NAME cli_psd_stream_stdin_in_memory EXIT 0 STDIN ${example}
  STDOUT "gx +N = " ARGS psd - --time-column t --unit deg/s)
sigmatau_cli_test(NAME cli_psd_stream_bad_memory EXIT 2 STDERR "--memory must be a size"
  ARGS psd ${example} --time-column t --memory lots)

# ROS 1 bags, --rate given so that the segment length is chosen after the first block: indexed
# and read without --topic, the bag states its message count; unindexed, it is counted in a
# first pass (--memory 1K). Both give the PSD of the same messages as CSV read in memory
# (bags.cmake writes them).
set(bags ${CMAKE_CURRENT_BINARY_DIR}/cli_bags)
add_test(NAME cli_psd_stream_bag_same_as_memory
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=psd@@${bags}/imu.bag@@--rate@@100@@--memory@@1K@@--format@@json"
                 "-DARGS_B=psd@@${bags}/imu.csv@@--time-column@@t@@--time-unit@@ns@@--gyro-unit@@rad/s@@--accel-unit@@m/s^2@@--rate@@100@@--gaps@@fill@@--format@@json"
                 "-DDROP=\"path\"" -P ${psd_same})
add_test(NAME cli_psd_stream_unindexed_bag_same_as_memory
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=psd@@${bags}/imu_unindexed.bag@@--rate@@100@@--memory@@1K@@--format@@json"
                 "-DARGS_B=psd@@${bags}/imu.csv@@--time-column@@t@@--time-unit@@ns@@--gyro-unit@@rad/s@@--accel-unit@@m/s^2@@--rate@@100@@--gaps@@fill@@--format@@json"
                 "-DDROP=\"path\"" -P ${psd_same})
set_tests_properties(cli_psd_stream_bag_same_as_memory cli_psd_stream_unindexed_bag_same_as_memory
                     PROPERTIES FIXTURES_REQUIRED cli_bags)
