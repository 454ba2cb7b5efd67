# Extreme values and corrupt inputs (issue 28): each is refused with a clear message, or warned
# about, instead of a crash, an overflow or a silent empty result.
set(extreme_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_extreme)
file(REMOVE_RECURSE ${extreme_dir})
file(MAKE_DIRECTORY ${extreme_dir})
set(extreme_white ${CMAKE_CURRENT_SOURCE_DIR}/data/cli/white_2ch_10Hz.csv)

# Dynamic Allan windows too short to form: 1500 windows over 2000 samples are 2 samples each;
# windows of 16 samples fit 2 x 2000 / 16 - 1 = 249 times. Before: empty windows, no word.
sigmatau_cli_test(NAME cli_extreme_dynamic_windows_too_many EXIT 0
  STDERR "warning: dynamic Allan deviation: none of the 1500 windows asked was formed: over 2000 samples each would hold 2 samples, fewer than the 16 an OADEV curve needs; at most 249 windows fit"
  ARGS analyze ${extreme_white} --time-column t --gyro-unit deg/s --dynamic
       --dynamic-windows 1500 -o ${extreme_dir}/dynamic --force)
