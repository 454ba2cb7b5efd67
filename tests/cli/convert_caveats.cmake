# What filter files say about the fit they rest on (review F findings 1, 3, 10, 11, 12), from
# `convert --fit` and from `analyze`, and the channel-name rule of convert --fit (code review G#1).
set(caveats_data ${PROJECT_SOURCE_DIR}/tests/data/convert)
set(caveats_out ${CMAKE_CURRENT_BINARY_DIR}/cli_convert_caveats)
file(REMOVE_RECURSE ${caveats_out})
file(MAKE_DIRECTORY ${caveats_out})

# A rejected fit: said on stderr and in the file's header, the file still written (exit 0).
sigmatau_cli_test(NAME cli_convert_fit_rejected EXIT 0
  STDERR "warning: .*fit_rejected.json: the noise-term fit is rejected by its goodness of fit \\(p < 0.001\\) on gx \\(p = 0, worst at tau = 0.02 s\\)"
  STDOUT "^# Kalibr imu.yaml[^\n]*\n# WARNING: incomplete: accelerometer_noise_density[^\n]*\n# WARNING: the noise-term fit is rejected .* on gx .*fit / analyze --tau-min.*\ngyroscope_noise_density: "
  ARGS convert --fit ${caveats_data}/fit_rejected.json --rate 100 --to kalibr --allow-incomplete)
# The level of the bounds (here no K on any axis, B everywhere: the rule of thumb, no bound) and
# the method: the joint fit at 95 %.
sigmatau_cli_test(NAME cli_convert_fit_method_level EXIT 0
  STDOUT "# note: terms from the joint noise-term fit, bounds and intervals at 95 %\n"
  ARGS convert --fit ${caveats_data}/fit_rejected.json --rate 100 --to px4 --allow-incomplete)
# Gauss-Markov: each axis's measured tau of the ADEV minimum, not a fixed 100 s.
sigmatau_cli_test(NAME cli_convert_fit_gm_measured_tau EXIT 0
  STDOUT "matched at the ADEV minimum at tau = 327.68 s \\(x\\), 327.68 s \\(y\\), 163.84 s \\(z\\): the tau of the ADEV minimum the fit measured"
  ARGS convert --fit ${caveats_data}/fit_rejected.json --rate 100 --to kalibr --bias-model gm --allow-incomplete)
sigmatau_cli_test(NAME cli_convert_fit_gm_given_tau EXIT 0
  STDOUT "matched at the ADEV minimum at tau = 400 s: given \\(convert --tau-min\\)"
  ARGS convert --fit ${caveats_data}/fit_rejected.json --rate 100 --to kalibr --bias-model gm --tau-min 400s --allow-incomplete)
# ROS field names without a quantity are gyro axes (the first letter 'a' made them accelerometers).
sigmatau_cli_test(NAME cli_convert_fit_ros_names EXIT 0
  STDOUT "\ngyroscope_noise_density: 0.0001 .*\ngyroscope_random_walk: 2.0e-06"
  ARGS convert --fit ${caveats_data}/fit_ros_names.json --rate 100 --to kalibr --allow-incomplete)

# analyze on a log in g read as m/s^2 (units forgotten), filter rate above the log's: every file
# says so, and convert --fit on its results.json repeats it on stderr.
sigmatau_cli_test(NAME cli_caveats_simulate EXIT 0
  ARGS simulate --sensors gyro,accel --out-unit "deg/s, g" --model "N=0.2 deg/sqrt(h), B=4 deg/h"
       --accel-model "N=80 ug/sqrt(Hz), B=40 ug" --rate 100 --duration 10min --seed 3
       -o ${caveats_out}/log.csv --force)
sigmatau_cli_test(NAME cli_caveats_analyze EXIT 0
  STDERR "the data look like g, not m/s\\^2.*warning: the filter rate 200 Hz is above the log's sample rate 100 Hz"
  ARGS analyze ${caveats_out}/log.csv --time-column t --rate-out 200 -o ${caveats_out}/an --force)
set_tests_properties(cli_caveats_analyze PROPERTIES DEPENDS cli_caveats_simulate)
foreach(file kalibr_imu_200Hz.yaml openvins_imu_200Hz.yaml vins_fusion_200Hz.yaml gtsam_200Hz.txt px4_ekf2_200Hz.params)
  add_test(NAME cli_caveats_header_${file}
           COMMAND ${CMAKE_COMMAND} -DFILE=${caveats_out}/an/${file}
                   "-DPATTERN=# WARNING: ax\\+ay\\+az: a static accelerometer .*the data look like g, not m/s\\^2.*# note: the filter rate 200 Hz is above the log's sample rate 100 Hz: the white-noise level was measured only up to 50 Hz"
                   -P ${CMAKE_CURRENT_SOURCE_DIR}/support/expect_in_file.cmake)
  set_tests_properties(cli_caveats_header_${file} PROPERTIES DEPENDS cli_caveats_analyze)
endforeach()
add_test(NAME cli_caveats_header_json
         COMMAND ${CMAKE_COMMAND} -DFILE=${caveats_out}/an/filter_200Hz.json
                 "-DPATTERN=\"warnings\": \\[[^]]*the data look like g, not m/s\\^2"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/expect_in_file.cmake)
set_tests_properties(cli_caveats_header_json PROPERTIES DEPENDS cli_caveats_analyze)
# The header no longer points to --tau-min for analyze's Gauss-Markov (analyze has no such option).
sigmatau_cli_test(NAME cli_caveats_analyze_gm EXIT 0
  ARGS analyze ${caveats_out}/log.csv --time-column t --gyro-unit deg/s --accel-unit g
       --bias-model gm -o ${caveats_out}/an_gm --force)
set_tests_properties(cli_caveats_analyze_gm PROPERTIES DEPENDS cli_caveats_simulate)
add_test(NAME cli_caveats_analyze_gm_tau
         COMMAND ${CMAKE_COMMAND} -DFILE=${caveats_out}/an_gm/kalibr_imu_100Hz.yaml
                 "-DPATTERN=# gyro bias Gauss-Markov from the bias stability B, matched at the ADEV minimum at tau = [^\n]*: the tau of the ADEV minimum the fit measured"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/expect_in_file.cmake)
set_tests_properties(cli_caveats_analyze_gm_tau PROPERTIES DEPENDS cli_caveats_analyze_gm)
sigmatau_cli_test(NAME cli_caveats_convert_results EXIT 0
  STDERR "warning: .*results.json: ax\\+ay\\+az: a static accelerometer.*warning: the filter rate 200 Hz is above the log's sample rate 100 Hz"
  ARGS convert --fit ${caveats_out}/an/results.json --rate 200 --to kalibr)
set_tests_properties(cli_caveats_convert_results PROPERTIES DEPENDS cli_caveats_analyze)
