# cmake -P helper: run CMD with ARGS_A and with ARGS_B ("@@"-separated), both must exit 0 (the
# first EXIT_A when given) and print the same stdout (e.g. a bag and the same data as CSV give
# the same table).
string(REPLACE "@@" ";" a "${ARGS_A}")
string(REPLACE "@@" ";" b "${ARGS_B}")
if(NOT DEFINED EXIT_A OR EXIT_A STREQUAL "")
  set(EXIT_A 0)
endif()
execute_process(COMMAND ${CMD} ${a} RESULT_VARIABLE code_a OUTPUT_VARIABLE out_a ERROR_VARIABLE err_a)
execute_process(COMMAND ${CMD} ${b} RESULT_VARIABLE code_b OUTPUT_VARIABLE out_b ERROR_VARIABLE err_b)
if(NOT code_a EQUAL EXIT_A OR NOT code_b EQUAL 0)
  message(FATAL_ERROR "exit codes ${code_a} and ${code_b}, expected ${EXIT_A} and 0\n${err_a}\n${err_b}")
endif()
if(out_a STREQUAL "")
  message(FATAL_ERROR "no output from ${CMD} ${a}")
endif()
if(NOT out_a STREQUAL out_b)
  message(FATAL_ERROR "outputs differ\n--- ${a} ---\n${out_a}\n--- ${b} ---\n${out_b}")
endif()
