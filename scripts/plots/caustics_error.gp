# Caustics: the wavefront map's error on the ball lens against its vertex count and its time
# (`slime bench caustics --csv caustics.csv`; columns photons, ms, error, focus_error, cell_mm).
load "scripts/plots/_style.gp"
set output dir."/caustics_error.png"
set multiplot layout 1,2 title "Caustics: ball lens, wavefront map against one of 64x the vertices (lower is better)"
set logscale xy
set key inside top right box opaque
set format x "%.0s%c"
set ylabel "error (share of the reference's light)"
set xlabel "budget (vertices, at most)"
plot dir."/caustics.csv" using 1:3 skip 1 with linespoints pt 7 title "shadow outside the focus: sum|m-r| / sum r", \
     dir."/caustics.csv" using 1:4 skip 1 with linespoints pt 5 title "light within 2 mm of the focus"
set xlabel "time (ms, vertices traced and spread, all threads)"
plot dir."/caustics.csv" using 2:3 skip 1 with linespoints pt 7 title "shadow outside the focus", \
     dir."/caustics.csv" using 2:4 skip 1 with linespoints pt 5 title "within 2 mm of the focus"
unset multiplot
