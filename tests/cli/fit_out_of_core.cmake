# CLI regression cases for `sigmatau fit` on logs larger than --memory (issues 3 and 10): the
# OADEV curves are computed exactly out of core, as `adev` does, and the fit is the in-memory
# one byte for byte (its JSON prints every double to 17 significant digits).
set(example ${PROJECT_SOURCE_DIR}/examples/gyro_static_100Hz.csv.gz)

add_test(NAME cli_fit_out_of_core_same_as_memory
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=fit@@${example}@@--time-column@@t@@--unit@@deg/s@@--memory@@1K@@--format@@json"
                 "-DARGS_B=fit@@${example}@@--time-column@@t@@--unit@@deg/s@@--format@@json"
                 -P ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake)
# Phase input has N phase points (not N + 1): the curve source the fit uses must say so.
add_test(NAME cli_fit_out_of_core_phase_same_as_memory
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>"
                 "-DARGS_A=fit@@${example}@@--time-column@@t@@--kind@@phase@@--unit@@deg@@--method@@both@@--memory@@1K@@--threads@@1@@--format@@json"
                 "-DARGS_B=fit@@${example}@@--time-column@@t@@--kind@@phase@@--unit@@deg@@--method@@both@@--format@@json"
                 -P ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake)
sigmatau_cli_test(NAME cli_fit_out_of_core_note EXIT 0
  STDERR "computing the OADEV curves exactly out of core"
  ARGS fit ${example} --time-column t --unit deg/s --memory 1K)
# A pipe cannot be read twice: it stays in memory whatever --memory says.
sigmatau_cli_test(NAME cli_fit_out_of_core_stdin_in_memory EXIT 0 STDIN ${example}
  STDOUT "angle random walk" ARGS fit - --time-column t --unit deg/s --memory 1K)
# --gaps fill needs the whole log: in memory too (no note).
sigmatau_cli_test(NAME cli_fit_out_of_core_fill_in_memory EXIT 0 STDOUT "angle random walk"
  ARGS fit ${example} --time-column t --unit deg/s --gaps fill --memory 1K)
sigmatau_cli_test(NAME cli_fit_out_of_core_bad_memory EXIT 2 STDERR "--memory must be a size"
  ARGS fit ${example} --time-column t --memory lots)
# The unit is checked before the (possibly long) log is read.
sigmatau_cli_test(NAME cli_fit_out_of_core_bad_unit EXIT 2
  STDERR "neither an angular rate nor an acceleration"
  ARGS fit ${example} --time-column t --unit deg --memory 1K)
