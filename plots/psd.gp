# sigmatau PSD plot: one-sided PSD per channel (log-binned), with the noise-density level.
# Variables set by sigmatau (gnuplot -e): datafile, outfile, term, title_text, ylabel_text,
# nchannels, names, levels (space-separated one-sided PSD levels of the noise density, or '').
# Data file: one block per channel (two blank lines between): frequency psd.

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
set xlabel 'frequency [Hz]'
set ylabel ylabel_text
set grid xtics ytics mxtics mytics lc rgb '#dddddd' lw 1
set key bottom left box opaque
colors = '#1f77b4 #d62728 #2ca02c #ff7f0e #9467bd #8c564b'
plot for [i=0:nchannels-1] datafile index i using 1:2 with lines lw 2 \
       lc rgb word(colors, i % 6 + 1) title word(names, i + 1), \
     for [i=0:(levels eq '' ? -1 : nchannels-1)] real(word(levels, i + 1)) with lines dt 2 lw 2 \
       lc rgb word(colors, i % 6 + 1) title sprintf('%s noise density', word(names, i + 1))
