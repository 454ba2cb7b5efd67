# sigmatau PSD plot: one-sided PSD per channel (log-binned), with dashed levels (measured noise
# density, data-sheet noise density) as horizontal lines.
# Variables set by sigmatau (gnuplot -e): datafile, linefile, outfile, term, title_text,
# ylabel_text, nchannels, colors, nlines, linecolors, and optionally ymin, ymax.
# Files: blocks separated by two blank lines, first line the quoted key title;
# datafile columns: frequency psd; linefile columns: frequency level.

if (term eq 'svg') {
  set terminal svg size 1100,700 dynamic enhanced font 'Helvetica,18' background rgb 'white'
} else {
  if (term eq 'pdfcairo') {
    set terminal pdfcairo size 11in,7in enhanced font 'Helvetica,14'
  } else {
    set terminal pngcairo size 1540,980 enhanced font 'Helvetica,20'
  }
}
set encoding utf8  # the 2×10^k labels of a single-decade y axis
set output outfile
set title title_text noenhanced
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'frequency [Hz]'
set ylabel ylabel_text noenhanced
# ymin, ymax (optional): whole decades around every point, so at least two ticks are labelled;
# a single decade also gets labels at its 2 and 5 steps, so that a value can be read off
if (exists('ymin')) {
  set yrange [ymin:ymax]
  if (ymax / ymin < 10.5) {
    y_exponent = floor(log10(ymin) + 0.5)
    set ytics add (sprintf('2×10^{%d}', y_exponent) 2 * ymin, sprintf('5×10^{%d}', y_exponent) 5 * ymin)
  }
}
set grid xtics ytics mxtics mytics lc rgb '#dddddd' lw 1
set key outside right top box opaque samplen 2 font ',13' noenhanced
plot for [i=0:nchannels-1] datafile index i using 1:2 with lines lw 2 \
       lc rgb word(colors, i + 1) title columnheader(1), \
     for [i=0:nlines-1] linefile index i using 1:2 with lines dt 2 lw 2 \
       lc rgb word(linecolors, i + 1) title columnheader(1)
