# Frame time against the slime's face count, log-log: our renderer and the Embree-only limit on all
# cores, the seed's algorithm (brute force, 1 thread) measured in the same run, and the seed's own figures.
load "scripts/plots/_style.gp"
set output dir."/render_throughput.png"
stats dir."/render.csv" using 3 nooutput
threads = int(STATS_max)
set title sprintf("Ray-traced frame time vs slime faces (734×564, depth 3; lower is better)")
set xlabel "slime faces (icosphere levels 0–6)"
set ylabel "time per frame (ms)"
set logscale xy
set format y "10^{%L}"
set xrange [12:130000]
full = rows(dir."/render.csv", 3, sprintf("%d", threads))
single = rows(dir."/render.csv", 3, "1")
plot full using 2:4 with linespoints pt 7 lc rgb "#1b9e77" title sprintf("Slime renderer (Embree + shading), %d threads", threads), \
     full using 2:9 with linespoints pt 5 dt 2 lc rgb "#7570b3" title sprintf("Embree-only limit (same rays, no shading), %d threads", threads), \
     single using 2:12 with linespoints pt 9 lc rgb "#d95f02" title "seed's algorithm (brute force), 1 thread, measured here", \
     rows(dir."/render_seed.csv", 4, "published") using 1:2 with points pt 6 ps 1.5 lc rgb "#e7298a" title "seed's report: 8 threads, i7-10510U", \
     rows(dir."/render_seed.csv", 4, "published") using 1:3 with points pt 4 ps 1.5 lc rgb "#e7298a" title "seed's report: serial", \
     rows(dir."/render_seed.csv", 4, "built_here") using 1:2 with points pt 3 ps 2 lc rgb "#666666" title "seed's program built on this kind of machine, 2 threads"
