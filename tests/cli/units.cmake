# CLI regression cases for `sigmatau units` (see sigmatau_cli_test in tests/CMakeLists.txt).
# Expected numbers come from the definitions (deg = pi/180 rad, h = 3600 s), not from sigmatau:
# 0.3 deg/sqrt(h) = 0.3/60 deg/s/sqrt(Hz) = 0.005; 0.15 deg/sqrt(h) = 0.15*pi/180/60 rad/sqrt(s)
# = 4.363323130e-05; 1 deg/h = pi/180/3600 rad/s = 4.848136811e-06; -40 degC = 233.15 K.

sigmatau_cli_test(NAME cli_units_convert EXIT 0 STDOUT "^0\\.005 deg/s/sqrt\\(Hz\\)"
  ARGS units "0.3 deg/sqrt(h)" --to "deg/s/sqrt(Hz)")
sigmatau_cli_test(NAME cli_units_value_and_unit_apart EXIT 0 STDOUT "^0\\.005 deg/s/sqrt\\(Hz\\)"
  ARGS units 0.3 "deg/sqrt(h)" --to "deg/s/sqrt(Hz)")
sigmatau_cli_test(NAME cli_units_si EXIT 0 STDOUT "^4\\.36332313e-05 rad/sqrt\\(s\\)"
  ARGS units "0.15 °/√h")
sigmatau_cli_test(NAME cli_units_unit_alone EXIT 0 STDOUT "^4\\.848136811e-06 rad/s"
  ARGS units deg/h)
sigmatau_cli_test(NAME cli_units_negative_celsius EXIT 0 STDOUT "^233\\.15 K"
  ARGS units -40 degC --to K)
sigmatau_cli_test(NAME cli_units_digits EXIT 0 STDOUT "^0\\.0412 m/s/sqrt\\(h\\)"
  ARGS units "70 ug/sqrt(Hz)" --to "m/s/sqrt(h)" --digits 3)
sigmatau_cli_test(NAME cli_units_list EXIT 0 STDOUT "g +9\\.80665 m/s\\^2 .*standard gravity"
  ARGS units --list)

sigmatau_cli_test(NAME cli_units_unknown_unit EXIT 2
  STDERR "unknown unit \"foo\" at column 5 of \"1\\.0 foo\""
  ARGS units "1.0 foo")
sigmatau_cli_test(NAME cli_units_bad_to_unit EXIT 2 STDERR "unknown unit \"furlong\""
  ARGS units "1 deg/s" --to furlong)
sigmatau_cli_test(NAME cli_units_dimension_mismatch EXIT 2
  STDERR "cannot convert 1 deg/s \\(angle/time\\) to m/s\\^2 \\(length/time\\^2\\)"
  ARGS units "1 deg/s" --to "m/s^2")
sigmatau_cli_test(NAME cli_units_double_slash EXIT 2 STDERR "column 5 of \"deg//s\""
  ARGS units "deg//s")
sigmatau_cli_test(NAME cli_units_out_of_range EXIT 2 STDERR "out of double range"
  ARGS units "1e999 deg")
sigmatau_cli_test(NAME cli_units_bad_digits EXIT 2 STDERR "--digits"
  ARGS units 1 deg --digits 0)
sigmatau_cli_test(NAME cli_units_nothing EXIT 2 STDERR "give a value with its unit"
  ARGS units)

# Hostile unit texts (issue 28): 20000 nested parentheses crashed the recursive parser (SIGSEGV).
string(REPEAT "(" 20000 sigmatau_deep_open)
string(REPEAT ")" 20000 sigmatau_deep_close)
sigmatau_cli_test(NAME cli_units_deep_nesting EXIT 2
  STDERR "more than 32 nested parentheses or roots .*at column 35 of"
  ARGS units "1 ${sigmatau_deep_open}s${sigmatau_deep_close}" --to s)
