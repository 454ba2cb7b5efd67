# `sigmatau simulate` options of issue 4: --out-unit (values read back with `adev --unit` give the
# same table as the SI log), the real quantizer, per-axis models, a user truth CSV (--truth).
set(SIMO_DIR ${CMAKE_CURRENT_BINARY_DIR}/simulate_options)
file(MAKE_DIRECTORY ${SIMO_DIR})

# A checker for files the simulator wrote (cmake -P):
#   FILE, LINES = "N=REGEX@@N=REGEX..." : line N (1-based) of FILE matches REGEX;
#   JSON = "a/b/0/c=REGEX@@..."        : that member of the JSON FILE matches REGEX;
#   COLUMN = i, ALL = REGEX             : field i (0-based) of every line after the header matches;
#   SIZE_FROM_JSON = DATA               : DATA's size in bytes is the JSON FILE's file/bytes.
file(WRITE ${SIMO_DIR}/check_simulated.cmake [=[
file(STRINGS "${FILE}" lines)
set(failed FALSE)
if(LINES)
  string(REPLACE "@@" ";" items "${LINES}")
  foreach(item IN LISTS items)
    string(FIND "${item}" "=" eq)
    string(SUBSTRING "${item}" 0 ${eq} n)
    math(EXPR start "${eq} + 1")
    string(SUBSTRING "${item}" ${start} -1 re)
    math(EXPR index "${n} - 1")
    list(GET lines ${index} line)
    if(NOT line MATCHES "${re}")
      message(SEND_ERROR "${FILE}:${n}: '${line}' does not match '${re}'")
      set(failed TRUE)
    endif()
  endforeach()
endif()
if(JSON)
  file(READ "${FILE}" text)
  string(REPLACE "@@" ";" items "${JSON}")
  foreach(item IN LISTS items)
    string(FIND "${item}" "=" eq)
    string(SUBSTRING "${item}" 0 ${eq} path)
    math(EXPR start "${eq} + 1")
    string(SUBSTRING "${item}" ${start} -1 re)
    string(REPLACE "/" ";" keys "${path}")
    string(JSON value ERROR_VARIABLE err GET "${text}" ${keys})
    if(err OR NOT value MATCHES "${re}")
      message(SEND_ERROR "${FILE}: ${path} = '${value}' does not match '${re}' ${err}")
      set(failed TRUE)
    endif()
  endforeach()
endif()
if(DEFINED COLUMN)
  list(LENGTH lines count)
  math(EXPR last "${count} - 1")
  foreach(i RANGE 1 ${last})
    list(GET lines ${i} line)
    string(REPLACE "," ";" fields "${line}")
    list(GET fields ${COLUMN} value)
    if(NOT value MATCHES "${ALL}")
      message(SEND_ERROR "${FILE}:${i}: field ${COLUMN} '${value}' does not match '${ALL}'")
      set(failed TRUE)
      break()
    endif()
  endforeach()
endif()
if(SIZE_FROM_JSON)
  # The data file SIZE_FROM_JSON has the size the sidecar FILE states in file/bytes.
  file(READ "${FILE}" text)
  string(JSON bytes GET "${text}" file bytes)
  file(SIZE "${SIZE_FROM_JSON}" actual)
  if(NOT actual EQUAL bytes)
    message(SEND_ERROR "${SIZE_FROM_JSON}: ${actual} bytes, the sidecar says ${bytes}")
    set(failed TRUE)
  endif()
endif()
if(failed)
  message(FATAL_ERROR "check failed")
endif()
]=])
function(simo_check name depends)
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} ${ARGN} -P ${SIMO_DIR}/check_simulated.cmake)
  set_tests_properties(${name} PROPERTIES DEPENDS ${depends})
endfunction()

# --- --out-unit: the same seed in SI and in deg/h, mg; `adev --unit` reads both back to the same
# table (the written value is SI / factor, read back as value x factor: 1 ulp, far below the
# table's 7 digits).
set(simo_model --model "N=0.15 deg/sqrt(h), B=3 deg/h" --accel-model "N=60 ug/sqrt(Hz), B=0.05 mg"
    --sensors gyro,accel --rate 100 --duration 2min --seed 21 --force)
sigmatau_cli_test(NAME cli_simulate_out_unit_si EXIT 0 WORKING_DIRECTORY ${SIMO_DIR} STDOUT "wrote"
  ARGS simulate ${simo_model} -o si.csv)
sigmatau_cli_test(NAME cli_simulate_out_unit EXIT 0 WORKING_DIRECTORY ${SIMO_DIR} STDOUT "wrote"
  ARGS simulate ${simo_model} --out-unit "deg/h, mg" -o units.csv)
simo_check(cli_simulate_out_unit_sidecar "cli_simulate_out_unit"
  -DFILE=${SIMO_DIR}/units.csv.json "-DJSON=output_units/gyro=^deg/h$@@output_units/accel=^mg$")
foreach(sensor gyro accel)
  if(sensor STREQUAL gyro)
    set(cols gx,gy,gz)
    set(si rad/s)
    set(written deg/h)
  else()
    set(cols ax,ay,az)
    set(si m/s^2)
    set(written mg)
  endif()
  add_test(NAME cli_simulate_out_unit_reads_back_${sensor}
           COMMAND ${CMAKE_COMMAND} -DCMD=$<TARGET_FILE:sigmatau_cli>
                   "-DARGS_A=adev@@si.csv@@--time-column@@t@@--columns@@${cols}@@--unit@@${si}@@--out-unit@@${written}@@--format@@csv"
                   "-DARGS_B=adev@@units.csv@@--time-column@@t@@--columns@@${cols}@@--unit@@${written}@@--out-unit@@${written}@@--format@@csv"
                   -P ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake
           WORKING_DIRECTORY ${SIMO_DIR})
  set_tests_properties(cli_simulate_out_unit_reads_back_${sensor} PROPERTIES
                       DEPENDS "cli_simulate_out_unit_si;cli_simulate_out_unit")
endforeach()
# Increments in deg and mm/s read back with adev --kind increment.
set(simo_inc --model "N=0.15 deg/sqrt(h)" --accel-model "N=60 ug/sqrt(Hz)" --sensors gyro,accel
    --kind increment --rate 100 --duration 1min --seed 22 --force)
sigmatau_cli_test(NAME cli_simulate_out_unit_inc_si EXIT 0 WORKING_DIRECTORY ${SIMO_DIR}
  STDOUT "kind increment" ARGS simulate ${simo_inc} -o inc_si.csv)
sigmatau_cli_test(NAME cli_simulate_out_unit_inc EXIT 0 WORKING_DIRECTORY ${SIMO_DIR}
  STDOUT "kind increment" ARGS simulate ${simo_inc} --out-unit "mm/s, deg" -o inc_units.csv)
add_test(NAME cli_simulate_out_unit_inc_reads_back
         COMMAND ${CMAKE_COMMAND} -DCMD=$<TARGET_FILE:sigmatau_cli>
                 "-DARGS_A=adev@@inc_si.csv@@--time-column@@t@@--kind@@increment@@--unit@@rad@@--columns@@gx@@--out-unit@@deg/s@@--format@@csv"
                 "-DARGS_B=adev@@inc_units.csv@@--time-column@@t@@--kind@@increment@@--unit@@deg@@--columns@@gx@@--out-unit@@deg/s@@--format@@csv"
                 -P ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake
         WORKING_DIRECTORY ${SIMO_DIR})
set_tests_properties(cli_simulate_out_unit_inc_reads_back PROPERTIES
                     DEPENDS "cli_simulate_out_unit_inc_si;cli_simulate_out_unit_inc")
sigmatau_cli_test(NAME cli_simulate_out_unit_wrong_kind EXIT 2 NO_FILE ${SIMO_DIR}/bad.csv
  WORKING_DIRECTORY ${SIMO_DIR} STDERR "fits no simulated sensor of kind increment"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --kind increment --out-unit deg/s --rate 100
       --duration 1 -o bad.csv)
sigmatau_cli_test(NAME cli_simulate_out_unit_counts EXIT 2 NO_FILE ${SIMO_DIR}/bad.csv
  WORKING_DIRECTORY ${SIMO_DIR} STDERR "does not apply to --kind counts"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --kind counts --gyro-lsb "0.01 deg/s"
       --gyro-full-scale "250 deg/s" --out-unit deg/s --rate 100 --duration 1 -o bad.csv)
sigmatau_cli_test(NAME cli_simulate_out_unit_twice EXIT 2 NO_FILE ${SIMO_DIR}/bad.csv
  WORKING_DIRECTORY ${SIMO_DIR} STDERR "two units for the gyro"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --out-unit "deg/s, deg/h" --rate 100 --duration 1
       -o bad.csv)

# --- the real quantizer: increments of 0.001 deg written in deg are whole thousandths (up to the
# rounding of deg -> rad -> deg: a run of 0s or 9s after the third decimal).
sigmatau_cli_test(NAME cli_simulate_quantizer EXIT 0 WORKING_DIRECTORY ${SIMO_DIR} STDOUT "wrote"
  ARGS simulate --model "N=1 deg/sqrt(h)" --gyro-quantizer "0.001 deg" --kind increment
       --out-unit deg --rate 100 --duration 20 --seed 4 --force -o quantized.csv)
simo_check(cli_simulate_quantizer_steps "cli_simulate_quantizer"
  -DFILE=${SIMO_DIR}/quantized.csv -DCOLUMN=1
  "-DALL=^-?[0-9]+(\\.[0-9]?[0-9]?[0-9]?(0000000+[0-9]*|9999999+[0-9]*)?)?$")
simo_check(cli_simulate_quantizer_sidecar "cli_simulate_quantizer"
  -DFILE=${SIMO_DIR}/quantized.csv.json "-DJSON=gyro/quantizer_step=^1\\.745329251994[0-9]*e-05$")
sigmatau_cli_test(NAME cli_simulate_quantizer_dimension EXIT 2 NO_FILE ${SIMO_DIR}/bad.csv
  WORKING_DIRECTORY ${SIMO_DIR} STDERR "--gyro-quantizer"
  ARGS simulate --model "N=1 deg/sqrt(h)" --gyro-quantizer "0.001 deg/s" --rate 100 --duration 1
       -o bad.csv)

# --- per-axis models: x and the group yz get their own terms (sidecar, SI: 0.15 deg/sqrt(h) =
# 4.3633e-5 rad/s/sqrt(Hz), 1.5 deg/sqrt(h) = 4.3633e-4, 3 deg/h = 1.4544e-5 rad/s). The ';' of
# the syntax is CMake's list separator, so these commands run from a bash script that turns each
# '|' into ';': $1 is sigmatau, $2 the expected exit code, $3 a grep pattern for stderr, then the
# model options.
file(WRITE ${SIMO_DIR}/per_axis.sh [=[
cmd=$1; expected=$2; pattern=$3; shift 3
args=()
for a in "$@"; do args+=("${a//|/;}"); done
err=$("$cmd" simulate "${args[@]}" --rate 100 --duration 10 --force 2>&1 >/dev/null)
code=$?
if [ "$code" != "$expected" ]; then echo "exit $code, expected $expected: $err"; exit 1; fi
if [ -n "$pattern" ] && ! printf '%s' "$err" | grep -q -- "$pattern"; then
  echo "stderr '$err' lacks '$pattern'"; exit 1
fi
]=])
add_test(NAME cli_simulate_per_axis
         COMMAND bash per_axis.sh $<TARGET_FILE:sigmatau_cli> 0 ""
                 --model "x: N=0.15 deg/sqrt(h)| yz: N=1.5 deg/sqrt(h), B=3 deg/h"
                 --accel-model "z: N=60 ug/sqrt(Hz)" --sensors gyro,accel -o per_axis.csv
         WORKING_DIRECTORY ${SIMO_DIR})
simo_check(cli_simulate_per_axis_sidecar "cli_simulate_per_axis"
  -DFILE=${SIMO_DIR}/per_axis.csv.json
  "-DJSON=gyro/noise/0/white=^4\\.3633231[0-9]*e-05$@@gyro/noise/1/white=^0\\.00043633231[0-9]*$@@gyro/noise/2/bias_instability=^1\\.45444104[0-9]*e-05$@@accel/noise/2/white=^0\\.00058839[0-9]*$")
simo_check(cli_simulate_per_axis_absent "cli_simulate_per_axis"
  -DFILE=${SIMO_DIR}/per_axis.csv.json "-DJSON=gyro/noise/0=^{[^\"]*\"white\"[^,]*}$@@accel/noise/0=^{[^\"]*}$")
add_test(NAME cli_simulate_per_axis_unlabelled
         COMMAND bash per_axis.sh $<TARGET_FILE:sigmatau_cli> 2 "has no axis label"
                 --model "x: N=0.15 deg/sqrt(h)| N=1 deg/sqrt(h)" -o bad.csv
         WORKING_DIRECTORY ${SIMO_DIR})
# A sum of Gauss-Markov processes: up to three GM keys; a fourth is an error naming the item.
add_test(NAME cli_simulate_gauss_markov_sum
         COMMAND bash per_axis.sh $<TARGET_FILE:sigmatau_cli> 0 ""
                 --model "N=0.15 deg/sqrt(h), GM=0.01 deg/s @ 100 s, GM=0.003 deg/s @ 2000 s"
                 -o gm_sum.csv
         WORKING_DIRECTORY ${SIMO_DIR})
simo_check(cli_simulate_gauss_markov_sum_sidecar "cli_simulate_gauss_markov_sum"
  -DFILE=${SIMO_DIR}/gm_sum.csv.json
  "-DJSON=gyro/noise/0/gauss_markov/0/tau_c_s=^100(\\.0)?$@@gyro/noise/0/gauss_markov/1/tau_c_s=^2000(\\.0)?$")
add_test(NAME cli_simulate_fourth_gauss_markov
         COMMAND bash per_axis.sh $<TARGET_FILE:sigmatau_cli> 2
                 "'GM=4 deg/s @ 1000 s' is Gauss-Markov term number 4; at most 3"
                 --model "GM=1 deg/s @ 1 s, GM=2 deg/s @ 10 s, GM=3 deg/s @ 100 s, GM=4 deg/s @ 1000 s"
                 -o bad.csv
         WORKING_DIRECTORY ${SIMO_DIR})
add_test(NAME cli_simulate_per_axis_twice
         COMMAND bash per_axis.sh $<TARGET_FILE:sigmatau_cli> 2 "axis y is given twice"
                 --model "xy: N=0.15 deg/sqrt(h)| y: N=1 deg/sqrt(h)" -o bad.csv
         WORKING_DIRECTORY ${SIMO_DIR})

# --- --truth: gx goes 1 -> 2 deg/s over 10 s, gz 0 -> -4 deg/s, held after; with scale 1 % and
# bias 1 deg/s on x the noise-free output is 1.01 x + 1 (t = 5 s: 2.515; t = 11 s: 3.02).
file(WRITE ${SIMO_DIR}/truth.csv "t,gx,gy,gz\n0,1,0,0\n10,2,0,-4\n")
sigmatau_cli_test(NAME cli_simulate_truth EXIT 0 WORKING_DIRECTORY ${SIMO_DIR} STDOUT "wrote"
  ARGS simulate --truth truth.csv --truth-unit deg/s --sensors gyro
       --gyro-bias "1 deg/s,0 deg/s,0 deg/s" --gyro-scale "1 %,0,0" --out-unit deg/s --rate 1
       --duration 12 --force -o truth_out.csv)
simo_check(cli_simulate_truth_values "cli_simulate_truth" -DFILE=${SIMO_DIR}/truth_out.csv
  "-DLINES=2=^0,2\\.01(0000000+[0-9]*|99999999+[0-9]*)?,0,0$@@7=^5,2\\.515(0000000+[0-9]*|4999999+[0-9]*)?,0,-2(\\.0000000+[0-9]*|\\.9999999+[0-9]*)?$@@13=^11,3\\.02(0000000+[0-9]*|99999999+[0-9]*)?,0,-4(\\.0000000+[0-9]*)?$")
simo_check(cli_simulate_truth_sidecar "cli_simulate_truth" -DFILE=${SIMO_DIR}/truth_out.csv.json
  "-DJSON=truth_series/rows=^2$@@truth_series/source=truth\\.csv$")
sigmatau_cli_test(NAME cli_simulate_truth_missing_columns EXIT 2 NO_FILE ${SIMO_DIR}/bad.csv
  WORKING_DIRECTORY ${SIMO_DIR} STDERR "truth\\.csv.*ax"
  ARGS simulate --truth truth.csv --sensors gyro,accel --rate 1 --duration 2 -o bad.csv)
sigmatau_cli_test(NAME cli_simulate_truth_unit_alone EXIT 2 NO_FILE ${SIMO_DIR}/bad.csv
  WORKING_DIRECTORY ${SIMO_DIR} STDERR "--truth-unit is given without --truth"
  ARGS simulate --truth-unit deg/s --model "N=1 deg/sqrt(h)" --rate 1 --duration 2 -o bad.csv)
sigmatau_cli_test(NAME cli_simulate_truth_and_positions EXIT 2 NO_FILE ${SIMO_DIR}/bad.csv
  WORKING_DIRECTORY ${SIMO_DIR} STDERR "either --truth or --positions"
  ARGS simulate --truth truth.csv --positions 6 --rate 10 -o bad.csv)

# --- review C finding 9: a binary file's sidecar describes the file as written. f32 with gyro,
# accel and a temperature profile holds 7 channels and no time column: 50 Hz x 4 s x 7 x 4 B =
# 5600 B, read back with --binary f32 --channels 7 --rate 50; csv keeps t first.
sigmatau_cli_test(NAME cli_simulate_binary_columns EXIT 0 WORKING_DIRECTORY ${SIMO_DIR}
  STDOUT "wrote" ARGS simulate --model "N=0.15 deg/sqrt(h)" --accel-model "N=60 ug/sqrt(Hz)"
       --sensors gyro,accel --temperature "20 degC @ 0 s" --rate 50 --duration 4 --format f32
       --force -o bin.f32)
simo_check(cli_simulate_binary_columns_sidecar "cli_simulate_binary_columns"
  -DFILE=${SIMO_DIR}/bin.f32.json -DSIZE_FROM_JSON=${SIMO_DIR}/bin.f32
  "-DJSON=columns/0=^gx$@@columns/6=^temp$@@file/channels=^7$@@file/bytes=^5600$@@file/read_with=^--binary f32 --channels 7 --rate 50$")
sigmatau_cli_test(NAME cli_simulate_binary_f64_increment EXIT 0 WORKING_DIRECTORY ${SIMO_DIR}
  STDOUT "wrote" ARGS simulate --model "N=0.15 deg/sqrt(h)" --kind increment --rate 100
       --duration 2 --format f64 --force -o inc.f64)
simo_check(cli_simulate_binary_f64_increment_sidecar "cli_simulate_binary_f64_increment"
  -DFILE=${SIMO_DIR}/inc.f64.json -DSIZE_FROM_JSON=${SIMO_DIR}/inc.f64
  "-DJSON=columns/0=^gx$@@file/read_with=^--binary f64 --channels 3 --rate 100 --kind increment$@@file/time=\\(k \\+ 1\\) / rate_hz")
# Counts written as f32 (the only binary form simulate writes): 3 channels of whole numbers.
simo_check(cli_simulate_f32_counts_sidecar "cli_simulate_f32"
  -DFILE=${SIM_DIR}/sim.f32.json -DSIZE_FROM_JSON=${SIM_DIR}/sim.f32
  "-DJSON=columns/0=^gx$@@file/read_with=^--binary f32 --channels 3 --rate 50$@@output_units/gyro=^counts$")
simo_check(cli_simulate_csv_columns_sidecar "cli_simulate_out_unit_si"
  -DFILE=${SIMO_DIR}/si.csv.json "-DJSON=columns/0=^t$@@columns/1=^gx$@@file/read_with=^--time-column t$")

# --- review C finding 8: --spec and the noise terms a sheet does not print.
sigmatau_cli_test(NAME cli_simulate_spec_no_accel_noise EXIT 2 NO_FILE ${SIMO_DIR}/bad.csv
  WORKING_DIRECTORY ${SIMO_DIR}
  STDERR "data sheet gyro_noise_only .*prints no accel noise term.*--accel-model"
  ARGS simulate --spec ${PROJECT_SOURCE_DIR}/tests/data/specs/gyro_noise_only.yaml
       --sensors gyro,accel --rate 100 --duration 10 -o bad.csv)
# A fixture with gyro ranges only and an accelerometer RMS noise only (tests/data/specs).
sigmatau_cli_test(NAME cli_simulate_spec_no_gyro_noise EXIT 2 NO_FILE ${SIMO_DIR}/bad.csv
  WORKING_DIRECTORY ${SIMO_DIR}
  STDERR "data sheet no_noise_terms .*prints no gyro noise term.*--model"
  ARGS simulate --spec ${PROJECT_SOURCE_DIR}/tests/data/specs/no_noise_terms.yaml --sensors gyro
       --rate 100 --duration 10 -o bad.csv)
sigmatau_cli_test(NAME cli_simulate_spec_rms_only EXIT 2 NO_FILE ${SIMO_DIR}/bad.csv
  WORKING_DIRECTORY ${SIMO_DIR} STDERR "RMS noise 2\\.5 mg is a total over the output band"
  ARGS simulate --spec ${PROJECT_SOURCE_DIR}/tests/data/specs/no_noise_terms.yaml --sensors accel
       --rate 100 --duration 10 -o bad.csv)
sigmatau_cli_test(NAME cli_simulate_spec_no_white EXIT 0 WORKING_DIRECTORY ${SIMO_DIR}
  STDOUT "wrote"
  STDERR "warning: data sheet adi_adis16470 .*prints no white noise for the accel.*left out: white noise"
  ARGS simulate --spec adi_adis16470 --sensors gyro,accel --rate 100 --duration 10 --force
       -o adis.csv)
simo_check(cli_simulate_spec_no_white_sidecar "cli_simulate_spec_no_white"
  -DFILE=${SIMO_DIR}/adis.csv.json
  "-DJSON=accel/noise_source/origin=^data sheet adi_adis16470$@@accel/noise_source/left_out/0=^white noise@@gyro/noise_source/read/0=^angle random walk")
# --accel-model supplies what the sheet lacks; the gyro stays the sheet's.
sigmatau_cli_test(NAME cli_simulate_spec_with_accel_model EXIT 0 WORKING_DIRECTORY ${SIMO_DIR}
  STDOUT "wrote" ARGS simulate --spec ${PROJECT_SOURCE_DIR}/tests/data/specs/gyro_noise_only.yaml
       --accel-model "N=190 ug/sqrt(Hz)"
       --sensors gyro,accel --rate 100 --duration 10 --force -o bmi.csv)
simo_check(cli_simulate_spec_with_accel_model_sidecar "cli_simulate_spec_with_accel_model"
  -DFILE=${SIMO_DIR}/bmi.csv.json
  "-DJSON=accel/noise_source/origin=^--accel-model$@@gyro/noise_source/origin=^data sheet gyro_noise_only$@@accel/noise/0/white=^0\\.00186")

# --- review C finding 5: a real quantizer 40x the per-sample noise (0.01 deg against
# 0.15 deg/sqrt(h) x sqrt(10 ms) = 2.5e-4 deg). White noise only: the sidecar's exact theory gives
# ADEV(10 ms) = 580 deg/h, AVAR 7.9e-6 (rad/s)^2, as the log measures (tests/
# test_simulate_quantizer.cpp), not 1802 deg/h = 7.6e-5 from 3 Q^2/tau^2.
sigmatau_cli_test(NAME cli_simulate_coarse_quantizer EXIT 0 WORKING_DIRECTORY ${SIMO_DIR}
  STDOUT "wrote" ARGS simulate --model "N=0.15 deg/sqrt(h)" --rate 100 --duration 5min
       --gyro-quantizer "0.01 deg" --force -o coarse.csv)
simo_check(cli_simulate_coarse_quantizer_sidecar "cli_simulate_coarse_quantizer"
  -DFILE=${SIMO_DIR}/coarse.csv.json
  "-DJSON=theory/avar/gx/0=^7\\.9[0-9]*e-06$@@theory/quantizer=^the real quantizer's AVAR is exact")
# With a rate random walk there is no exact theory: a warning on stderr and in the sidecar.
sigmatau_cli_test(NAME cli_simulate_coarse_quantizer_rrw EXIT 0 WORKING_DIRECTORY ${SIMO_DIR}
  STDOUT "wrote"
  STDERR "warning: the gyro quantizer step is 40x the per-sample white noise on gx, gy, gz"
  ARGS simulate --model "N=0.15 deg/sqrt(h), K=0.02 deg/h/sqrt(h)" --rate 100 --duration 1min
       --gyro-quantizer "0.01 deg" --force -o coarse_k.csv)
simo_check(cli_simulate_coarse_quantizer_rrw_sidecar "cli_simulate_coarse_quantizer_rrw"
  -DFILE=${SIMO_DIR}/coarse_k.csv.json "-DJSON=warnings/0=^the gyro quantizer step is 40x")

# --- counts as a sensor's registers give them: --format i16 / i32 (kind counts only). The same
# seed as csv reads back to the same adev table (only the channel name differs: c0 vs gx).
set(simo_counts --model "N=0.15 deg/sqrt(h), GM=1 deg/h @ 10 s" --rate 50 --duration 2min
    --kind counts --gyro-lsb "0.01 deg/s" --gyro-full-scale "250 deg/s" --seed 5 --force)
sigmatau_cli_test(NAME cli_simulate_i16 EXIT 0 WORKING_DIRECTORY ${SIMO_DIR} STDOUT "wrote"
  ARGS simulate ${simo_counts} --format i16 -o counts.i16)
simo_check(cli_simulate_i16_sidecar "cli_simulate_i16"
  -DFILE=${SIMO_DIR}/counts.i16.json -DSIZE_FROM_JSON=${SIMO_DIR}/counts.i16
  "-DJSON=file/bytes=^36000$@@file/read_with=^--binary i16 --channels 3 --rate 50$@@columns/2=^gz$")
sigmatau_cli_test(NAME cli_simulate_i16_csv EXIT 0 WORKING_DIRECTORY ${SIMO_DIR} STDOUT "wrote"
  ARGS simulate ${simo_counts} -o counts.csv)
file(WRITE ${SIMO_DIR}/same_but_name.sh [=[
# $1 sigmatau; $2 and $3: '@'-separated argument lists; the csv outputs must agree after the
# first field (the channel name).
cmd=$1
IFS=@ read -r -a a <<< "$2"
IFS=@ read -r -a b <<< "$3"
out_a=$("$cmd" "${a[@]}" | cut -d, -f2-) || exit 1
out_b=$("$cmd" "${b[@]}" | cut -d, -f2-) || exit 1
[ -n "$out_a" ] || { echo "no output"; exit 1; }
[ "$out_a" = "$out_b" ] || { printf 'differ:\n%s\n---\n%s\n' "$out_a" "$out_b"; exit 1; }
]=])
add_test(NAME cli_simulate_i16_reads_back
         COMMAND bash same_but_name.sh $<TARGET_FILE:sigmatau_cli>
                 "adev@counts.i16@--binary@i16@--channels@3@--rate@50@--columns@0@--format@csv"
                 "adev@counts.csv@--time-column@t@--columns@gx@--format@csv"
         WORKING_DIRECTORY ${SIMO_DIR})
set_tests_properties(cli_simulate_i16_reads_back PROPERTIES
                     DEPENDS "cli_simulate_i16;cli_simulate_i16_csv")
sigmatau_cli_test(NAME cli_simulate_i32 EXIT 0 WORKING_DIRECTORY ${SIMO_DIR} STDOUT "wrote"
  ARGS simulate ${simo_counts} --format i32 -o counts.i32)
simo_check(cli_simulate_i32_sidecar "cli_simulate_i32"
  -DFILE=${SIMO_DIR}/counts.i32.json -DSIZE_FROM_JSON=${SIMO_DIR}/counts.i32
  "-DJSON=file/bytes=^72000$@@file/read_with=^--binary i32 --channels 3 --rate 50$")
sigmatau_cli_test(NAME cli_simulate_i16_needs_counts EXIT 2 NO_FILE ${SIMO_DIR}/bad.i16
  WORKING_DIRECTORY ${SIMO_DIR} STDERR "format i16 writes integers: it needs --kind counts"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --rate 50 --duration 2 --format i16 -o bad.i16)
sigmatau_cli_test(NAME cli_simulate_i16_full_scale EXIT 2 NO_FILE ${SIMO_DIR}/bad.i16
  WORKING_DIRECTORY ${SIMO_DIR} STDERR "gyro full scale is 200000 LSB, more than 32767; use i32"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --rate 50 --duration 2 --kind counts
       --gyro-lsb "0.01 deg/s" --gyro-full-scale "2000 deg/s" --format i16 -o bad.i16)
sigmatau_cli_test(NAME cli_simulate_i16_temperature EXIT 2 NO_FILE ${SIMO_DIR}/bad.i16
  WORKING_DIRECTORY ${SIMO_DIR} STDERR "cannot hold the temperature channel"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --rate 50 --duration 2 --kind counts
       --gyro-lsb "0.01 deg/s" --gyro-full-scale "250 deg/s" --temperature "20 degC @ 0 s"
       --format i16 -o bad.i16)
