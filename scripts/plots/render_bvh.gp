# BVH update per frame (refit vs rebuild at LOW/MEDIUM/HIGH) and the trace time after it on the round
# and on the stretched slime, levels 4 and 6.
load "scripts/plots/_style.gp"
if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
  set terminal pngcairo size 1300,640 enhanced font "DejaVu Sans,11" linewidth 1.5
}
set output dir."/render_bvh.png"
method(s) = s eq "high" ? 0 : s eq "medium" ? 1 : s eq "low" ? 2 : 3
set xtics ("rebuild\nHIGH" 0, "rebuild\nMEDIUM" 1, "rebuild\nLOW" 2, "refit" 3)
set xrange [-0.6:3.6]
set bmargin 4
set style fill solid 0.85 border -1
set multiplot layout 1,2 title "BVH refit vs rebuild on a slime stretched by the physics (all threads)"
set title "update cost per frame (lower is better)"
set ylabel "ms per frame (log scale)"
set logscale y
plot dir."/render_bvh.csv" using (method(strcol(3)) - 0.2):($1==4 ? $5 : 1/0):(0.38) with boxes lc rgb "#a6d854" title "level 4 (5,120 faces)", \
     ""                    using (method(strcol(3)) + 0.2):($1==6 ? $5 : 1/0):(0.38) with boxes lc rgb "#1b9e77" title "level 6 (81,920 faces)"
unset logscale y
set title "Embree time for the frame's slime queries after the update"
set ylabel "ms per frame"
set yrange [0:*]
plot dir."/render_bvh.csv" using (method(strcol(3)) - 0.3):($1==4 ? $7 : 1/0):(0.19) with boxes lc rgb "#d9f0a3" title "level 4, round", \
     ""                    using (method(strcol(3)) - 0.1):($1==4 ? $8 : 1/0):(0.19) with boxes lc rgb "#66a61e" title "level 4, stretched", \
     ""                    using (method(strcol(3)) + 0.1):($1==6 ? $7 : 1/0):(0.19) with boxes lc rgb "#b3e2cd" title "level 6, round", \
     ""                    using (method(strcol(3)) + 0.3):($1==6 ? $8 : 1/0):(0.19) with boxes lc rgb "#1b9e77" title "level 6, stretched"
unset multiplot
