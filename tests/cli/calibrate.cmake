# `sigmatau calibrate`: a simulated multi-position log (gyro + accel + temperature ramp) is
# calibrated to JSON; degenerate logs are refused with exit 2 and the reason.
set(CAL_DIR ${CMAKE_CURRENT_BINARY_DIR}/calibrate_cli)
file(MAKE_DIRECTORY ${CAL_DIR})
sigmatau_cli_test(NAME cli_calibrate_simulate EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDOUT "wrote cal\\.csv"
  ARGS simulate --model "N=0.005 deg/s/sqrt(Hz)" --accel-model "N=100 ug/sqrt(Hz)" --rate 100
       --sensors gyro,accel --positions 16 --dwell "10 s" --latitude "45 deg" --seed 7
       --gyro-scale "0.4 %,-0.6 %,0.25 %" --gyro-misalignment "0.3 %,-0.2 %,0.15 %,0.4 %,-0.25 %,0.1 %"
       --accel-scale "-0.5 %,0.8 %,0.3 %" --accel-bias "30 mg,-20 mg,25 mg"
       --temperature "15 degC @ 0 s, 35 degC @ 5 min" --accel-temp-coef "0.2 mg/K,-0.3 mg/K,0.25 mg/K"
       --force -o cal.csv)
sigmatau_cli_test(NAME cli_calibrate_json EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDOUT "wrote cal\\.json"
  ARGS calibrate cal.csv --time-column t --latitude 45 --format json --force -o cal.json)
set_tests_properties(cli_calibrate_json PROPERTIES DEPENDS cli_calibrate_simulate)
sigmatau_cli_test(NAME cli_calibrate_table EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDOUT "gain error x.*cross-axis yx.*bias tempco x"
  ARGS calibrate cal.csv --time-column t --latitude 45)
set_tests_properties(cli_calibrate_table PROPERTIES DEPENDS cli_calibrate_simulate)
# Without --latitude or --gravity, standard gravity is assumed and a note says what that does to
# the gains (this log was simulated at 45 deg, where normal gravity is 0.005 % below standard).
sigmatau_cli_test(NAME cli_calibrate_standard_gravity_note EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "note: gravity taken as standard gravity, 9\\.80665 m/s\\^2 \\(no --latitude or --gravity\\): local gravity differs from it by -0\\.27 % at the equator and \\+0\\.26 % at the poles"
  ARGS calibrate cal.csv --time-column t --format json)
set_tests_properties(cli_calibrate_standard_gravity_note PROPERTIES DEPENDS cli_calibrate_simulate)
# The calibration result feeds `check` (the same keys compliance.cpp reads).
sigmatau_cli_test(NAME cli_calibrate_wrong_unit EXIT 2 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "--accel-unit"
  ARGS calibrate cal.csv --time-column t --accel-unit g)
set_tests_properties(cli_calibrate_wrong_unit PROPERTIES DEPENDS cli_calibrate_simulate)
sigmatau_cli_test(NAME cli_calibrate_few_positions_sim EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDOUT "wrote few\\.csv"
  ARGS simulate --model "N=0.005 deg/s/sqrt(Hz)" --accel-model "N=100 ug/sqrt(Hz)" --rate 100
       --sensors gyro,accel --positions 6 --dwell "5 s" --force -o few.csv)
sigmatau_cli_test(NAME cli_calibrate_too_few_positions EXIT 2 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "few\\.csv: calibrate: 6 static intervals but only 6 distinct orientations \\(need >= 9\\)"
  ARGS calibrate few.csv --time-column t)
set_tests_properties(cli_calibrate_too_few_positions PROPERTIES DEPENDS cli_calibrate_few_positions_sim)
sigmatau_cli_test(NAME cli_calibrate_min_orientations_option EXIT 2 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "distinct orientations \\(need >= 12\\)"
  ARGS calibrate few.csv --time-column t --accel ax,ay,az --gyro gx,gy,gz --min-orientations 12)
# Fewer than 9 orientations can never determine the accelerometer's 9 unknowns (review C: the
# classic 6 faces with --min-orientations 6 ended in "condition number inf > 1e10").
sigmatau_cli_test(NAME cli_calibrate_min_orientations_below_nine EXIT 2 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "--min-orientations 6: must be 9 to 1000.*9 unknowns.*6 faces need at least 3 more"
  ARGS calibrate few.csv --time-column t --min-orientations 6)
set_tests_properties(cli_calibrate_min_orientations_option PROPERTIES DEPENDS cli_calibrate_few_positions_sim)
sigmatau_cli_test(NAME cli_calibrate_missing_column EXIT 2 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "no column 'qx'"
  ARGS calibrate few.csv --time-column t --accel qx,qy,qz)
set_tests_properties(cli_calibrate_missing_column PROPERTIES DEPENDS cli_calibrate_few_positions_sim)

# Review C, unit checks: a column in a wrong unit is refused naming the unit given and its option.
# Accelerometer in mg read as g: the message names g (not m/s^2) and the unit the data look like.
sigmatau_cli_test(NAME cli_calibrate_units_sim EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDOUT "wrote units\\.csv"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --accel-model "N=60 ug/sqrt(Hz)" --rate 100
       --sensors gyro,accel --positions 12 --seed 5 --out-unit "deg/s, mg" --force -o units.csv)
sigmatau_cli_test(NAME cli_calibrate_accel_unit_named EXIT 2 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "units\\.csv: .* x the gravity .* read in g \\(--accel-unit g\\): they look like mg \\(--accel-unit mg\\)"
  ARGS calibrate units.csv --time-column t --accel-unit g --gyro-unit deg/s)
# Gyroscope in deg/s read as rad/s: every rotation turns 57 times too far (was exit 0 with
# chi2/dof 1.5e5/13).
sigmatau_cli_test(NAME cli_calibrate_gyro_unit_wrong EXIT 2 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "units\\.csv: calibrate: the gyroscope, read in rad/s \\(--gyro-unit rad/s\\), integrated across the rotations, misses where gravity went by more than 30 deg in [0-9]+ of 11 rotations.* Are the gyro columns in rad/s"
  ARGS calibrate units.csv --time-column t --accel-unit mg)
# Gyroscope in rad/s read as deg/s: the sensor turned 1/57 of the angle gravity turned (was exit
# 0, the gyro matrix "not estimated" in the JSON only).
sigmatau_cli_test(NAME cli_calibrate_gyro_unit_too_small EXIT 2 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "cal\\.csv: calibrate: the gyroscope, read in deg/s \\(--gyro-unit deg/s\\), turned less than 0\\.5 times the angle gravity turned in the sensor frame in 1[0-9] of 1[0-9] rotations"
  ARGS calibrate cal.csv --time-column t --latitude 45 --gyro-unit deg/s)
set_tests_properties(cli_calibrate_gyro_unit_too_small PROPERTIES DEPENDS cli_calibrate_simulate)
# The same log in the right units passes the checks (they cannot trip on a good log).
sigmatau_cli_test(NAME cli_calibrate_units_right EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDOUT "gain error x"
  ARGS calibrate units.csv --time-column t --accel-unit mg --gyro-unit deg/s)
set_tests_properties(cli_calibrate_accel_unit_named cli_calibrate_gyro_unit_wrong
                     cli_calibrate_units_right PROPERTIES DEPENDS cli_calibrate_units_sim)

# Review C, temperature: 12 positions cannot determine the accelerometer's temperature model
# (needs >= 14 intervals); that is said on stderr and in the table, the bias is labelled with
# the log's mean temperature, and the table prints the temperature range.
sigmatau_cli_test(NAME cli_calibrate_temp12_sim EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDOUT "wrote temp12\\.csv"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --accel-model "N=60 ug/sqrt(Hz)" --rate 100
       --sensors gyro,accel --positions 12 --seed 1 --accel-bias "10 mg,-5 mg,20 mg"
       --accel-temp-coef "0.2 mg/K,0 mg/K,-0.1 mg/K" --gyro-temp-coef "0.001 deg/s/K,0 deg/s/K,0 deg/s/K"
       --temperature "20 degC @ 0 s, 40 degC @ 276 s" --force -o temp12.csv)
sigmatau_cli_test(NAME cli_calibrate_temp_model_dropped_stderr EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "note: accelerometer: no bias temperature model \\(.*need >= 14.*\\); its bias holds at the log's mean temperature [0-9.]+ degC, not at T0 = 25\\.00 degC"
  ARGS calibrate temp12.csv --time-column t --latitude 90 --format json --force -o temp12.json)
sigmatau_cli_test(NAME cli_calibrate_temp_model_dropped_table EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDOUT "# temperature 2[0-9]\\.[0-9][0-9] to [34][0-9]\\.[0-9][0-9] degC over the static intervals.*accelerometer.*bias b at the log's mean temperature [0-9.]+ degC \\(no temperature model\\).*gyroscope.*bias b at T0 = 25\\.00 degC \\(temperature model below\\).*notes:.*accelerometer: no bias temperature model"
  ARGS calibrate temp12.csv --time-column t --latitude 90)
# A temperature column in degC read as K (20-40 "K"): refused, naming --temp-unit (the bias was
# extrapolated 273 K away). Simulated as a profile in K of the same numbers.
sigmatau_cli_test(NAME cli_calibrate_temp_cold_sim EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDOUT "wrote tempk\\.csv"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --accel-model "N=60 ug/sqrt(Hz)" --rate 100
       --sensors gyro,accel --positions 18 --seed 2 --temperature "20 K @ 0 s, 40 K @ 400 s"
       --force -o tempk.csv)
sigmatau_cli_test(NAME cli_calibrate_temp_unit_degc_as_k EXIT 2 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "tempk\\.csv: .*read in K \\(--temp-unit K\\), has a median of [23][0-9.]+ K \\(-2[0-9.]+ degC\\), below any IMU's range \\(150 K to 500 K\\): is the column in degC \\(--temp-unit degC\\)\\?"
  ARGS calibrate tempk.csv --time-column t)
set_tests_properties(cli_calibrate_temp_unit_degc_as_k PROPERTIES DEPENDS cli_calibrate_temp_cold_sim)
# A column in K read as degC (about 566 K): refused too.
sigmatau_cli_test(NAME cli_calibrate_temp_unit_k_as_degc EXIT 2 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "temp12\\.csv: .*read in degC \\(--temp-unit degC\\), has a median of 5[0-9.]+ K .* above any IMU's range"
  ARGS calibrate temp12.csv --time-column t --temp-unit degC)
set_tests_properties(cli_calibrate_temp_model_dropped_stderr cli_calibrate_temp_model_dropped_table
                     cli_calibrate_temp_unit_k_as_degc PROPERTIES DEPENDS cli_calibrate_temp12_sim)
# A temperature span under 1 K: no temperature model for either sensor, said on stderr.
sigmatau_cli_test(NAME cli_calibrate_temp_flat_sim EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDOUT "wrote tflat\\.csv"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --accel-model "N=60 ug/sqrt(Hz)" --rate 100
       --sensors gyro,accel --positions 12 --seed 3 --temperature "25 degC @ 0 s, 25.4 degC @ 276 s"
       --force -o tflat.csv)
sigmatau_cli_test(NAME cli_calibrate_temp_flat_note EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "note: accelerometer: no bias temperature model \\(the static intervals span only 0\\.[0-9]+ K of temperature \\(under 1 K\\)\\).*note: gyroscope: no bias temperature model \\(the static intervals span only"
  ARGS calibrate tflat.csv --time-column t)
set_tests_properties(cli_calibrate_temp_flat_note PROPERTIES DEPENDS cli_calibrate_temp_flat_sim)
# The gyro bias is fitted with the Earth rate of the first rest, turned into the others by the
# integrated rotations: the table and the JSON say so (the norm is printed, ~15 deg/h).
sigmatau_cli_test(NAME cli_calibrate_earth_rate_table EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDOUT "Earth rate: fitted with the bias, turned into each rest by the integrated rotations: \\|w\\| = 1[45]\\.[0-9]+ deg/h"
  ARGS calibrate cal.csv --time-column t --latitude 45)
set_tests_properties(cli_calibrate_earth_rate_table PROPERTIES DEPENDS cli_calibrate_simulate)
sigmatau_cli_test(NAME cli_calibrate_earth_rate_json EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDOUT "\"earth_rate_model\": \"heading\""
  ARGS calibrate cal.csv --time-column t --latitude 45 --format json)
set_tests_properties(cli_calibrate_earth_rate_json PROPERTIES DEPENDS cli_calibrate_simulate)
# Nine orientations for the accelerometer's nine parameters: the fit passes through the data and
# its residuals test nothing; the note says so (stderr and table).
sigmatau_cli_test(NAME cli_calibrate_nine_positions_sim EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDOUT "wrote p9\\.csv"
  ARGS simulate --model "N=0.005 deg/s/sqrt(Hz)" --accel-model "N=100 ug/sqrt(Hz)" --rate 100
       --sensors gyro,accel --positions 9 --dwell "10 s" --latitude "45 deg" --seed 7 --force -o p9.csv)
sigmatau_cli_test(NAME cli_calibrate_zero_dof_note EXIT 0 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "accelerometer: the fit has 0 degrees of freedom \\(as many parameters as equations\\)"
  STDOUT "notes:.*accelerometer: the fit has 0 degrees of freedom"
  ARGS calibrate p9.csv --time-column t --latitude 45)
set_tests_properties(cli_calibrate_zero_dof_note PROPERTIES DEPENDS cli_calibrate_nine_positions_sim)
