# sigmatau ADEV plot: one curve per channel with its confidence band, log-log.
# Variables set by sigmatau (gnuplot -e): datafile, outfile, term ('svg'|'pngcairo'|'pdfcairo'),
# title_text, ylabel_text, nchannels, names (space-separated channel names).
# Data file: one block per channel (separated by two blank lines): tau dev ci_low ci_high.
# Edit freely: sigmatau only sets the variables above.

if (term eq 'svg') {
  set terminal svg size 1000,700 dynamic enhanced font 'Helvetica,18' background rgb 'white'
} else {
  if (term eq 'pdfcairo') {
    set terminal pdfcairo size 10in,7in enhanced font 'Helvetica,14'
  } else {
    set terminal pngcairo size 1400,980 enhanced font 'Helvetica,20'
  }
}
set output outfile
set title title_text
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'averaging time {/Symbol t} [s]'
set ylabel ylabel_text
set grid xtics ytics mxtics mytics lc rgb '#dddddd' lw 1
set key top right box opaque
set style fill transparent solid 0.18 noborder
colors = '#1f77b4 #d62728 #2ca02c #ff7f0e #9467bd #8c564b'
plot for [i=0:nchannels-1] datafile index i using 1:3:4 with filledcurves \
       lc rgb word(colors, i % 6 + 1) notitle, \
     for [i=0:nchannels-1] datafile index i using 1:2 with linespoints \
       lw 2.5 pt 7 ps 0.8 lc rgb word(colors, i % 6 + 1) title word(names, i + 1)
