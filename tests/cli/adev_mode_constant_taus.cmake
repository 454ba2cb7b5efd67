# CLI cases from review D: the mode is recorded (finding 6), a constant channel is said
# (finding 14), and an explicit --taus list is computed per statistic (finding 11).
set(mct_white ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv)  # 2000 rows, 10 Hz
set(mct_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_adev_mct)
file(MAKE_DIRECTORY ${mct_dir})

# Stream results are approximate at long taus: the table, the CSV and the JSON say so.
sigmatau_cli_test(NAME cli_adev_mode_stream_table EXIT 0
  STDOUT "^# [^\n]*\n# mode: stream \\(approximate: 8 start points per tau"
  ARGS adev ${mct_white} --time-column t --mode stream)
sigmatau_cli_test(NAME cli_adev_mode_stream_csv EXIT 0
  STDOUT "^# mode: stream \\(approximate: 4 start points per tau[^\n]*\nchannel,statistic,unit"
  ARGS adev ${mct_white} --time-column t --mode stream --density 4 --format csv)
sigmatau_cli_test(NAME cli_adev_mode_stream_json EXIT 0
  STDOUT "\"mode\": {\n  \"approximate\": true,\n  \"density\": 8,\n  \"name\": \"stream\""
  ARGS adev ${mct_white} --time-column t --mode stream --format json)
sigmatau_cli_test(NAME cli_adev_mode_exact_json EXIT 0
  STDOUT "\"mode\": {\n  \"name\": \"exact\""
  ARGS adev ${mct_white} --time-column t --format json)

# A constant channel (gc: 300 rows of 0.123456789) next to a varying one; stamps in ms, 10 Hz.
set(mct_const ${mct_dir}/constant_10Hz.csv)
set(rows "t,gc,gv\n")
foreach(i RANGE 299)
  math(EXPR v "(${i} * 7919) % 13")
  math(EXPR t_ms "${i} * 100")
  string(APPEND rows "${t_ms},0.123456789,${v}\n")
endforeach()
file(WRITE ${mct_const} "${rows}")
set(mct_const_re "channel gc is constant \\(every value is 0\\.123456789\\): a stuck sensor, or precision lost")
sigmatau_cli_test(NAME cli_adev_constant_warned EXIT 0 STDERR "${mct_const_re}"
  ARGS adev ${mct_const} --time-column t --time-unit ms)
sigmatau_cli_test(NAME cli_adev_constant_json EXIT 0
  STDOUT "\"warnings\": .\n  \"channel gc is constant"
  ARGS adev ${mct_const} --time-column t --time-unit ms --format json)
sigmatau_cli_test(NAME cli_adev_constant_stream EXIT 0
  STDERR "channel gc is constant \\(every deviation is 0\\)"
  ARGS adev ${mct_const} --time-column t --time-unit ms --mode stream)
sigmatau_cli_test(NAME cli_psd_constant_warned EXIT 0
  STDERR "${mct_const_re}.*its PSD and noise density are rounding residue"
  ARGS psd ${mct_const} --time-column t --time-unit ms --unit deg/s)
# The varying channel is not flagged.
sigmatau_cli_test(NAME cli_psd_constant_only_that_channel EXIT 0 STDERR "^[^\n]*gc[^\n]*\n$"
  ARGS psd ${mct_const} --time-column t --time-unit ms)

# 2000 rate samples = 2001 phase points: OADEV and MDEV stop at m = 500 (50 s), TOTDEV at
# m = 1000 (100 s). 80 s is computed for totdev and skipped, with a note, for the others.
sigmatau_cli_test(NAME cli_adev_taus_per_statistic EXIT 0
  STDOUT "gx,totdev,,8\\.000000e\\+01,800,"
  STDERR "oadev skips tau 80 s: its longest on this log is 50 s \\(m = 500\\).*mdev skips tau 80 s"
  ARGS adev ${mct_white} --time-column t --stat totdev,oadev,mdev --taus 10,80 --format csv)
# Out of core (the file over --memory) the length is known only after the first pass: the
# same per-statistic taus, chosen then (before, 80 s aborted the run for oadev).
sigmatau_cli_test(NAME cli_adev_taus_per_statistic_out_of_core EXIT 0
  STDOUT "gx,totdev,,8\\.000000e\\+01,800,"
  STDERR "computing exactly out of core.*oadev skips tau 80 s: its longest on this log is 50 s \\(m = 500\\).*mdev skips tau 80 s"
  ARGS adev ${mct_white} --time-column t --stat totdev,oadev,mdev --taus 10,80 --format csv
       --memory 1KB)
sigmatau_cli_test(NAME cli_adev_taus_none_reaches_out_of_core EXIT 2
  STDERR "tau 200 s is too long for"
  ARGS adev ${mct_white} --time-column t --stat totdev,oadev --taus 10,200 --memory 1KB)
# Times with a unit, as --duration takes them: 100 ms is m = 1, half a minute m = 300.
sigmatau_cli_test(NAME cli_adev_taus_with_units EXIT 0
  STDOUT "gx,oadev,,1\\.000000e-01,1,[^\n]*\ngx,oadev,,3\\.000000e\\+01,300,"
  ARGS adev ${mct_white} --time-column t --taus "100ms, 0.5min" --format csv)
sigmatau_cli_test(NAME cli_adev_taus_with_wrong_unit EXIT 2
  STDERR "bad tau specification \"1m\": \"1m\" is not a time"
  ARGS adev ${mct_white} --time-column t --taus 1m)
# A tau no statistic reaches is still an error.
sigmatau_cli_test(NAME cli_adev_taus_none_reaches EXIT 2
  STDERR "tau 200 s is too long for"
  ARGS adev ${mct_white} --time-column t --stat totdev,oadev --taus 10,200)
# Stream mode knows the length only at the end: the same note from the curves (ADEV stops at
# m = 400, 40 s; OADEV at 50 s), and a tau in no curve is an error instead of an empty table.
sigmatau_cli_test(NAME cli_adev_taus_per_statistic_stream EXIT 0
  STDOUT "gx,oadev,,4\\.500000e\\+01,450,"
  STDERR "adev skips tau 45 s: too long for it on this log"
  ARGS adev ${mct_white} --time-column t --columns gx --stat adev,oadev --taus 10,45 --mode stream
       --format csv)
sigmatau_cli_test(NAME cli_adev_taus_none_reaches_stream EXIT 2
  STDERR "tau 450 s is too long for oadev on this log \\(stream mode\\)"
  ARGS adev ${mct_white} --time-column t --columns gx --taus 450 --mode stream)
# --gaps split: the longest segment bounds the taus (1990 rows: OADEV to m = 497, TOTDEV to
# m = 995): the same per-statistic taus.
sigmatau_write_gapped_log(${mct_dir}/split.csv 3000 1000 1009)
sigmatau_cli_test(NAME cli_adev_taus_per_statistic_split EXIT 0
  STDOUT "gx,totdev,,6\\.000000e\\+01,600,"
  STDERR "oadev skips tau 60 s: its longest on this log is 49\\.7 s \\(m = 497\\)"
  ARGS adev ${mct_dir}/split.csv --time-column t --time-unit ms --gaps split
       --stat totdev,oadev --taus 10,60 --format csv)
