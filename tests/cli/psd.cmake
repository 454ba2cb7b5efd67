# CLI regression cases for `sigmatau psd`.
set(example ${PROJECT_SOURCE_DIR}/examples/gyro_static_100Hz.csv.gz)
set(white ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv)

# The example log's white noise is N = 0.3 deg/sqrt(h) = 0.005 deg/s/sqrt(Hz) on every axis
# (examples/make_gyro_static.py); the table prints it to 5 digits with its interval.
sigmatau_cli_test(NAME cli_psd_table EXIT 0
  STDOUT "gx +N = 0\\.00(4[89]|5[01])[0-9]* \\[.*\\] deg/s/sqrt\\(Hz\\)"
  ARGS psd ${example} --time-column t --unit deg/s)
sigmatau_cli_test(NAME cli_psd_out_unit EXIT 0
  STDOUT "gy +N = 0\\.(29|30|31)[0-9]* \\[.*\\] deg/sqrt\\(h\\)"
  ARGS psd ${example} --time-column t --unit deg/s --out-unit "deg/sqrt(h)")
sigmatau_cli_test(NAME cli_psd_json EXIT 0
  STDOUT "\"convention\": \"one-sided\".*\"one_sided_asd\""
  ARGS psd ${white} --time-column t --format json --bins-per-decade 5)
sigmatau_cli_test(NAME cli_psd_bad_band EXIT 2 STDERR "--band expects F1:F2"
  ARGS psd ${white} --time-column t --band 1-2)
sigmatau_cli_test(NAME cli_psd_band_above_nyquist EXIT 2 STDERR "Nyquist"
  ARGS psd ${white} --time-column t --band 1:20)
sigmatau_cli_test(NAME cli_psd_segment_too_long EXIT 2 STDERR "shorter than one segment"
  ARGS psd ${white} --time-column t --segment 100000)
sigmatau_cli_test(NAME cli_psd_bad_window EXIT 2 STDERR "unknown window"
  ARGS psd ${white} --time-column t --window hamming)
sigmatau_cli_test(NAME cli_psd_density_dimension EXIT 2 STDERR "noise density"
  ARGS psd ${example} --time-column t --unit deg/s --out-unit deg/h)
