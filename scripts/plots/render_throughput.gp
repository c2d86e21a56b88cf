# Frame time against the slime's face count, log-log: our renderer's moving-camera frame (every pixel
# traced) and still-camera frame and the Embree-only limit on all cores, the seed's algorithm (brute
# force, 1 thread) on the same moving-camera frame in the same run, and the seed's own figures.
# render.csv columns: 2 faces, 3 threads, 4 still_camera_frame_ms, 7 moving_camera_frame_ms,
# 12 limit_ms_per_frame, 16 brute_force_frame_ms.
load "scripts/plots/_style.gp"
if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
  set terminal pngcairo size 1150,820 enhanced font "DejaVu Sans,11" linewidth 1.5
}
set output dir."/render_throughput.png"
stats dir."/render.csv" using 3 nooutput
threads = int(STATS_max)
set title sprintf("Ray-traced frame time vs slime faces (734×564, depth 3; lower is better)")
set xlabel "slime faces (icosphere levels 0–6)"
set ylabel "time per frame (ms)"
set logscale xy
set format y "10^{%L}"
set xrange [12:130000]
# Seven long entries: below the plot (on a taller canvas), so the plot keeps the width.
set bmargin 13
set key at screen 0.5, 0.2 center top box opaque spacing 1.2
set yrange [1:1e6]
full = rows(dir."/render.csv", 3, sprintf("%d", threads))
single = rows(dir."/render.csv", 3, "1")
plot full using 2:7 with linespoints pt 7 lc rgb "#1b9e77" title sprintf("Slime renderer, moving camera (every pixel traced), %d threads", threads), \
     full using 2:4 with linespoints pt 6 dt 4 lc rgb "#66a61e" title sprintf("Slime renderer, still camera (reuses what the slime cannot change), %d threads", threads), \
     full using 2:12 with linespoints pt 5 dt 2 lc rgb "#7570b3" title sprintf("Embree-only limit (the moving frame's queries, no shading), %d threads", threads), \
     single using 2:16 with linespoints pt 9 lc rgb "#d95f02" title "seed's algorithm (brute force), same moving frame, 1 thread, measured here", \
     rows(dir."/render_seed.csv", 4, "published") using 1:2 with points pt 6 ps 1.5 lc rgb "#e7298a" title "seed's report: 8 threads, i7-10510U", \
     rows(dir."/render_seed.csv", 4, "published") using 1:3 with points pt 4 ps 1.5 lc rgb "#e7298a" title "seed's report: serial", \
     rows(dir."/render_seed.csv", 4, "built_here") using 1:2 with points pt 3 ps 2 lc rgb "#666666" title "seed's program built on this kind of machine, 2 threads"
