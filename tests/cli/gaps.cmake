# Time-stamp gaps through the CLI: `error` is the default and says where and what to use; `split`
# pools the contiguous segments (allan_segments.hpp); `report` stays available on request.
set(gap_small ${PROJECT_SOURCE_DIR}/tests/data/logs/gap.csv)  # 40 ms gap at line 10, duplicate at 12

# A log with one gap, written at configure time (small, deterministic, not committed): 1000
# samples every 10 ms, a 5 s hole (a logger restart), 600 more samples with the bias moved by
# 10000 (units arbitrary). Values are integers from a fixed pattern so the file is the same everywhere.
set(gap_log ${CMAKE_CURRENT_BINARY_DIR}/cli_gaps/restart.csv)
if(NOT EXISTS ${gap_log})
  set(rows "t_ms,gx\n")
  foreach(i RANGE 0 1599)
    math(EXPR v "(${i} * 7919) % 101 - 50")
    if(i LESS 1000)
      math(EXPR t "${i} * 10")
    else()
      math(EXPR t "${i} * 10 + 5000")
      math(EXPR v "${v} + 10000")
    endif()
    string(APPEND rows "${t},${v}\n")
  endforeach()
  file(WRITE ${gap_log} "${rows}")
endif()

# The default is error: where (file:line), what (length, count) and which options to use.
sigmatau_cli_test(NAME cli_gaps_default_is_error EXIT 2
  STDERR "gap.csv:10: .*time stamp gap of 40 ms.*--gaps split.*--gaps fill.*--gaps report"
  ARGS adev ${gap_small} --time-column t_ms --time-unit ms)
# Stamps jittered +-4 ms around 100 Hz (receive times; no sample is missing): as many intervals
# under half the nominal one as "gaps" over 1.5 of it, so the error says jitter, points to
# --gaps report and --rate, and warns that fill would invent samples (review D, finding 12).
# Lost samples (gap.csv, restart.csv) make no short intervals and keep the split/fill advice.
sigmatau_cli_test(NAME cli_gaps_jitter_is_not_loss EXIT 2
  STDERR "jittered_stamps_100Hz.csv:15: time stamp gap .*42 gaps in all.*25 intervals are also under half the nominal one, so these look like jittered time stamps .*--gaps report .*--rate .*mean interval says 99\\.9169 Hz.*--gaps fill would invent samples"
  ARGS adev ${PROJECT_SOURCE_DIR}/tests/data/cli/jittered_stamps_100Hz.csv --time-column t)
sigmatau_cli_test(NAME cli_gaps_default_error_restart EXIT 2
  STDERR "restart.csv:1002: .*time stamp gap of 5\\.01 s.*before data row 1000"
  ARGS adev ${gap_log} --time-column t_ms --time-unit ms)
# A duplicated stamp is an error by default too (gap.csv's first problem is its gap, so a log
# whose only problem is the duplicate: the catalogue's duplicate_time_fill.csv).
sigmatau_cli_test(NAME cli_gaps_default_error_duplicate EXIT 2
  STDERR "duplicated time stamp.*--gaps split.*--gaps report"
  ARGS adev ${PROJECT_SOURCE_DIR}/tests/data/bad/duplicate_time_fill.csv --time-column t)

# report, asked for explicitly, analyses the rows as if contiguous: 1599 OADEV terms at m = 1.
sigmatau_cli_test(NAME cli_gaps_report_on_request EXIT 0 STDOUT " 0\\.01 +1 +1599 "
  ARGS adev ${gap_log} --time-column t_ms --time-unit ms --gaps report)

# split: two segments (1000 and 600 samples) pooled: 999 + 599 = 1598 terms at m = 1. The
# pattern steps by +41 or -60 (7919 = 41 mod 101), so OADEV(m = 1) is about
# sqrt((41^2 60 + 60^2 41) / 101 / 2) = 35; the one cross-gap step of 10000 would add
# 10000^2 / 2 / 1599 to the variance (a deviation of ~180), which report shows and split must not.
sigmatau_cli_test(NAME cli_gaps_split_adev EXIT 0
  STDOUT "2 contiguous segments pooled.* 0\\.01 +1 +1598 +[-0-9]+ +[0-9.e+]+ +[0-9.e+]+ +3\\.[45][0-9]*e\\+01 "
  ARGS adev ${gap_log} --time-column t_ms --time-unit ms --gaps split)
sigmatau_cli_test(NAME cli_gaps_report_spans_the_gap EXIT 0
  STDOUT " 0\\.01 +1 +1599 +[-0-9]+ +[0-9.e+]+ +[0-9.e+]+ +1\\.[6-9][0-9]*e\\+02 "
  ARGS adev ${gap_log} --time-column t_ms --time-unit ms --gaps report)
sigmatau_cli_test(NAME cli_gaps_split_json EXIT 0
  STDOUT "\"segment_starts\": \\[[^0-9]*0,[^0-9]*1000[^0-9]*\\]"
  ARGS adev ${gap_log} --time-column t_ms --time-unit ms --gaps split --format json)
# psd with split: Welch windows stay inside a segment. 128-sample windows at 50 % overlap fit
# (1000 - 128) / 64 + 1 = 14 times in the first segment and (600 - 128) / 64 + 1 = 8 in the
# second: 22 windows, where the contiguous 1600 samples (report) hold 24, two across the gap.
sigmatau_cli_test(NAME cli_gaps_split_psd EXIT 0 STDOUT "\"segments\": 22,"
  ARGS psd ${gap_log} --time-column t_ms --time-unit ms --gaps split --segment 128 --format json)
sigmatau_cli_test(NAME cli_gaps_report_psd_spans_the_gap EXIT 0 STDOUT "\"segments\": 24,"
  ARGS psd ${gap_log} --time-column t_ms --time-unit ms --gaps report --segment 128 --format json)
sigmatau_cli_test(NAME cli_gaps_split_needs_exact EXIT 2 STDERR "--gaps split needs --mode exact"
  ARGS adev ${gap_log} --time-column t_ms --time-unit ms --gaps split --mode stream)

# analyze with split: the segments are listed in results.json and the curve pools them.
set(gap_analyze ${CMAKE_CURRENT_BINARY_DIR}/cli_gaps/analyze)
sigmatau_cli_test(NAME cli_gaps_split_analyze EXIT 0
  ARGS analyze ${gap_log} --time-column t_ms --time-unit ms --gaps split --trim none
       -o ${gap_analyze} --force)
# results.json must list both segments: a small cmake -P check written next to the outputs.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/cli_gaps/expect_match.cmake [=[
file(READ "${FILE}" text)
if(NOT text MATCHES "${PATTERN}")
  message(FATAL_ERROR "${FILE} does not match ${PATTERN}")
endif()
]=])
add_test(NAME cli_gaps_split_analyze_results
         COMMAND ${CMAKE_COMMAND} -DFILE=${gap_analyze}/results.json
                 "-DPATTERN=\"segments\": \\[[^a-z]*\"duration_s\": 10\\.0,[^a-z]*\"first_sample\": 0,[^a-z]*\"samples\": 1000[^a-z]*\"duration_s\": 6\\.0,[^a-z]*\"first_sample\": 1000,[^a-z]*\"samples\": 600[^a-z]*\\]"
                 -P ${CMAKE_CURRENT_BINARY_DIR}/cli_gaps/expect_match.cmake)
set_tests_properties(cli_gaps_split_analyze_results PROPERTIES DEPENDS cli_gaps_split_analyze)

# fill: the 5.01 s hole at 10 ms holds 500 missing samples, interpolated: 1000 + 500 + 600 rows.
sigmatau_cli_test(NAME cli_gaps_fill_adev EXIT 0 STDOUT "restart\\.csv: 2100 samples at 100 Hz"
  ARGS adev ${gap_log} --time-column t_ms --time-unit ms --gaps fill)
