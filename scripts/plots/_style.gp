# Shared look of the charts (loaded by each chart script; not a chart itself).
if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
  set terminal pngcairo size 1150,620 enhanced font "DejaVu Sans,11" linewidth 1.5
} else {
  set terminal png size 1150,620
}
set datafile separator ","
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key outside right top box opaque spacing 1.3
# The data rows of a CSV whose column `column` equals `value` (a gnuplot filter that keeps lines
# unbroken, unlike plotting 1/0 for the rows left out).
rows(file, column, value) = sprintf("< awk -F, 'NR > 1 && $%d == \"%s\"' %s", column, value, file)
