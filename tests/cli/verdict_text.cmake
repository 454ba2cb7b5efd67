# How `check` and `convert` word their results (review E, A3-A5).
set(verdict_data ${PROJECT_SOURCE_DIR}/tests/data/check)
# A fail by 0.13 % against a typical value: the ratio keeps four digits (it printed "1" in
# analyze's summary), typ and max limits are marked, the note that a typ is not a guarantee
# stands just before RESULT, and the rule's header advises --ci 0.95 for a gate.
sigmatau_cli_test(NAME cli_check_ratio_digits_typ_note EXIT 1
  STDOUT "--ci 0\\.95.*gyro white_noise x +fail .*0\\.007 °/s/√Hz \\(typ\\) +1\\.001 +\\[0\\.9984, 1\\.004\\] +within uncertainty.*accel bias_instability x +pass .*15 µg \\(max\\) .*# note: limits marked \\(typ\\) are typical values, not guaranteed maxima[^\n]*\nRESULT: FAIL"
  ARGS check --spec xsens_mti630 ${verdict_data}/fit_at_typical.json)
# The same result at 95 %: the advice to use --ci 0.95 is not repeated to a result that did.
file(READ ${verdict_data}/fit_at_typical.json verdict_fit_text)
string(REGEX REPLACE "^{" "{\"confidence\": 0.95, " verdict_fit_95 "${verdict_fit_text}")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/cli_check_at_95/fit_at_typical_95.json "${verdict_fit_95}")
add_test(NAME cli_check_no_gate_advice_at_95
         COMMAND ${CMAKE_COMMAND} -DCLI=$<TARGET_FILE:sigmatau_cli>
                 -DSPEC=xsens_mti630 -DRESULT=${CMAKE_CURRENT_BINARY_DIR}/cli_check_at_95/fit_at_typical_95.json
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/check_without_gate_advice.cmake)
# A sensor the sheet describes without any noise term gets a line (the accelerometer of a sheet
# printing ranges only vanished from the output, while the ADIS16470's said "white noise: not
# given").
sigmatau_cli_test(NAME cli_convert_sensor_without_noise_terms EXIT 0
  STDOUT "gyro: f_s = 100 Hz.*accel: not given \\(the sheet describes it but prints no noise density"
  ARGS convert --spec ${PROJECT_SOURCE_DIR}/tests/data/specs/gyro_noise_only.yaml --rate 100)
