# Frame time against image size (issue 15): the still, moving-camera and deforming frames of the
# default slime (level 4, depth 3, 2 threads) beside the Embree-only replay of the deforming frame's
# own queries, measured in the same run (`slime bench render ... --headline-sizes`, render_sizes_headline.csv),
# with the aims: 16.7 ms at 734×564 and 33 ms at 1280×720.
load "scripts/plots/_style.gp"
set output dir."/render_frame_size.png"
file = dir."/render_sizes_headline.csv"
stats file using 6 nooutput
set title "Frame time vs image size (level 4, depth 3, 2 threads; lower is better)\n{/*0.85 wall clock of one run; compare lines within the chart (same run), not with the aims, when the machine was shared}"
set key inside left top box opaque
set xlabel "pixels per frame (millions): 734×564, 960×540, 1280×720, 1600×900, 1920×1080"
set ylabel "time per frame (ms)"
set yrange [0:*]
set xrange [0:2.2]
set label 1 "aim 734×564" at 0.414, 16.7 point pt 8 ps 2 lc rgb "#e7298a" offset 1,-1
set label 2 "aim 1280×720" at 0.922, 33.0 point pt 8 ps 2 lc rgb "#e7298a" offset 1,-1
plot file using ($3/1e6):6 with linespoints pt 7 lc rgb "#d95f02" title "deforming slime, moving camera (refit + every pixel)", \
     file using ($3/1e6):9 with linespoints pt 5 lc rgb "#1b9e77" title "moving camera (every pixel traced)", \
     file using ($3/1e6):10 with linespoints pt 9 lc rgb "#66a61e" title "still camera (pixels the slime cannot change reused)", \
     file using ($3/1e6):7 with linespoints pt 4 dt 2 lc rgb "#7570b3" title "Embree-only replay of the deforming frame's queries", \
     file using ($3/1e6):(2*$7) with lines dt 3 lc rgb "#7570b3" title "2 × that replay (aim)"
