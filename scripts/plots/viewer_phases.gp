# The viewer's frame times over a run, one colour per phase (issue 43): every frame of `slime view
# --size 1280x720 --frames N --frame-log viewer_phases.csv` (falling, landing, settling, creeping,
# resting; a scenario or a hand adds held, stretched, orbiting). Frame log columns: 2 end_s, 3 frame_ms,
# 20 phase. Run: gnuplot -e "dir='DIR'" scripts/plots/viewer_phases.gp (writes DIR/viewer_phases.png).
load "scripts/plots/_style.gp"
log = dir."/viewer_phases.csv"
if (system(sprintf("test -s '%s' && echo yes", log)) ne "yes") {
  print sprintf("viewer_phases.gp: no %s; no chart", log)
  exit
}
set output dir."/viewer_phases.png"
set title "Viewer frame times by phase, 1280×720 window (lower is better)\n{/*0.85 every frame of one run; a frame with nothing new to trace waits up to 1/60 s}"
set xlabel "wall time, s"
set ylabel "frame time, ms"
set yrange [0:*]
set offsets 0, 0, graph 0.05, 0
# The phases the run has, in the order they first appear.
phases = system(sprintf("awk -F, 'NR > 1 && !seen[$20]++ { printf \"%%s \", $20 }' %s", log))
plot for [phase in phases] \
       rows(log, 20, phase) using 2:3 with points pt 7 ps 0.45 title phase, \
     1000.0 / 30 with lines dt 3 lw 1.5 lc rgb "#e7298a" title "30 fps", \
     100 with lines dt 2 lw 1 lc rgb "#999999" title "100 ms"
