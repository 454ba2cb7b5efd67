# CLI regression cases for clock records as Stable32 users have them (issue 28): phase records,
# Stable32's stop ratios, Stable32 data files, time stamps in days.
set(clock_data ${PROJECT_SOURCE_DIR}/tests/data/cli)

# N = 1000 phase points: Stable32 (and allantools) stop OADEV at m = N/4 = 250 (N - 2m = 500
# terms) and TOTDEV at N/2 = 500; counting N - 1 samples refused both taus.
sigmatau_cli_test(NAME cli_clock_phase_oadev_last_octave EXIT 0
  STDOUT "\n +250 +250 +500 "
  ARGS adev ${clock_data}/clock_phase_1000.txt --kind phase --rate 1 --taus 250 --stat oadev)
sigmatau_cli_test(NAME cli_clock_phase_totdev_half EXIT 0
  STDOUT "\n +500 +500 +998 "
  ARGS adev ${clock_data}/clock_phase_1000.txt --kind phase --rate 1 --taus 500 --stat totdev)
# The same limit out of core (--memory 1K) and in stream mode (its strided terms).
sigmatau_cli_test(NAME cli_clock_phase_oadev_last_octave_out_of_core EXIT 0
  STDOUT "\n +250 +250 +500 "
  ARGS adev ${clock_data}/clock_phase_1000.txt --kind phase --rate 1 --taus 250 --stat oadev
       --memory 1K)
sigmatau_cli_test(NAME cli_clock_phase_oadev_last_octave_stream EXIT 0
  STDOUT "\n +250 +250 +[0-9]+ "
  ARGS adev ${clock_data}/clock_phase_1000.txt --kind phase --rate 1 --taus 250 --stat oadev
       --mode stream)
sigmatau_cli_test(NAME cli_clock_phase_beyond EXIT 2
  STDERR "tau 251 s is too long for oadev on this log: the longest is 250 s \\(m = 250 of 1000 phase points\\)"
  ARGS adev ${clock_data}/clock_phase_1000.txt --kind phase --rate 1 --taus 251 --stat oadev)

# Stable32 data files read as they are: a preamble of Key: value lines (Stable32's ACF output:
# it used to be ":2:3: expected 2 fields, found 3"), and a data file's Type and Tau.
set(clock_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_clock)
file(MAKE_DIRECTORY ${clock_dir})
file(WRITE ${clock_dir}/auto.dat "File: AUTO.DAT\nDate: 01/01/21 15:34:21\nPoints: 4\n0 1.0\n1 0.7\n2 0.5\n3 0.3\n")
sigmatau_cli_test(NAME cli_clock_preamble EXIT 0 STDOUT "4 samples at 1 Hz"
  ARGS adev ${clock_dir}/auto.dat --rate 1 --columns 1 --taus 1)
# A Stable32 phase file: its Type and Tau give --kind phase and --rate 1, said on stderr; the
# OADEV at 1 s of PHASE.DAT's first 1001 points is the published 0.29223 (Stable32, allantools).
file(READ ${clock_data}/clock_phase_1000.txt clock_values)
file(WRITE ${clock_dir}/stable32.dat "#Type: Phase\n#Points: 1000\n#Tau: 1.000000e+00\n# Header End\n${clock_values}")
sigmatau_cli_test(NAME cli_clock_stable32_header EXIT 0
  STDOUT "1000 samples at 1 Hz, kind phase.*\n +250 +250 +500 "
  STDERR "its header declares phase data \\(Type:\\): read as --kind phase.*Tau 1 s: read at --rate 1 Hz"
  ARGS adev ${clock_dir}/stable32.dat --taus 250)
sigmatau_cli_test(NAME cli_clock_stable32_kind_contradicted EXIT 0
  STDERR "warning: .*its header declares phase data \\(Type:\\), but --kind rate is given"
  ARGS adev ${clock_dir}/stable32.dat --kind rate --taus 1)
# Time stamps in days (an MJD column) and hours.
file(WRITE ${clock_dir}/mjd.csv "mjd,y\n60000.00,1e-12\n60000.25,3e-12\n60000.50,2e-12\n60000.75,4e-12\n60001.00,1e-12\n60001.25,2e-12\n")
sigmatau_cli_test(NAME cli_clock_time_unit_days EXIT 0 STDOUT "6 samples at 4\\.62963e-05 Hz"
  ARGS adev ${clock_dir}/mjd.csv --time-column mjd --time-unit d --taus 21600)
sigmatau_cli_test(NAME cli_clock_time_unit_hours EXIT 0 STDOUT "6 samples at 0\\.00111111 Hz"
  ARGS adev ${clock_dir}/mjd.csv --time-column mjd --time-unit h --taus 900)
