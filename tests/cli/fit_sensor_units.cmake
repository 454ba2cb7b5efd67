# `fit --gyro-unit / --accel-unit`: a 6-axis log with the gyros in deg/s and the accelerometers in
# g is fitted in one run, as each sensor alone with its --unit, and its result makes a complete
# filter file (fit + convert used to need one --unit for every column, so one sensor was missing).
if(CMAKE_SCRIPT_MODE_FILE)
  # -DCMD= the sigmatau binary, -DLOG= the 6-axis log, -DDIR= a scratch directory.
  file(MAKE_DIRECTORY ${DIR})
  function(run_fit out)
    execute_process(COMMAND ${CMD} fit ${LOG} --time-column t ${ARGN} --format json
                    OUTPUT_VARIABLE json RESULT_VARIABLE rc ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "fit ${ARGN} exited ${rc}: ${err}")
    endif()
    set(${out} "${json}" PARENT_SCOPE)
  endfunction()
  run_fit(both --gyro-unit deg/s --accel-unit g)
  run_fit(gyro --columns gx,gy,gz --unit deg/s)
  run_fit(accel --columns ax,ay,az --unit g)
  file(WRITE ${DIR}/both.json "${both}")
  # The N of every channel agrees with the one-sensor fit. The two routes scale by the unit at
  # different steps (the samples vs the curve), so they may differ in the last bits: 1e-12.
  foreach(index RANGE 5)
    if(index LESS 3)
      set(single "${gyro}")
      set(single_index ${index})
    else()
      set(single "${accel}")
      math(EXPR single_index "${index} - 3")
    endif()
    string(JSON name GET "${both}" channels ${index} name)
    string(JSON a GET "${both}" channels ${index} parameters N value)
    string(JSON b GET "${single}" channels ${single_index} parameters N value)
    string(JSON quantity GET "${both}" channels ${index} quantity)
    if(index LESS 3 AND NOT quantity STREQUAL "angular_rate")
      message(FATAL_ERROR "${name}: quantity ${quantity}, expected angular_rate")
    endif()
    if(index GREATER 2 AND NOT quantity STREQUAL "specific_force")
      message(FATAL_ERROR "${name}: quantity ${quantity}, expected specific_force")
    endif()
    # Relative difference from the decimal strings (cmake has no floating point): equal to 12
    # significant digits.
    string(REGEX MATCH "^[0-9]\\.?[0-9]*" ma "${a}")
    string(REGEX MATCH "^[0-9]\\.?[0-9]*" mb "${b}")
    string(REGEX MATCH "e[-+]?[0-9]+$" ea "${a}")
    string(REGEX MATCH "e[-+]?[0-9]+$" eb "${b}")
    string(REPLACE "." "" da "${ma}")
    string(REPLACE "." "" db "${mb}")
    string(SUBSTRING "${da}000000000000" 0 12 da)
    string(SUBSTRING "${db}000000000000" 0 12 db)
    if(NOT ea STREQUAL eb OR NOT da STREQUAL db)
      message(FATAL_ERROR "${name}: N ${a} with --gyro-unit/--accel-unit, ${b} alone with --unit")
    endif()
  endforeach()
  # The one result gives a Kalibr file with all four keys and no warning.
  execute_process(COMMAND ${CMD} convert --fit ${DIR}/both.json --rate 10 --to kalibr
                  OUTPUT_VARIABLE kalibr ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0 OR kalibr MATCHES "not given" OR err MATCHES "warning")
    message(FATAL_ERROR "convert exited ${rc}; file:\n${kalibr}\nstderr: ${err}")
  endif()
  foreach(key gyroscope_noise_density accelerometer_noise_density gyroscope_random_walk
              accelerometer_random_walk)
    if(NOT kalibr MATCHES "\n${key}: [0-9]")
      message(FATAL_ERROR "no ${key} in\n${kalibr}")
    endif()
  endforeach()
  return()
endif()

set(imu6 ${PROJECT_SOURCE_DIR}/tests/data/cli/imu6_10Hz.csv)
add_test(NAME cli_fit_sensor_units_one_run
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>" -DLOG=${imu6}
                 -DDIR=${CMAKE_CURRENT_BINARY_DIR}/cli_fit_sensor_units -P ${CMAKE_CURRENT_LIST_FILE})
sigmatau_cli_test(NAME cli_fit_sensor_units_with_unit EXIT 2
  STDERR "--unit deg/s names one unit for every column; with --gyro-unit / --accel-unit leave it out"
  ARGS fit ${imu6} --time-column t --unit deg/s --accel-unit g)
sigmatau_cli_test(NAME cli_fit_sensor_units_wrong_dimension EXIT 2 STDERR "--accel-unit: expected"
  ARGS fit ${imu6} --time-column t --gyro-unit deg/s --accel-unit deg/s)
# A column whose name says no sensor cannot take a sensor's unit.
# (t named as a channel: without that it is the time column, found by its name.)
sigmatau_cli_test(NAME cli_fit_sensor_units_unknown_column EXIT 2
  STDERR "column \"t\" is neither a gyro nor an accelerometer by its name"
  ARGS fit ${imu6} --rate 10 --columns t,gx,gy,gz,ax,ay,az --gyro-unit deg/s --accel-unit g)
