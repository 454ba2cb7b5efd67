# sigmatau ADEV plot: one curve per channel with its confidence band, log-log, plus dashed
# lines (fitted model and terms, data-sheet lines) and read-off markers.
# Variables set by sigmatau (gnuplot -e): datafile, linefile, markerfile, outfile,
# term ('svg'|'pngcairo'|'pdfcairo'), title_text, ylabel_text, nchannels, colors, nlines,
# linecolors, nmarkers, markercolors (colour lists: space-separated '#rrggbb' words), and
# optionally ymin, ymax.
# Files: one block per curve / line / marker set, blocks separated by two blank lines; the first
# line of a block is its quoted key title ("" for none). datafile columns: tau dev ci_low
# ci_high; linefile and markerfile columns: tau value.
# Edit freely: sigmatau only sets the variables above.

set encoding utf8  # the axis label's tau: Symbol-font letters show as Latin in browsers
if (term eq 'svg') {
  set terminal svg size 1100,700 dynamic enhanced font 'Helvetica,18' background rgb 'white'
} else {
  if (term eq 'pdfcairo') {
    set terminal pdfcairo size 11in,7in enhanced font 'Helvetica,14'
  } else {
    set terminal pngcairo size 1540,980 enhanced font 'Helvetica,20'
  }
}
set output outfile
set title title_text noenhanced
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'averaging time τ [s]'
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
set style fill transparent solid 0.18 noborder
plot for [i=0:nchannels-1] datafile index i using 1:3:4 with filledcurves \
       lc rgb word(colors, i + 1) notitle, \
     for [i=0:nchannels-1] datafile index i using 1:2 with linespoints \
       lw 2.5 pt 7 ps 0.7 lc rgb word(colors, i + 1) title columnheader(1), \
     for [i=0:nlines-1] linefile index i using 1:2 with lines dt 2 lw 2 \
       lc rgb word(linecolors, i + 1) title columnheader(1), \
     for [i=0:nmarkers-1] markerfile index i using 1:2 with points pt 6 ps 2.2 lw 2 \
       lc rgb word(markercolors, i + 1) title columnheader(1)
