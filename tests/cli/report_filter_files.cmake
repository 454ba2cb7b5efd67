# The report shows the filter files (review F, finding 15). `analyze` on the shipped example at
# two filter rates (two groups of files); then every file results.json names must be in the
# directory, named in summary.md and report.html, and its text shown in report.html, escaped
# (tests/support/check_report_filter_files.cmake); and in Chromium at 1200 px with every file
# open nothing may be cut off sideways (tests/support/check_report_layout.cmake; the example's
# bias line of the filter arithmetic used to scroll out of view). A file results.json names but
# the report is not given is covered by tests/test_report_filter_files.cpp (analyze always gives
# them all).
set(report_files_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_report_files)
sigmatau_cli_test(NAME cli_report_filter_files_run EXIT 0
  STDOUT "## Filter files.*at 200 Hz:.*- `kalibr_imu_200Hz.yaml`: Kalibr imu.yaml.*wrote "
  ARGS analyze ${PROJECT_SOURCE_DIR}/examples/gyro_static_100Hz.csv.gz --time-column t
       --gyro-unit deg/s --rate-out 100 200 -o ${report_files_dir}/example --force)
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
