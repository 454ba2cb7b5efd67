# sigmatau compliance chart: measured / data-sheet limit per parameter with its confidence
# interval, coloured by verdict (pass green, marginal amber, fail red, inconclusive grey); the
# limit is the line at 1. A term the fit did not detect is one point at upper bound / limit
# (its label says so).
# Variables set by sigmatau (gnuplot -e): datafile, outfile, term, title_text, nrows, xmin, xmax
# (the x range, which always holds the limit line at 1).
# datafile columns: row ratio ratio_low ratio_high color(0xRRGGBB) "label"

if (term eq 'svg') {
  set terminal svg size 1000,(200 + 42 * nrows) dynamic enhanced font 'Helvetica,16' background rgb 'white'
} else {
  if (term eq 'pdfcairo') {
    set terminal pdfcairo size 10in,(2 + 0.42 * nrows)in enhanced font 'Helvetica,12'
  } else {
    set terminal pngcairo size 1400,(280 + 60 * nrows) enhanced font 'Helvetica,18'
  }
}
set output outfile
set title title_text noenhanced
set logscale x
set xrange [xmin:xmax]
# a short range holds no decade but 1: label the 2 and 5 steps too
set xtics add (0.02, 0.05, 0.2, 0.5, 2, 5, 20, 50)
set xlabel "measured / data-sheet limit\n(bar: confidence interval; a term not detected: its upper bound)" noenhanced
set yrange [-0.7:nrows-0.3]
set ytics nomirror
set grid xtics lc rgb '#dddddd'
set key off
set arrow from 1, graph 0 to 1, graph 1 nohead lw 2 dt 2 lc rgb '#444444'
plot datafile using 2:1:3:4:5:ytic(6) with xerrorbars pt 7 ps 1.6 lw 3 lc rgb variable
