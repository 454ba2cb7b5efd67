# The report shows the filter files (review F, finding 15). `analyze` on the shipped example at
# two filter rates (two groups of files); then every file results.json names must be in the
# directory, named in summary.md and report.html, and its text shown in report.html, escaped
# (tests/support/check_report_filter_files.cmake); and in Chromium at 1200 px with every file
# open nothing may be cut off sideways (tests/support/check_report_layout.cmake; the example's
# bias line of the filter arithmetic used to scroll out of view). A file results.json names but
# the report is not given is covered by tests/test_report_filter_files.cpp (analyze always gives
# them all).
# The log has both sensors (10 min at 100 Hz, simulated): every filter needs both, and analyze
# writes no file its filter would read with values missing (the shipped example is gyro only).
set(report_files_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_report_files)
sigmatau_cli_test(NAME cli_report_filter_files_log EXIT 0
  ARGS simulate --sensors gyro,accel --out-unit "deg/s, g" --model "N=0.2 deg/sqrt(h), B=4 deg/h"
       --accel-model "N=80 ug/sqrt(Hz), B=40 ug" --rate 100 --duration 10min --seed 5
       -o ${report_files_dir}/log.csv --force)
sigmatau_cli_test(NAME cli_report_filter_files_run EXIT 0
  STDOUT "## Filter files.*at 200 Hz:.*- `kalibr_imu_200Hz.yaml`: Kalibr imu.yaml.*wrote "
  ARGS analyze ${report_files_dir}/log.csv --time-column t --gyro-unit deg/s --accel-unit g
       --rate-out 100 200 -o ${report_files_dir}/example --force)
set_tests_properties(cli_report_filter_files_run PROPERTIES DEPENDS cli_report_filter_files_log)
add_test(NAME cli_report_filter_files_shown
         COMMAND ${CMAKE_COMMAND} -DDIR=${report_files_dir}/example
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/check_report_filter_files.cmake)
set_tests_properties(cli_report_filter_files_shown PROPERTIES DEPENDS cli_report_filter_files_run)
# 12 files: 6 formats at each of the 2 rates.
add_test(NAME report_layout_in_chromium
         COMMAND ${CMAKE_COMMAND} -DDIR=${report_files_dir}/example -DWIDTH=1200 -DMIN_FILES=12
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/check_report_layout.cmake)
set_tests_properties(report_layout_in_chromium PROPERTIES DEPENDS cli_report_filter_files_shown
                     SKIP_RETURN_CODE 77)
