# `fit` and `analyze` take the units of a log's channels as `adev` and `psd` do (one set of rules
# in cli/channel_units.cpp): a single --unit that contradicts a column's sensor is refused,
# --gyro-unit / --accel-unit go by the columns' names and give adev's numbers, a ROS bag's
# channels carry their sensor_msgs/Imu units and a unit that contradicts them is refused, and
# the check comes before the log is read. Last, `analyze --spec` with a sheet that checks none of
# the log's terms exits 2 as `check` does.
if(CMAKE_SCRIPT_MODE_FILE)
  # -DMODE=fit|analyze, -DCMD= the sigmatau binary, -DLOG= the 6-axis log (gyros deg/s,
  # accelerometers g), -DDIR= a scratch directory.
  file(REMOVE_RECURSE ${DIR})
  file(MAKE_DIRECTORY ${DIR})
  function(run out)
    execute_process(COMMAND ${CMD} ${ARGN} OUTPUT_VARIABLE text RESULT_VARIABLE rc
                    ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${ARGN} exited ${rc}: ${err}")
    endif()
    set(${out} "${text}" PARENT_SCOPE)
  endfunction()
  set(units --gyro-unit deg/s --accel-unit g)
  if(MODE STREQUAL "fit")
    # fit on the log and fit on adev's saved result of the same log in the same units: the same
    # curves (adev scales each channel's curve by its unit as fit does), so the same JSON to the
    # last digit, but for the input's path.
    run(ignored adev ${LOG} --time-column t ${units} --format json -o ${DIR}/adev.json)
    run(from_adev fit ${DIR}/adev.json --format json)
    run(from_log fit ${LOG} --time-column t ${units} --format json)
    string(REGEX REPLACE "\"path\": \"[^\"]*\"" "\"path\": \"P\"" from_adev "${from_adev}")
    string(REGEX REPLACE "\"path\": \"[^\"]*\"" "\"path\": \"P\"" from_log "${from_log}")
    if(NOT from_adev STREQUAL from_log)
      message(FATAL_ERROR "fit of adev's result:\n${from_adev}\nfit of the log:\n${from_log}")
    endif()
    string(JSON quantity GET "${from_log}" channels 3 quantity)
    if(NOT quantity STREQUAL "specific_force")
      message(FATAL_ERROR "ax is ${quantity}, expected specific_force")
    endif()
    return()
  endif()

  # MODE analyze: every channel's OADEV (deviation and interval) in results.json is adev's in SI
  # (--out-unit rad/s,m/s^2). analyze scales the samples to SI before the curves and adev the
  # curves after, so they differ by rounding (4e-14 relative measured): agreement to 1e-9 is
  # far below any unit's factor (mdps against deg/s: 1e-3; deg/s against rad/s: 57).
  run(ignored adev ${LOG} --time-column t ${units} --out-unit rad/s,m/s^2 --format json
      -o ${DIR}/adev.json)
  run(ignored analyze ${LOG} --time-column t ${units} --trim none -o ${DIR}/analyze)
  file(READ ${DIR}/adev.json adev)
  file(READ ${DIR}/analyze/results.json analysis)
  # A decimal text as a 15-digit integer mantissa M and exponent E (value = 0.M x 10^E).
  function(decimal text m e)
    string(REGEX MATCH "^-?([0-9]*)\\.?([0-9]*)(e([-+]?[0-9]+))?$" ok "${text}")
    if(NOT ok)
      message(FATAL_ERROR "not a number: ${text}")
    endif()
    set(exponent 0)
    if(CMAKE_MATCH_4)
      math(EXPR exponent "${CMAKE_MATCH_4}")
    endif()
    set(digits "${CMAKE_MATCH_1}${CMAKE_MATCH_2}")
    string(LENGTH "${CMAKE_MATCH_2}" fraction)
    string(REGEX REPLACE "^0+" "" digits "${digits}")
    string(LENGTH "${digits}" length)
    math(EXPR exponent "${exponent} - ${fraction} + ${length}")
    string(SUBSTRING "${digits}000000000000000" 0 15 digits)
    set(${m} ${digits} PARENT_SCOPE)
    set(${e} ${exponent} PARENT_SCOPE)
  endfunction()
  function(expect_close what a b)
    decimal("${a}" ma ea)
    decimal("${b}" mb eb)
    # Across a power of ten the larger exponent's mantissa gets one more digit.
    math(EXPR step "${ea} - ${eb}")
    if(step EQUAL 1)
      math(EXPR ma "${ma} * 10")
    elseif(step EQUAL -1)
      math(EXPR mb "${mb} * 10")
    elseif(NOT step EQUAL 0)
      message(FATAL_ERROR "${what}: adev ${a}, analyze ${b}")
    endif()
    math(EXPR diff "${ma} - ${mb}")
    if(diff LESS 0)
      math(EXPR diff "-${diff}")
    endif()
    math(EXPR allowed "${ma} / 1000000000")  # 1e-9 relative
    if(diff GREATER allowed)
      message(FATAL_ERROR "${what}: adev ${a}, analyze ${b} (differ by more than 1e-9)")
    endif()
  endfunction()
  string(JSON channels LENGTH "${analysis}" channels)
  if(NOT channels EQUAL 6)
    message(FATAL_ERROR "${channels} channels in results.json, expected 6")
  endif()
  set(compared 0)
  math(EXPR last_channel "${channels} - 1")
  foreach(c RANGE ${last_channel})
    string(JSON name GET "${analysis}" channels ${c} name)
    string(JSON adev_name GET "${adev}" results ${c} channel)
    if(NOT name STREQUAL adev_name)
      message(FATAL_ERROR "channel ${c}: ${name} in analyze, ${adev_name} in adev")
    endif()
    string(JSON points LENGTH "${analysis}" channels ${c} allan 0 points)
    string(JSON adev_points LENGTH "${adev}" results ${c} points)
    if(NOT points EQUAL adev_points)
      message(FATAL_ERROR "${name}: ${points} taus in analyze, ${adev_points} in adev")
    endif()
    math(EXPR last_point "${points} - 1")
    foreach(p RANGE ${last_point})
      foreach(key dev ci_low ci_high)
        string(JSON a GET "${adev}" results ${c} points ${p} ${key})
        string(JSON b GET "${analysis}" channels ${c} allan 0 points ${p} ${key})
        expect_close("${name} point ${p} ${key}" "${a}" "${b}")
        math(EXPR compared "${compared} + 1")
      endforeach()
    endforeach()
  endforeach()
  message(STATUS "${compared} values agree")
  return()
endif()

set(fau_imu6 ${PROJECT_SOURCE_DIR}/tests/data/cli/imu6_10Hz.csv)  # gx..gz deg/s, ax..az g
set(fau_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_fit_analyze_units)
file(REMOVE_RECURSE ${fau_dir})  # no output directory left by an earlier run (NO_FILE below)
file(MAKE_DIRECTORY ${fau_dir})

# One --unit for a 6-axis log is refused by fit and analyze with adev's message (analyze used to
# say "--unit (applied to the accelerometer column ax; ...)" in its own words).
sigmatau_cli_test(NAME cli_fit_unit_contradicts_column EXIT 2
  STDERR "--unit deg/s is an angular rate \\(a gyro's unit\\), but column ax is an accelerometer axis by its name; give each sensor its unit with --gyro-unit and --accel-unit"
  ARGS fit ${fau_imu6} --time-column t --unit deg/s)
sigmatau_cli_test(NAME cli_analyze_unit_contradicts_column EXIT 2
  STDERR "--unit g is an acceleration \\(an accelerometer's unit\\), but column gx is a gyro axis by its name; give each sensor its unit with --gyro-unit and --accel-unit"
  NO_FILE ${fau_dir}/one_unit
  ARGS analyze ${fau_imu6} --time-column t --unit g -o ${fau_dir}/one_unit)
# Columns named a sensor by analyze's --gyro / --accel are checked the same way, and the message
# says how the column's sensor is known.
sigmatau_cli_test(NAME cli_analyze_unit_contradicts_named_column EXIT 2
  STDERR "--unit deg/s is an angular rate .*column ax is an accelerometer axis by --accel"
  ARGS analyze ${fau_imu6} --time-column t --gyro gx,gy,gz --accel ax,ay,az --unit deg/s
       -o ${fau_dir}/named)
# --gyro-unit / --accel-unit on a column whose name says no sensor: refused as in adev (analyze
# used to analyse it in no unit).
file(WRITE ${fau_dir}/with_temp.csv "t,gx,temp\n0.0,0.1,25\n0.1,0.2,25.1\n0.2,0.1,25\n")
sigmatau_cli_test(NAME cli_analyze_sensor_unit_unnamed_column EXIT 2
  STDERR "column \"temp\" is neither a gyro nor an accelerometer by its name"
  ARGS analyze ${fau_dir}/with_temp.csv --time-column t --gyro-unit deg/s -o ${fau_dir}/temp)

# Checked from the header, before the log is read: the broken third row is never reached.
file(WRITE ${fau_dir}/broken.csv "t,gyro_x,accel_x\n0.0,0.1,0.01\n0.1,0.2,oops\n")
sigmatau_cli_test(NAME cli_fit_unit_checked_before_reading EXIT 2
  STDERR "column accel_x is an accelerometer axis by its name"
  ARGS fit ${fau_dir}/broken.csv --time-column t --unit deg/s)
sigmatau_cli_test(NAME cli_analyze_unit_checked_before_reading EXIT 2
  STDERR "column accel_x is an accelerometer axis by its name"
  ARGS analyze ${fau_dir}/broken.csv --time-column t --unit deg/s -o ${fau_dir}/broken)

# --gyro-unit / --accel-unit on the 6-axis log: fit gives what it gives from adev's saved result,
# analyze's curves are adev's (in SI), in memory and out of core (--memory 1K).
add_test(NAME cli_fit_sensor_units_same_as_adev
         COMMAND ${CMAKE_COMMAND} -DMODE=fit "-DCMD=$<TARGET_FILE:sigmatau_cli>" -DLOG=${fau_imu6}
                 -DDIR=${fau_dir}/fit_same -P ${CMAKE_CURRENT_LIST_FILE})
add_test(NAME cli_analyze_sensor_units_same_as_adev
         COMMAND ${CMAKE_COMMAND} -DMODE=analyze "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 -DLOG=${fau_imu6} -DDIR=${fau_dir}/analyze_same -P ${CMAKE_CURRENT_LIST_FILE})
add_test(NAME cli_fit_sensor_units_out_of_core
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=fit@@${fau_imu6}@@--time-column@@t@@--gyro-unit@@deg/s@@--accel-unit@@g"
                 "-DARGS_B=fit@@${fau_imu6}@@--time-column@@t@@--gyro-unit@@deg/s@@--accel-unit@@g@@--memory@@1K"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/support/expect_same_output.cmake)
# One sensor's unit only: the other's columns stay in the input unit, said as adev says it.
sigmatau_cli_test(NAME cli_fit_sensor_unit_one_given EXIT 0
  STDERR "no --accel-unit: ax, ay, az left in the input unit"
  ARGS fit ${fau_imu6} --time-column t --gyro-unit deg/s)

# ROS bags (fixture cli_bags, tests/cli/bags.cmake): the channels are rad/s and m/s^2; a unit
# that says otherwise is refused by fit and analyze as by adev (fit took --gyro-unit deg/s on a
# bag and scaled the rad/s gyros by it; analyze did so with --unit and --gyro-unit).
set(fau_bags ${CMAKE_CURRENT_BINARY_DIR}/cli_bags)
sigmatau_cli_test(NAME cli_fit_bag_gyro_unit_contradicts EXIT 2
  STDERR "channel gx is rad/s \\(a ROS bag's sensor_msgs/Imu, whose units REP 103 fixes\\), but --gyro-unit deg/s says otherwise"
  ARGS fit ${fau_bags}/imu.bag --columns gx,ax --gyro-unit deg/s)
sigmatau_cli_test(NAME cli_analyze_bag_unit_contradicts EXIT 2
  STDERR "channel gx is rad/s \\(a ROS bag's sensor_msgs/Imu, whose units REP 103 fixes\\), but --unit deg/s says otherwise"
  NO_FILE ${fau_dir}/bag_unit
  ARGS analyze ${fau_bags}/imu.bag --columns gx,gy,gz --unit deg/s -o ${fau_dir}/bag_unit)
sigmatau_cli_test(NAME cli_analyze_bag_accel_unit_contradicts EXIT 2
  STDERR "channel ax is m/s\\^2 .*but --accel-unit g says otherwise"
  ARGS analyze ${fau_bags}/imu.db3 --accel-unit g -o ${fau_dir}/bag_accel_unit)
# The bag's own unit, given, is accepted; fit takes each channel's sensor from it.
sigmatau_cli_test(NAME cli_fit_bag_unit_agrees EXIT 0
  STDOUT "\"name\": \"gx\",.*\"quantity\": \"angular_rate\".*\"name\": \"az\",.*\"quantity\": \"specific_force\""
  ARGS fit ${fau_bags}/imu.bag --columns gx,az --gyro-unit rad/s --accel-unit m/s^2 --format json)
set_tests_properties(cli_fit_bag_gyro_unit_contradicts cli_analyze_bag_unit_contradicts
                     cli_analyze_bag_accel_unit_contradicts cli_fit_bag_unit_agrees
                     PROPERTIES FIXTURES_REQUIRED cli_bags)

# analyze --spec with a sheet that prints no limit on what the log measures: exit 2, a message
# naming the sheet and the log's channels, and no output directory, as `check` does (it used to
# print "nothing to check" and exit 0, a silent pass for a gate on the exit code). A gyro-only
# log against a fixture sheet with no noise figure (tests/data/specs/no_noise_terms.yaml),
# checked from the header before the read.
sigmatau_cli_test(NAME cli_analyze_spec_nothing_to_check_gyro EXIT 2
  STDERR "nothing to check: no_noise_terms \\(T-RMS\\) prints no limit on the noise terms measured in .*gyro_static_100Hz.csv.gz: the log has gyro channels gx, gy, gz; .* limits are for no sensor"
  NO_FILE ${fau_dir}/nothing_gyro
  ARGS analyze ${PROJECT_SOURCE_DIR}/examples/gyro_static_100Hz.csv.gz --time-column t
       --gyro-unit deg/s --spec ${PROJECT_SOURCE_DIR}/tests/data/specs/no_noise_terms.yaml
       -o ${fau_dir}/nothing_gyro)
# The other way round: accelerometer columns against a sheet with noise limits for its gyro only.
sigmatau_cli_test(NAME cli_analyze_spec_nothing_to_check_accel EXIT 2
  STDERR "nothing to check: gyro_noise_only \\(T-GYRO\\) .*the log has accelerometer channels ax, ay, az; .* limits are for the gyro"
  NO_FILE ${fau_dir}/nothing_accel
  ARGS analyze ${fau_imu6} --time-column t --columns ax,ay,az --accel-unit g
       --spec ${PROJECT_SOURCE_DIR}/tests/data/specs/gyro_noise_only.yaml -o ${fau_dir}/nothing_accel)
# From stdin (no header to read first) it is found after the analysis: still exit 2, no output.
sigmatau_cli_test(NAME cli_analyze_spec_nothing_to_check_stdin EXIT 2
  STDERR "nothing to check: gyro_noise_only \\(T-GYRO\\) .*measured in stdin: the log has accelerometer channels ax, ay, az"
  NO_FILE ${fau_dir}/nothing_stdin STDIN ${fau_imu6}
  ARGS analyze - --time-column t --columns ax,ay,az --accel-unit g
       --spec ${PROJECT_SOURCE_DIR}/tests/data/specs/gyro_noise_only.yaml -o ${fau_dir}/nothing_stdin)
# A sensor the sheet covers, but no term fitted (noise terms come from OADEV, first in --stat).
sigmatau_cli_test(NAME cli_analyze_spec_nothing_fitted EXIT 2
  STDERR "put oadev first in --stat.*nothing to check: bosch_bmi088 .*gyro channels gx, gy, gz and accelerometer channels ax, ay, az, but no noise term of theirs was fitted"
  NO_FILE ${fau_dir}/nothing_fitted
  ARGS analyze ${fau_imu6} --time-column t --gyro-unit deg/s --accel-unit g --spec bosch_bmi088
       --stat mdev -o ${fau_dir}/nothing_fitted)
# The same log and sheet with both sensors: the gyros are checked, exit 0.
sigmatau_cli_test(NAME cli_analyze_spec_something_to_check EXIT 0
  STDOUT "data sheet: Test T-GYRO: \\*\\*all pass\\*\\*"
  ARGS analyze ${fau_imu6} --time-column t --gyro-unit deg/s --accel-unit g
       --spec ${PROJECT_SOURCE_DIR}/tests/data/specs/gyro_noise_only.yaml -o ${fau_dir}/something --force)
