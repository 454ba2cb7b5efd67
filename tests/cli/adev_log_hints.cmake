# CLI cases for reading logs (review D finding 13): --gaps report says what it found on stderr,
# --kind rate with an amount unit is refused, and a header split by ';' or a binary file read
# as text gets a hint. The inputs are written here, at configure time.
set(lh_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_log_hints)
file(MAKE_DIRECTORY ${lh_dir})

# 10 Hz stamps in ms, rows 100..102 missing: one gap of 0.4 s before the row stamped 10300 ms.
sigmatau_write_gapped_log(${lh_dir}/gap.csv 300 100 102)
# Line 1 is the header, so the row after the gap (i = 103, the 101st data row) is on line 102.
sigmatau_cli_test(NAME cli_log_gaps_report_summary EXIT 0
  STDERR "--gaps report: 1 time stamp gap \\(> 1\\.5 intervals\\), the largest 0\\.4 s before line 102; analysed as if contiguous"
  ARGS adev ${lh_dir}/gap.csv --time-column t --time-unit ms --gaps report --taus 1)
sigmatau_cli_test(NAME cli_log_gaps_report_psd EXIT 0 STDERR "--gaps report: 1 time stamp gap"
  ARGS psd ${lh_dir}/gap.csv --time-column t --time-unit ms --gaps report)

# An angle is no rate (the reverse, --kind increment --unit rad/s, was refused already).
sigmatau_cli_test(NAME cli_log_kind_rate_with_angle EXIT 2
  STDERR "--unit rad is an angle \\(neither an angular rate nor an acceleration\\), but --kind rate says the values are rates"
  ARGS adev ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv --time-column t --unit rad)
sigmatau_cli_test(NAME cli_log_kind_rate_with_velocity EXIT 2
  STDERR "--unit m/s is a velocity \\(.*\\), but --kind rate"
  ARGS psd ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv --time-column t --unit m/s)

# A European CSV: fields separated by ';'.
file(WRITE ${lh_dir}/semicolon.csv "t;gx\n0.00;1.23\n0.01;1.25\n0.02;1.21\n")
sigmatau_cli_test(NAME cli_log_semicolon_time_column EXIT 2
  STDERR "unknown time column \"t\" \\(available: t;gx\\); the header holds ';'"
  ARGS adev ${lh_dir}/semicolon.csv --time-column t)
sigmatau_cli_test(NAME cli_log_semicolon_no_numeric EXIT 2
  STDERR "no numeric columns.*the header holds ';'"
  ARGS adev ${lh_dir}/semicolon.csv --rate 100)
# ';' in the data rows only: under a comma header, in a field that is no number, and in a
# line with more fields than the header.
file(WRITE ${lh_dir}/semicolon_rows.csv "t,gx\n0.00;1.23\n0.01;1.25\n")
sigmatau_cli_test(NAME cli_log_semicolon_rows EXIT 2
  STDERR "semicolon_rows.csv:2: the first data row holds no number; it holds ';'"
  ARGS adev ${lh_dir}/semicolon_rows.csv --rate 100)
file(WRITE ${lh_dir}/semicolon_field.csv "gx\n1.23\n1;25\n")
sigmatau_cli_test(NAME cli_log_semicolon_field EXIT 2
  STDERR "semicolon_field.csv:3:1: expected a number, found \"1;25\"; the field holds ';'"
  ARGS adev ${lh_dir}/semicolon_field.csv --rate 100)
file(WRITE ${lh_dir}/semicolon_ragged.csv "0;0,1;0,2\n0,01;0,3;0,1\n")
sigmatau_cli_test(NAME cli_log_semicolon_ragged EXIT 2
  STDERR "semicolon_ragged.csv:2:4: expected 3 fields, found 4; the line holds ';'"
  ARGS adev ${lh_dir}/semicolon_ragged.csv --rate 100)

# Bytes 1, 2, 3 in the first line (no NUL, which the text reader names itself).
string(ASCII 1 2 3 lh_control)
file(WRITE ${lh_dir}/binary.dat "${lh_control}abc,x\nabc,def\n")
sigmatau_cli_test(NAME cli_log_binary_as_text EXIT 2
  STDERR "no numeric columns.*the file looks binary.*--binary i16\\|i32\\|f32\\|f64"
  ARGS adev ${lh_dir}/binary.dat --rate 100)
