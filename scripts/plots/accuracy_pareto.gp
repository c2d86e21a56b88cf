# Render accuracy against cost: the share of pixels visibly different (> 2 steps of 8-bit sRGB) from
# the analytic sphere at depth 6, against ms/frame, for levels 0-6 (points along each line) per depth.
load "scripts/plots/_style.gp"
set output dir."/accuracy_pareto.png"
set title "Render: image error vs frame time (mesh vs analytic sphere; lower left is better)"
set xlabel "time per frame (ms, all threads)"
set ylabel "pixels off by more than 2 sRGB steps (%)"
set logscale y
set yrange [0.01:100]
set arrow from graph 0, first 1 to graph 1, first 1 nohead dt 2 lw 2 lc rgb "#cc0000"
set label "visibility threshold 1 %" at graph 0.02, first 1.3 tc rgb "#cc0000"
smooth(d) = sprintf("< awk -F, 'NR > 1 && $3 == \"smooth\" && $4 == %d' %s", d, dir."/accuracy.csv")
plot for [d=1:6] smooth(d) using 5:($9*100) with linespoints pt 7 title sprintf("smooth normals, depth %d", d), \
     rows(dir."/accuracy.csv", 3, "flat") using 5:($9*100) with points pt 1 lc rgb "#aaaaaa" title "flat normals (all depths)"
