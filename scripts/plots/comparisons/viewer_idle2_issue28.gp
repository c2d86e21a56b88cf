# Issue 28 after the merge of fps3 (2026-11-27 afternoon, main 677df0f): the viewer's frame rate at 1280×720
# over the scripted drag and over the first 20 s after the drop (nobody touches it, the camera still),
# 55b35a3 (the issue's base) against main, run in turn on the idle AMD EPYC family 25 (held: round 4 of 5,
# the median round of main; settling: round 1 of 2), and the PSNR of checked frames (--check-every 10)
# from fps3's loaded runs (docs/bench/issue28/fps3).
# Commands: docs/performance.md, "Issue 28 on the idle machine, after the merge of fps3".
# Frame log columns: 3 frame_ms, 14 grabbed, 15 simulated_s, 16 check_psnr_db.
# Run from the repository root:
#   gnuplot -e 'dir="docs/bench/issue28/idle2"; checks="docs/bench/issue28/fps3"' scripts/plots/comparisons/viewer_idle2_issue28.gp
load "scripts/plots/_style.gp"
set output dir."/viewer_idle2_issue28.png"
set lmargin 10
set rmargin 4
set multiplot layout 3, 1 title "Viewer at 1280×720, AMD EPYC family 25 (2 cores, AVX2), idle, builds in turn\n{/*0.85 held median 15.5 → 38.8 fps (2.49×, 5 rounds), first 20 s after the drop 18.5 → 47.0 fps (2.54×, 2 rounds)}"
set key inside right top box opaque
set ylabel "fps, drag"
set xlabel "simulated time (s)"
set yrange [0:70]
plot dir."/held_base_4.csv" using 15:(1000.0 / $3) with lines lw 1 lc rgb "#7570b3" title "55b35a3", \
     dir."/held_main_4.csv" using 15:(1000.0 / $3) with lines lw 1 lc rgb "#d95f02" title "main 677df0f", \
     dir."/held_main_4.csv" using 15:($14 == 1 ? 1 : NaN) with points pt 5 ps 0.3 lc rgb "#999999" title "held", \
     30 with lines dt 3 lc rgb "#666666" title "30 fps"
set ylabel "fps, after the drop"
set xrange [0:20]
set yrange [0:110]
set key inside left top horizontal
plot dir."/settle_base_1.csv" using 15:(1000.0 / $3) with lines lw 1 lc rgb "#7570b3" title "55b35a3", \
     dir."/settle_main_1.csv" using 15:(1000.0 / $3) with lines lw 1 lc rgb "#d95f02" title "main 677df0f", \
     30 with lines dt 3 lc rgb "#666666" title "30 fps"
set autoscale x
set key inside right top vertical
set ylabel "PSNR (dB)"
set xlabel "frame"
set yrange [25:70]
plot checks."/drag_check_fps3.csv" using 1:($16 > 0 ? $16 : NaN) with points pt 7 ps 0.6 lc rgb "#d95f02" title "drag", \
     checks."/settle_check_fps3.csv" using 1:($16 > 0 ? $16 : NaN) with points pt 9 ps 0.6 lc rgb "#e6ab02" title "after the drop", \
     38 with lines dt 3 lc rgb "#1b9e77" title "mean aim 38 dB", \
     32 with lines dt 2 lc rgb "#e7298a" title "floor 32 dB"
unset multiplot
