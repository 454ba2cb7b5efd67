# sigmatau compliance chart: measured / data-sheet limit per parameter with its confidence
# interval, coloured by verdict (the key names the colours: pass green, marginal amber, fail red,
# inconclusive grey); the limit is the line at 1. A term the fit did not detect has no estimate,
# only a one-sided upper bound: it is drawn as an arrow pointing left from that bound ("at most
# here"), not as a point.
# Variables set by sigmatau (gnuplot -e): datafile, outfile, term, title_text, ncaption and
# caption1..caption3 (the caption's lines, at most 60 characters each: what the bars and arrows
# are, with the confidence level), nrows, nundetected, xmin, xmax (the x range, which always
# holds the limit line at 1), label_chars (the longest row label, in characters), label_steps
# (1: label the 2 and 5 steps of the x axis too).
# datafile columns: row ratio ratio_low ratio_high color(0xRRGGBB) "label" detected(1|0)

# The layout follows the labels: the row labels take label_chars characters at about char_w
# each, and the plot area gets at least plot_w whatever their length (on the ADIS16405 log
# against the ADIS16448 sheet, labels of 57 characters beside a key on the right left the plot
# a strip of 60 px, its x labels on each other and the caption cut off). The canvas widens
# beyond its usual width when the labels need it; the key sits above the plot, not beside it.
# char_w errs wide: a browser draws these labels at about 0.51 em a character, cairo (png, pdf)
# at about 0.65 em; 0.6 and 0.7 em are assumed. char_h is a line's height.
if (term eq 'svg') {
  char_w = 0.6 * 16; char_h = 1.25 * 16; plot_w = 62 * char_w; width = 1100
  height = 300 + 42 * nrows
} else {
  if (term eq 'pdfcairo') {
    char_w = 0.7 * 12 / 72.0; char_h = 1.25 * 12 / 72.0; plot_w = 62 * char_w; width = 10
    height = 3.3 + 0.42 * nrows
  } else {
    char_w = 0.7 * 18; char_h = 1.25 * 18; plot_w = 62 * char_w; width = 1540
    height = 400 + 60 * nrows
  }
}
# label area + tick marks and gaps (4 characters) + plot area + right margin (4 characters)
needed = (label_chars + 8) * char_w + plot_w
width = (needed > width ? needed : width)
if (term eq 'svg') {
  set terminal svg size width,height dynamic enhanced font 'Helvetica,16' background rgb 'white'
} else {
  if (term eq 'pdfcairo') {
    set terminal pdfcairo size (width)in,(height)in enhanced font 'Helvetica,12'
  } else {
    set terminal pngcairo size width,height enhanced font 'Helvetica,18'
  }
}
set encoding utf8
set output outfile
set logscale x
set xrange [xmin:xmax]
# a short range holds no decade but 1: label the 2 and 5 steps too (not on a long one, where
# they would crowd)
if (label_steps) { set xtics add (0.02, 0.05, 0.2, 0.5, 2, 5, 20, 50) }
caption = caption1.(ncaption > 1 ? "\n".caption2 : "").(ncaption > 2 ? "\n".caption3 : "")
set xlabel "measured / data-sheet limit\n".caption."\nlimits: (typ) a typical value, (max) a guaranteed maximum" noenhanced
set yrange [-0.7:nrows-0.3]
set ytics nomirror
# The margins from the same estimate, so the plot area is plot_w wide whatever gnuplot thinks the
# labels measure.
set lmargin at screen (label_chars + 4) * char_w / width
set rmargin at screen 1 - 4 * char_w / width
set grid xtics lc rgb '#dddddd'
# The title, then the key in one row under it, both centred on the canvas above the plot. The
# key is drawn as labels: gnuplot's own key takes no more columns than fit the plot area, and
# fell back to one column lying over the plot.
set tmargin 3.8
set label 1 title_text at screen 0.5, screen 1 - 0.9 * char_h / height center noenhanced
key_y = 1 - 2.1 * char_h / height
# an entry's width: its symbol and the gaps (5 characters) and its text
entry(n) = (n + 5) * char_w / width
key_w = entry(4) + entry(8) + entry(4) + entry(12) + (nundetected > 0 ? entry(26) : 0)
key_x = 0.5 - key_w / 2 + char_w / width
set label 11 'pass' at screen key_x, screen key_y left noenhanced point pt 7 ps 1.4 lc rgb '#2ca02c' offset 1.5,-0.25
key_x = key_x + entry(4)
set label 12 'marginal' at screen key_x, screen key_y left noenhanced point pt 7 ps 1.4 lc rgb '#e6a000' offset 1.5,-0.25
key_x = key_x + entry(8)
set label 13 'fail' at screen key_x, screen key_y left noenhanced point pt 7 ps 1.4 lc rgb '#d62728' offset 1.5,-0.25
key_x = key_x + entry(4)
set label 14 'inconclusive' at screen key_x, screen key_y left noenhanced point pt 7 ps 1.4 lc rgb '#7f7f7f' offset 1.5,-0.25
key_x = key_x + entry(12)
if (nundetected > 0) {
  # the symbol of a bound: a short arrow pointing left, as in the chart
  set arrow 15 from screen key_x + 0.6 * char_w / width, screen key_y \
      to screen key_x - 1.0 * char_w / width, screen key_y head filled size screen 0.01,25 lw 3 lc rgb '#444444'
  set label 15 'not detected (upper bound)' at screen key_x, screen key_y left noenhanced offset 1.5,0
}
unset key
set arrow from 1, graph 0 to 1, graph 1 nohead lw 2 dt 2 lc rgb '#444444'
# The arrow of a bound: from the bound to 1/1.8 of it (a fixed length on the log axis).
shaft = 1.0 / 1.8
plot datafile using (1):1:ytic(6) with points ps 0 notitle, \
     datafile using ($7 == 1 ? $2 : NaN):1:3:4:5 with xerrorbars pt 7 ps 1.6 lw 3 lc rgb variable notitle, \
     datafile using ($7 == 0 ? $4 : NaN):1:($4 * (shaft - 1)):(0):5 with vectors head filled size screen 0.012,25 lw 3 lc rgb variable notitle, \
     datafile using ($7 == 0 ? $4 : NaN):1:4:4:5 with xerrorbars pt 0 lw 3 lc rgb variable notitle
