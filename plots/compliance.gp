# sigmatau compliance chart: measured / data-sheet limit per parameter with its confidence
# interval, coloured by verdict (the key names the colours: pass green, marginal amber, fail red,
# inconclusive grey); the limit is the line at 1. A term the fit did not detect has no estimate,
# only a one-sided upper bound: it is drawn as an arrow pointing left from that bound ("at most
# here"), not as a point.
# Variables set by sigmatau (gnuplot -e): datafile, outfile, term, title_text, xlabel_text (the
# caption's middle line: what the bars and arrows are, with the confidence level),
# nrows, nundetected, xmin, xmax (the x range, which always holds the limit line at 1).
# datafile columns: row ratio ratio_low ratio_high color(0xRRGGBB) "label" detected(1|0)

if (term eq 'svg') {
  set terminal svg size 1100,(260 + 42 * nrows) dynamic enhanced font 'Helvetica,16' background rgb 'white'
} else {
  if (term eq 'pdfcairo') {
    set terminal pdfcairo size 10in,(2.9 + 0.42 * nrows)in enhanced font 'Helvetica,12'
  } else {
    set terminal pngcairo size 1540,(340 + 60 * nrows) enhanced font 'Helvetica,18'
  }
}
set encoding utf8
set output outfile
set title title_text noenhanced
set logscale x
set xrange [xmin:xmax]
# a short range holds no decade but 1: label the 2 and 5 steps too
set xtics add (0.02, 0.05, 0.2, 0.5, 2, 5, 20, 50)
set xlabel "measured / data-sheet limit\n".xlabel_text."\nlimits: (typ) a typical value, (max) a guaranteed maximum" noenhanced
set yrange [-0.7:nrows-0.3]
set ytics nomirror
set grid xtics lc rgb '#dddddd'
set key outside right top vertical Left reverse box noenhanced samplen 1
set arrow from 1, graph 0 to 1, graph 1 nohead lw 2 dt 2 lc rgb '#444444'
# The arrow of a bound: from the bound to 1/1.8 of it (a fixed length on the log axis).
shaft = 1.0 / 1.8
plot datafile using (1):1:ytic(6) with points ps 0 notitle, \
     datafile using ($7 == 1 ? $2 : NaN):1:3:4:5 with xerrorbars pt 7 ps 1.6 lw 3 lc rgb variable notitle, \
     datafile using ($7 == 0 ? $4 : NaN):1:($4 * (shaft - 1)):(0):5 with vectors head filled size screen 0.012,25 lw 3 lc rgb variable notitle, \
     datafile using ($7 == 0 ? $4 : NaN):1:4:4:5 with xerrorbars pt 0 lw 3 lc rgb variable notitle, \
     keyentry with points pt 7 ps 1.4 lc rgb '#2ca02c' title 'pass', \
     keyentry with points pt 7 ps 1.4 lc rgb '#e6a000' title 'marginal', \
     keyentry with points pt 7 ps 1.4 lc rgb '#d62728' title 'fail', \
     keyentry with points pt 7 ps 1.4 lc rgb '#7f7f7f' title 'inconclusive', \
     keyentry with points pt '<' ps 2 lc rgb '#444444' title (nundetected > 0 ? 'not detected (upper bound)' : '')
