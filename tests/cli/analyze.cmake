# `sigmatau analyze`: the whole chain on the shipped example log into one directory.
set(example ${PROJECT_SOURCE_DIR}/examples/gyro_static_100Hz.csv.gz)
set(analyze_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_analyze)
file(REMOVE_RECURSE ${analyze_dir})
file(MAKE_DIRECTORY ${analyze_dir})

sigmatau_cli_test(NAME cli_analyze_example EXIT 0
  STDOUT "\\| gx \\|.*deg/sqrt\\(h\\).*wrote .*example"
  ARGS analyze ${example} --time-column t --gyro-unit deg/s --dynamic --rate-out 200
       --spec adi_adis16465 -o ${analyze_dir}/example --force)
# The example is gyro only: the filter files whose filters need the accelerometer too are not
# written (Kalibr would stop, VINS-Fusion read 0, PX4 and GTSAM keep their defaults), and the
# warning says so and how to write them; the JSON holds the gyro's values.
add_test(NAME cli_analyze_example_files
         COMMAND ${CMAKE_COMMAND} -DDIR=${analyze_dir}/example
                 "-DFILES=report.html;results.json;summary.md;adev_gyro.svg;psd_gyro.svg;compliance.svg;dynamic_gx.svg;filter_200Hz.json"
                 "-DABSENT=kalibr_imu_200Hz.yaml;openvins_imu_200Hz.yaml;vins_fusion_200Hz.yaml;gtsam_200Hz.txt;px4_ekf2_200Hz.params"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/expect_files.cmake)
set_tests_properties(cli_analyze_example_files PROPERTIES DEPENDS cli_analyze_example)
string(JOIN "@@" analyze_incomplete_json
  "results.json::filter 0 not_written 0::^kalibr_imu_200Hz.yaml$"
  "results.json::filter 0 files 0::^filter_200Hz.json$")
add_test(NAME cli_analyze_example_incomplete_not_written
         COMMAND ${CMAKE_COMMAND} -DDIR=${analyze_dir}/example "-DJSON_MATCH=${analyze_incomplete_json}"
                 "-DTEXT_MATCH=report.html::id=\"warnings\".*not written: kalibr_imu_200Hz.yaml, openvins_imu_200Hz.yaml, vins_fusion_200Hz.yaml, gtsam_200Hz.txt, px4_ekf2_200Hz.params: their filters need the white noise and bias of both sensors and the log gives no accelerometer white noise and bias"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/expect_json.cmake)
set_tests_properties(cli_analyze_example_incomplete_not_written PROPERTIES DEPENDS cli_analyze_example)
sigmatau_cli_test(NAME cli_analyze_refuses_existing EXIT 2 STDERR "exists; use --force"
  ARGS analyze ${example} --time-column t -o ${analyze_dir}/example)
set_tests_properties(cli_analyze_refuses_existing PROPERTIES DEPENDS cli_analyze_example_files)

# Without gnuplot the results and the report are still written, and a warning says how to
# install it.
sigmatau_cli_test(NAME cli_analyze_without_gnuplot EXIT 0
  STDERR "gnuplot not found.*apt-get install gnuplot-nox"
  ARGS analyze ${example} --time-column t --gyro-unit deg/s -o ${analyze_dir}/no_gnuplot --force)
set_tests_properties(cli_analyze_without_gnuplot PROPERTIES ENVIRONMENT "PATH=/nonexistent")
add_test(NAME cli_analyze_without_gnuplot_files
         COMMAND ${CMAKE_COMMAND} -DDIR=${analyze_dir}/no_gnuplot
                 "-DFILES=report.html;results.json;summary.md" "-DABSENT=adev_gyro.svg"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/expect_files.cmake)
set_tests_properties(cli_analyze_without_gnuplot_files PROPERTIES DEPENDS cli_analyze_without_gnuplot)

sigmatau_cli_test(NAME cli_analyze_bad_trim EXIT 2 STDERR "--trim"
  ARGS analyze ${example} --time-column t --trim soon -o ${analyze_dir}/bad_trim)
sigmatau_cli_test(NAME cli_analyze_bad_gyro_unit EXIT 2 STDERR "--gyro-unit"
  NO_FILE ${analyze_dir}/bad_unit
  ARGS analyze ${example} --time-column t --gyro-unit m/s^2 -o ${analyze_dir}/bad_unit)

# One --unit for a log with both sensors: the error names --unit (the option given), the column
# it failed on and the way out, not --accel-unit (an option the user did not give); adev's words.
sigmatau_cli_test(NAME cli_analyze_one_unit_two_sensors EXIT 2
  STDERR "--unit deg/s is an angular rate .*column ax is an accelerometer axis by its name; give each sensor its unit with --gyro-unit and --accel-unit"
  ARGS analyze ${PROJECT_SOURCE_DIR}/tests/data/cli/imu6_10Hz.csv --time-column t --unit deg/s
       -o ${analyze_dir}/one_unit)
# --tau-min / --tau-max restrict the taus the fit uses, as in fit (from 1 s: 8 of the 15 points,
# N and K, 6 degrees of freedom); a reversed range is refused.
sigmatau_cli_test(NAME cli_analyze_tau_range_reversed EXIT 2 STDERR "--tau-min / --tau-max: expected"
  ARGS analyze ${example} --time-column t --gyro-unit deg/s --tau-min 10 --tau-max 1
       -o ${analyze_dir}/tau_range_reversed)
sigmatau_cli_test(NAME cli_analyze_tau_range EXIT 0 STDOUT "wrote .*tau_range"
  ARGS analyze ${example} --time-column t --gyro-unit deg/s --tau-min 1 -o ${analyze_dir}/tau_range --force)
add_test(NAME cli_analyze_tau_range_points
         COMMAND ${CMAKE_COMMAND} -DFILE=${analyze_dir}/tau_range/results.json
                 "-DPATTERN=\"dof\": 6,"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/expect_in_file.cmake)
set_tests_properties(cli_analyze_tau_range_points PROPERTIES DEPENDS cli_analyze_tau_range)
# --unit and --gyro-unit together are refused (as in adev): the gyros used to be read in
# --gyro-unit without a word, so a deg/s log came out 57x too noisy.
sigmatau_cli_test(NAME cli_analyze_unit_conflict EXIT 2
  STDERR "--unit deg/s names one unit for every column; with --gyro-unit / --accel-unit leave it out"
  NO_FILE ${analyze_dir}/unit_conflict
  ARGS analyze ${example} --time-column t --unit deg/s --gyro-unit rad/s -o ${analyze_dir}/unit_conflict)
# --unit beside --accel-unit is refused too, as in adev (--unit names one unit for every column;
# analyze used to take it for the gyros here).
sigmatau_cli_test(NAME cli_analyze_unit_and_accel_unit EXIT 2
  STDERR "--unit deg/s names one unit for every column; with --gyro-unit / --accel-unit leave it out"
  ARGS analyze ${PROJECT_SOURCE_DIR}/tests/data/cli/imu6_10Hz.csv --time-column t --unit deg/s
       --accel-unit m/s^2 -o ${analyze_dir}/unit_and_accel_unit --force)

# A raw binary log has channels c0..c5: --gyro / --accel give their sensors and axes, and the
# filter files are written from them (before: analyze computed everything, then stopped with
# 'channel "c0": cannot tell its sensor and axis' and wrote nothing). results.json records
# each fitted channel's axis.
set(analyze_binary_roles [=[
run simulate --spec adi_adis16465 --sensors gyro,accel --rate 100 --duration 20min --format f32 -o "$W/imu.f32"
expect 0 ""
run analyze "$W/imu.f32" --binary f32 --channels 6 --gyro c0,c1,c2 --accel c3,c4,c5 --rate 100 -o "$W/out"
expect 0 ""
for f in kalibr_imu_100Hz.yaml px4_ekf2_100Hz.params filter_100Hz.json report.html; do
  [ -s "$W/out/$f" ] || fail "$f not written"
done
grep -q '"axis": "z"' "$W/out/results.json" || grep -q '"axis":"z"' "$W/out/results.json" || fail "no axis in results.json"
echo "ok: filter files from c0..c5"
]=])
add_test(NAME cli_analyze_binary_roles
         COMMAND bash -c "${sigmatau_cli_shell_prologue}${analyze_binary_roles}" analyze_binary_roles
                 $<TARGET_FILE:sigmatau_cli> ${analyze_dir}/binary_roles none)
