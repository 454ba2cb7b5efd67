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
  STDERR "only 6 distinct orientations \\(need >= 9\\)"
  ARGS calibrate few.csv --time-column t)
set_tests_properties(cli_calibrate_too_few_positions PROPERTIES DEPENDS cli_calibrate_few_positions_sim)
sigmatau_cli_test(NAME cli_calibrate_min_orientations_option EXIT 2 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "distinct orientations"
  ARGS calibrate few.csv --time-column t --accel ax,ay,az --gyro gx,gy,gz --min-orientations 7)
set_tests_properties(cli_calibrate_min_orientations_option PROPERTIES DEPENDS cli_calibrate_few_positions_sim)
sigmatau_cli_test(NAME cli_calibrate_missing_column EXIT 2 WORKING_DIRECTORY ${CAL_DIR}
  STDERR "no column 'qx'"
  ARGS calibrate few.csv --time-column t --accel qx,qy,qz)
set_tests_properties(cli_calibrate_missing_column PROPERTIES DEPENDS cli_calibrate_few_positions_sim)
