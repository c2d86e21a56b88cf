# Issue 28, checkerboard tracing: the viewer's frame rate at 1280×720 over the scripted drag and over the
# first seconds after the drop (nobody touches it, the camera still), main's build beside the `fps`
# branch's, run in turn on the same shared machine, and the PSNR of the checked frames (--check-every 10)
# of the branch's build against the full trace of the same state. Commands: docs/performance.md,
# "Issue 28: checkerboard tracing". Frame log columns: 2 end_s, 3 frame_ms, 14 grabbed, 15 simulated_s,
# 16 check_psnr_db.
# Run from the repository root:
#   gnuplot -e 'dir="docs/bench/issue28/checkerboard"' scripts/plots/comparisons/viewer_checkerboard_issue28.gp
load "scripts/plots/_style.gp"
set output dir."/viewer_checkerboard_issue28.png"
set lmargin 10
set rmargin 4
set multiplot layout 3, 1 title "Viewer at 1280×720, AMD EPYC family 25 (2 cores, AVX2), machine shared with other builds (load 10–18)\n{/*0.85 one run of each build, in turn; render.checkerboard on in the branch (its default)}"
set key inside right top box opaque
set ylabel "fps, drag"
set xlabel "simulated time (s)"
set yrange [0:*]
plot dir."/drag_main.csv" using 15:(1000.0 / $3) with lines lw 1 lc rgb "#7570b3" title "main", \
     dir."/drag_fps.csv" using 15:(1000.0 / $3) with lines lw 1 lc rgb "#d95f02" title "checkerboard", \
     dir."/drag_fps.csv" using 15:($14 == 1 ? 0.2 : NaN) with points pt 5 ps 0.3 lc rgb "#999999" title "held"
set ylabel "fps, after the drop"
set xlabel "wall time since start (s)"
plot dir."/settle_main.csv" using 2:(1000.0 / $3) with lines lw 1 lc rgb "#7570b3" title "main", \
     dir."/settle_fps.csv" using 2:(1000.0 / $3) with lines lw 1 lc rgb "#d95f02" title "checkerboard"
set ylabel "PSNR (dB)"
set xlabel "frame"
set yrange [25:102]
set key inside right top box opaque
plot dir."/drag_fps.csv" using 1:($16 > 0 ? $16 : NaN) with points pt 7 ps 0.6 lc rgb "#d95f02" title "drag: shown vs full trace", \
     dir."/settle_fps.csv" using 1:($16 > 0 ? $16 : NaN) with points pt 9 ps 0.6 lc rgb "#1b9e77" title "after the drop", \
     38 with lines dt 3 lc rgb "#1b9e77" title "mean aim 38 dB", \
     32 with lines dt 2 lc rgb "#e7298a" title "floor 32 dB"
unset multiplot
