# `sigmatau simulate`: files, header, sidecar, no overwrite, bad input (exit 2, one-line message).
set(SIM_DIR ${CMAKE_CURRENT_BINARY_DIR}/simulate_cli)
file(MAKE_DIRECTORY ${SIM_DIR})
sigmatau_cli_test(NAME cli_simulate_csv EXIT 0 WORKING_DIRECTORY ${SIM_DIR}
  STDOUT "wrote sim\\.csv \\(1000 samples at 100 Hz"
  ARGS simulate --model "N=0.15 deg/sqrt(h), B=3 deg/h, K=0.02 deg/h/sqrt(h)" --rate 100
       --duration "10 s" --seed 3 --sensors gyro,accel --force -o sim.csv)
sigmatau_cli_test(NAME cli_simulate_no_overwrite EXIT 2 WORKING_DIRECTORY ${SIM_DIR}
  STDERR "exists; use --force"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --rate 100 --duration 1 -o sim.csv)
set_tests_properties(cli_simulate_no_overwrite PROPERTIES DEPENDS cli_simulate_csv)
sigmatau_cli_test(NAME cli_simulate_wrong_dimension EXIT 2 NO_FILE ${SIM_DIR}/bad.csv
  WORKING_DIRECTORY ${SIM_DIR}
  STDERR "N"
  ARGS simulate --model "N=3 deg/h" --rate 100 --duration 1 -o bad.csv)
sigmatau_cli_test(NAME cli_simulate_unknown_term EXIT 2 NO_FILE ${SIM_DIR}/bad.csv
  WORKING_DIRECTORY ${SIM_DIR}
  STDERR "unknown term 'Z'"
  ARGS simulate --model "Z=3 deg/h" --rate 100 --duration 1 -o bad.csv)
sigmatau_cli_test(NAME cli_simulate_counts_need_lsb EXIT 2 NO_FILE ${SIM_DIR}/bad.csv
  WORKING_DIRECTORY ${SIM_DIR}
  STDERR "--gyro-lsb"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --rate 100 --duration 1 --kind counts -o bad.csv)
sigmatau_cli_test(NAME cli_simulate_f32 EXIT 0 WORKING_DIRECTORY ${SIM_DIR}
  STDOUT "wrote sim\\.f32"
  ARGS simulate --model "N=0.15 deg/sqrt(h), GM=1 deg/h @ 10 s" --rate 50 --duration 2min
       --kind counts --gyro-lsb "0.001 deg/s" --gyro-full-scale "250 deg/s" --format f32
       --force -o sim.f32)

# From a data sheet: the ICM-42688-P prints 2.8 mdps/sqrt(Hz) (specs/tdk_icm42688p.yaml); the
# simulated log's PSD reads it back (10 min at 200 Hz: the estimate's 1-sigma error is ~0.3 %,
# so the value rounds to the printed two digits: 0.00275 <= N < 0.00285 deg/s/sqrt(Hz)).
set(sim_spec_out ${CMAKE_CURRENT_BINARY_DIR}/cli_simulate_spec.csv)
file(REMOVE ${sim_spec_out} ${sim_spec_out}.json)
sigmatau_cli_test(NAME cli_simulate_from_spec EXIT 0 STDOUT "wrote"
  ARGS simulate --spec tdk_icm42688p --sensors gyro --rate 200 --duration 10min --seed 3
       -o ${sim_spec_out} --force)
sigmatau_cli_test(NAME cli_simulate_from_spec_psd EXIT 0
  STDOUT "gx +N = 0\\.002(7[5-9]|8[0-4])[0-9]* \\[.*\\] deg/s/sqrt\\(Hz\\)"
  ARGS psd ${sim_spec_out} --time-column t --unit rad/s --out-unit "deg/s/sqrt(Hz)")
set_tests_properties(cli_simulate_from_spec_psd PROPERTIES DEPENDS cli_simulate_from_spec)
# --model replaces the sheet's gyro terms (the sidecar names where each sensor's terms came from).
sigmatau_cli_test(NAME cli_simulate_spec_and_model EXIT 0 STDOUT "wrote"
  ARGS simulate --spec tdk_icm42688p --model "N=1 deg/sqrt(h)" --rate 200 --duration 1min
       --force -o ${CMAKE_CURRENT_BINARY_DIR}/spec_and_model.csv)
