# `sigmatau demo --sheet` on shipped sheets that do not print every noise term (review E, A1, A2,
# A5): the demo takes the sheet's terms as `simulate --spec` does (simulate_spec.hpp), leaves
# out a sensor the sheet gives no noise term, says so in the report's Warnings and on stderr,
# refuses a sheet with no noise term at all, and records each sensor's noise_source in truth.json.
# 0.2 h at 100 Hz: long enough for the chain, short enough for the test suite.
set(demo_sheets_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_demo_sheets)
file(MAKE_DIRECTORY ${demo_sheets_dir})
set(demo_check ${CMAKE_CURRENT_SOURCE_DIR}/support/expect_json.cmake)

# A sheet that prints no noise term (a fixture: gyro ranges, accelerometer RMS noise only):
# nothing to simulate, exit 2, nothing written. It used to simulate two noiseless sensors and exit
# 0 with "stuck sensor" warnings.
sigmatau_cli_test(NAME cli_demo_sheet_without_noise_terms EXIT 2
  STDERR "data sheet no_noise_terms .*prints no gyro noise term .* and prints no accel noise term .*RMS noise.*nothing to simulate"
  NO_FILE ${demo_sheets_dir}/no_noise_terms
  ARGS demo --sheet ${PROJECT_SOURCE_DIR}/tests/data/specs/no_noise_terms.yaml --hours 0.2
       -o ${demo_sheets_dir}/no_noise_terms --force)

# A sheet whose accelerometer prints no noise term (a fixture, the shape the BMI088's had before
# its data sheet was read): the demo simulates the gyro only (three fitted channels), names the
# accel as left out first in the Warnings, and nothing is stuck or unplotted.
sigmatau_cli_test(NAME cli_demo_sheet_sensor_left_out EXIT 0
  STDERR "warning: data sheet gyro_noise_only .*prints no accel noise term .*so the demo leaves the accel out"
  STDOUT "gyro only"
  ARGS demo --sheet ${PROJECT_SOURCE_DIR}/tests/data/specs/gyro_noise_only.yaml --hours 0.2
       -o ${demo_sheets_dir}/bmi088 --force)
string(JOIN "@@" bmi088_json
  "results.json::warnings 0::^data sheet gyro_noise_only .*prints no accel noise term .*leaves the accel out"
  "results.json::fit channels 2 name::^gz$"
  "truth.json::gyro noise_source origin::^data sheet gyro_noise_only, each term x 0.8$"
  "truth.json::gyro noise_source read 0::^noise density 0.014")
string(JOIN "@@" bmi088_absent "results.json::fit channels 3" "truth.json::accel")
add_test(NAME cli_demo_sheet_sensor_left_out_files
         COMMAND ${CMAKE_COMMAND} -DDIR=${demo_sheets_dir}/bmi088 "-DJSON_MATCH=${bmi088_json}"
                 "-DJSON_ABSENT=${bmi088_absent}"
                 "-DJSON_NONE=results.json::warnings::stuck sensor|gnuplot|no noise-term fit"
                 "-DTEXT_MATCH=report.html::id=\"warnings\".*leaves the accel out"
                 -P ${demo_check})
set_tests_properties(cli_demo_sheet_sensor_left_out_files PROPERTIES DEPENDS cli_demo_sheet_sensor_left_out)

# ADIS16470 prints no accelerometer white noise (bias stability only): simulate's warning reaches
# the report's Warnings and stderr, and truth.json says what was read and left out.
sigmatau_cli_test(NAME cli_demo_sheet_without_white_noise EXIT 0
  STDERR "warning: data sheet adi_adis16470 .*prints no white noise for the accel, so the demo simulates the accel with in-run bias stability"
  ARGS demo --sheet adi_adis16470 --hours 0.2 -o ${demo_sheets_dir}/adis16470 --force)
string(JOIN "@@" adis16470_json
  "results.json::warnings 0::prints no white noise for the accel.*left out: white noise"
  "truth.json::accel noise_source read 0::^in-run bias stability 13 µg [(]typ[)]"
  "truth.json::accel noise_source left_out 0::^white noise"
  "truth.json::gyro noise_source read 0::^angle random walk 0.34")
add_test(NAME cli_demo_sheet_without_white_noise_files
         COMMAND ${CMAKE_COMMAND} -DDIR=${demo_sheets_dir}/adis16470 "-DJSON_MATCH=${adis16470_json}"
                 "-DTEXT_MATCH=report.html::id=\"warnings\".*prints no white noise for the accel"
                 -P ${demo_check})
set_tests_properties(cli_demo_sheet_without_white_noise_files PROPERTIES DEPENDS cli_demo_sheet_without_white_noise)

# MTi-630 prints its accel bias stability as a range 10-15 µg: the maximum is simulated, and the
# report's input line and truth.json say so (the line used to say "its typical noise terms" only).
sigmatau_cli_test(NAME cli_demo_sheet_max_value EXIT 0
  ARGS demo --sheet xsens_mti630 --hours 0.2 -o ${demo_sheets_dir}/mti630 --force)
string(JOIN "@@" mti630_json
  "results.json::input path::0.8 x its typical noise terms and, where no typical is printed, its accel bias instability 15 µg [(]max[)]"
  "truth.json::accel noise_source read 1::^in-run bias stability 15 µg [(]max[)]")
add_test(NAME cli_demo_sheet_max_value_files
         COMMAND ${CMAKE_COMMAND} -DDIR=${demo_sheets_dir}/mti630 "-DJSON_MATCH=${mti630_json}"
                 "-DJSON_NONE=results.json::warnings::."
                 -P ${demo_check})
set_tests_properties(cli_demo_sheet_max_value_files PROPERTIES DEPENDS cli_demo_sheet_max_value)

# A sheet given by path (find_data_sheet takes a file first): the report's input line names that
# file, not "specs/NAME.yaml" (which would point at a shipped sheet that does not exist).
sigmatau_cli_test(NAME cli_demo_sheet_by_path EXIT 0
  STDOUT "gyro white noise x [|] pass"
  ARGS demo --sheet ${PROJECT_SOURCE_DIR}/tests/data/specs/good_minimal.yaml --hours 0.2
       -o ${demo_sheets_dir}/by_path --force)
add_test(NAME cli_demo_sheet_by_path_files
         COMMAND ${CMAKE_COMMAND} -DDIR=${demo_sheets_dir}/by_path
                 "-DJSON_MATCH=results.json::input path::simulated from /.*tests/data/specs/good_minimal[.]yaml with 0[.]8 x"
                 -P ${demo_check})
set_tests_properties(cli_demo_sheet_by_path_files PROPERTIES DEPENDS cli_demo_sheet_by_path)

# The LSM6DSO prints noise densities for both sensors (specs/st_lsm6dso.yaml): the demo simulates
# them at 0.8 x and judges the six white-noise rows (its sheet prints no B or K to judge).
sigmatau_cli_test(NAME cli_demo_sheet_lsm6dso EXIT 0
  STDOUT "gyro white noise x [|] pass.*accel white noise z [|] pass"
  ARGS demo --sheet st_lsm6dso --hours 0.2 -o ${demo_sheets_dir}/lsm6dso --force)
