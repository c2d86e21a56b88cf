# Parallel speed-up of the renderer (moving- and still-camera frames) and of the Embree-only limit over
# one thread, per level. render.csv columns: 19 still, 20 moving, 21 limit speed-up over 1 thread.
load "scripts/plots/_style.gp"
set output dir."/render_threads.png"
stats dir."/render.csv" using 3 nooutput
threads = int(STATS_max)
set title sprintf("Scaling with threads: speed-up on %d threads over 1 thread (higher is better)", threads)
set xlabel "slime faces (icosphere levels 0–6)"
set ylabel "speed-up over 1 thread (×)"
set logscale x
set xrange [12:130000]
set yrange [0:threads+0.5]
full = rows(dir."/render.csv", 3, sprintf("%d", threads))
plot full using 2:20 with linespoints pt 7 lc rgb "#1b9e77" title "Slime renderer, moving camera (every pixel traced)", \
     full using 2:19 with linespoints pt 6 dt 4 lc rgb "#66a61e" title "Slime renderer, still camera", \
     full using 2:21 with linespoints pt 5 dt 2 lc rgb "#7570b3" title "Embree-only limit", \
     threads with lines dt 3 lc rgb "#888888" title sprintf("ideal (%d×)", threads)
