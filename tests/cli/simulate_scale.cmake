# `simulate --spec NAME --scale F`: the sheet's noise terms x F, as `demo --scale` (one function
# scales and checks for both, simulate_spec.hpp), recorded in the sidecar's noise_source. The
# STIM300 prints ARW 0.15 deg/sqrt(h) (N = 4.3633e-05 rad/s/sqrt(Hz)) and VRW 0.06 m/s/sqrt(h)
# (N = 1e-3 m/s^2/sqrt(Hz)): x 0.8 they are 3.4907e-05 and 8e-4.
set(sim_scale_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_simulate_scale)
file(MAKE_DIRECTORY ${sim_scale_dir})
sigmatau_cli_test(NAME cli_simulate_scale_spec EXIT 0 STDOUT "wrote"
  ARGS simulate --spec safran_stim300 --sensors gyro,accel --rate 100 --duration 10 --scale 0.8
       -o ${sim_scale_dir}/scaled.csv --force)
sigmatau_cli_test(NAME cli_simulate_scale_spec_unscaled EXIT 0 STDOUT "wrote"
  ARGS simulate --spec safran_stim300 --sensors gyro,accel --rate 100 --duration 10
       -o ${sim_scale_dir}/unscaled.csv --force)
string(JOIN "@@" sim_scale_json
  "scaled.csv.json::gyro noise_source origin::^data sheet safran_stim300, each term x 0\\.8$"
  "scaled.csv.json::gyro noise 0 white::^3\\.490658[0-9]*e-05$"
  "scaled.csv.json::gyro noise 2 white::^3\\.490658[0-9]*e-05$"
  "scaled.csv.json::accel noise_source origin::^data sheet safran_stim300, each term x 0\\.8$"
  "scaled.csv.json::accel noise 1 white::^0\\.0008(0000000000[0-9]*)?$"
  "unscaled.csv.json::gyro noise_source origin::^data sheet safran_stim300$"
  "unscaled.csv.json::gyro noise 0 white::^4\\.363323[0-9]*e-05$")
add_test(NAME cli_simulate_scale_sidecar
         COMMAND ${CMAKE_COMMAND} -DDIR=${sim_scale_dir} "-DJSON_MATCH=${sim_scale_json}"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/expect_json.cmake)
set_tests_properties(cli_simulate_scale_sidecar PROPERTIES
                     DEPENDS "cli_simulate_scale_spec;cli_simulate_scale_spec_unscaled")

# --model / --accel-model replace the sheet's terms and are not scaled: the accel's are.
sigmatau_cli_test(NAME cli_simulate_scale_model_not_scaled EXIT 0 STDOUT "wrote"
  ARGS simulate --spec safran_stim300 --sensors gyro,accel --rate 100 --duration 10 --scale 0.8
       --model "N=0.15 deg/sqrt(h)" -o ${sim_scale_dir}/model.csv --force)
string(JOIN "@@" sim_scale_model_json
  "model.csv.json::gyro noise_source origin::^--model$"
  "model.csv.json::gyro noise 0 white::^4\\.363323[0-9]*e-05$"
  "model.csv.json::accel noise 0 white::^0\\.0008(0000000000[0-9]*)?$")
add_test(NAME cli_simulate_scale_model_sidecar
         COMMAND ${CMAKE_COMMAND} -DDIR=${sim_scale_dir} "-DJSON_MATCH=${sim_scale_model_json}"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/expect_json.cmake)
set_tests_properties(cli_simulate_scale_model_sidecar PROPERTIES
                     DEPENDS cli_simulate_scale_model_not_scaled)

# Refused, nothing written: a factor that is not > 0 (as demo refuses it), --scale without
# --spec, and --scale with nothing of the sheet's left to scale.
foreach(bad 0 -0.5 nan inf)
  string(MAKE_C_IDENTIFIER "${bad}" id)
  sigmatau_cli_test(NAME cli_simulate_scale_bad_${id} EXIT 2 NO_FILE ${sim_scale_dir}/bad.csv
    STDERR "^sigmatau: error: --scale must be a number > 0 [^\n]*got ${bad}\n$"
    ARGS simulate --spec safran_stim300 --rate 100 --duration 10 --scale ${bad}
         -o ${sim_scale_dir}/bad.csv)
endforeach()
sigmatau_cli_test(NAME cli_demo_scale_bad EXIT 2 NO_FILE ${sim_scale_dir}/demo_bad
  STDERR "^sigmatau: error: --scale must be a number > 0 [^\n]*got 0\n$"
  ARGS demo --scale 0 --hours 0.01 -o ${sim_scale_dir}/demo_bad)
sigmatau_cli_test(NAME cli_simulate_scale_without_spec EXIT 2 NO_FILE ${sim_scale_dir}/bad.csv
  STDERR "--scale scales a data sheet's noise terms: give --spec"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --rate 100 --duration 10 --scale 0.8
       -o ${sim_scale_dir}/bad.csv)
sigmatau_cli_test(NAME cli_simulate_scale_nothing_to_scale EXIT 2 NO_FILE ${sim_scale_dir}/bad.csv
  STDERR "--scale has nothing to scale"
  ARGS simulate --spec safran_stim300 --model "N=0.15 deg/sqrt(h)" --rate 100 --duration 10
       --scale 0.8 -o ${sim_scale_dir}/bad.csv)
# The help says what it does.
sigmatau_cli_test(NAME cli_simulate_scale_help EXIT 0 STDOUT "--scale[^\n]*with --spec: the sheet's noise terms x this factor"
  ARGS simulate --help)
