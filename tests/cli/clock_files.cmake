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
sigmatau_cli_test(NAME cli_clock_phase_beyond EXIT 2
  STDERR "tau 251 s is too long for oadev on this log: the longest is 250 s \\(m = 250 of 1000 phase points\\)"
  ARGS adev ${clock_data}/clock_phase_1000.txt --kind phase --rate 1 --taus 251 --stat oadev)
