# The compliance chart as a reader sees it, in Chromium (tests/support/check_compliance_chart.cmake:
# every text inside the chart, none overlapping, the x labels spread over the plot): issue 28,
# where the ADIS16405 log against the ADIS16448 sheet gave labels such as "gyro bias instability
# z (typ), fit rejected, not detected" that left a plot area of about 60 px.
set(chart_check ${CMAKE_CURRENT_SOURCE_DIR}/support/check_compliance_chart.cmake)
set(chart_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_compliance_chart)

# That log (../shared/data, skipped when absent): 9 rows, every one a "read-out" (the joint fits
# are rejected or contradict their curves: tests/cli/fit_guards.cmake).
set(adis16405 ${SIGMATAU_DATA_DIR}/imu/adis16405_imudata/adis16405_imu1_100Hz.csv.gz)
if(EXISTS ${adis16405})
  sigmatau_cli_test(NAME cli_compliance_chart_adis16405 EXIT 0
    ARGS analyze ${adis16405} --rate 100 --gyro-unit deg/s --accel-unit g --spec adi_adis16448
         -o ${chart_dir}/adis16405 --force)
endif()
add_test(NAME compliance_chart_in_chromium_adis16405
         COMMAND ${CMAKE_COMMAND} -DFILE=${chart_dir}/adis16405/report.html -DSKIP_IF_ABSENT=1
                 -DMIN_TEXTS=20 -P ${chart_check})
set_tests_properties(compliance_chart_in_chromium_adis16405 PROPERTIES SKIP_RETURN_CODE 77)
if(EXISTS ${adis16405})
  set_tests_properties(compliance_chart_in_chromium_adis16405 PROPERTIES
                       DEPENDS cli_compliance_chart_adis16405)
endif()

# 36 rows with labels of up to 64 characters over four decades, drawn by test_compliance_chart.
# That unit test is built only in scripts/test.sh's sanitized stage, so both tests carry the label
# needs_unit_tests, which the plain stage leaves out (it ran the Chromium check without the chart).
add_test(NAME compliance_chart_long_labels_draw
         COMMAND test_compliance_chart --test-case=*widens*)
set_tests_properties(compliance_chart_long_labels_draw PROPERTIES
                     ENVIRONMENT "SIGMATAU_CHART_DIR=${chart_dir}/long_labels"
                     LABELS needs_unit_tests)
add_test(NAME compliance_chart_in_chromium_long_labels
         COMMAND ${CMAKE_COMMAND} -DFILE=${chart_dir}/long_labels/long_labels_36_rows.svg
                 -DMIN_TEXTS=40 -P ${chart_check})
set_tests_properties(compliance_chart_in_chromium_long_labels PROPERTIES
                     DEPENDS compliance_chart_long_labels_draw SKIP_RETURN_CODE 77
                     LABELS needs_unit_tests)

# The demo's report (tests/cli/demo.cmake).
add_test(NAME compliance_chart_in_chromium_demo
         COMMAND ${CMAKE_COMMAND} -DFILE=${CMAKE_CURRENT_BINARY_DIR}/cli_demo_output/report.html
                 -DMIN_TEXTS=10 -P ${chart_check})
set_tests_properties(compliance_chart_in_chromium_demo PROPERTIES DEPENDS cli_demo_check
                     SKIP_RETURN_CODE 77)
