# The built-in demo end to end, at 3 h rather than its default 10 h to keep the suite (and its
# sanitizer run) short: shorter logs leave the gyro bias instability floor too close to the end
# of the curve to be selected. Then the output directory is checked against the simulator's
# truth (tests/support/check_demo.cmake).
set(demo_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_demo_output)
sigmatau_cli_test(NAME cli_demo_run EXIT 0 STDOUT "wrote .*cli_demo_output"
  ARGS demo -o ${demo_dir} --hours 3 --ci 0.999 --force)
add_test(NAME cli_demo_check
         COMMAND ${CMAKE_COMMAND} -DDIR=${demo_dir} -P ${CMAKE_CURRENT_SOURCE_DIR}/support/check_demo.cmake)
set_tests_properties(cli_demo_check PROPERTIES DEPENDS cli_demo_run)
sigmatau_cli_test(NAME cli_demo_refuses_existing EXIT 2 STDERR "exists; use --force"
  ARGS demo -o ${demo_dir} --hours 0.1)
set_tests_properties(cli_demo_refuses_existing PROPERTIES DEPENDS cli_demo_check)

# The demo report in a real browser (skipped, with a message, when chromium is not installed).
add_test(NAME report_in_chromium
         COMMAND ${CMAKE_COMMAND} -DDIR=${demo_dir} -P ${CMAKE_CURRENT_SOURCE_DIR}/support/check_report_browser.cmake)
set_tests_properties(report_in_chromium PROPERTIES DEPENDS cli_demo_check SKIP_RETURN_CODE 77)
