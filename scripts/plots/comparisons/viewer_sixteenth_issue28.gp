# Issue 28, sixteenth checkerboard: the viewer's frame rate at 1280×720 over the scripted drag and over the
# first frames after the drop (nobody touches it, the camera still): 55b35a3 (the issue's base), main
# (441c32b, the quarter checkerboard) and the `fps` branch (b2c6734, the sixteenth), run in turn on the
# same shared machine (round 2 of 3), and the PSNR of the checked frames (--check-every 10) of the
# branch's build and of the quarter's against the full trace of the same state. Commands:
# docs/performance.md, "Issue 28: the sixteenth checkerboard". Frame log columns: 1 frame, 2 end_s,
# 3 frame_ms, 14 grabbed, 15 simulated_s, 16 check_psnr_db.
# Run from the repository root:
#   gnuplot -e 'dir="docs/bench/issue28/sixteenth"' scripts/plots/comparisons/viewer_sixteenth_issue28.gp
load "scripts/plots/_style.gp"
set output dir."/viewer_sixteenth_issue28.png"
set lmargin 10
set rmargin 4
set multiplot layout 3, 1 title "Viewer at 1280×720, AMD EPYC family 25 (2 cores, AVX2), machine shared with other builds\n{/*0.85 round 2 of 3 in turn; checkerboard defaults of each build; PSNR from separate --check-every 10 runs}"
set key inside right top box opaque
set ylabel "fps, drag"
set xlabel "simulated time (s)"
set yrange [0:*]
plot dir."/drag_base55_2.csv" using 15:(1000.0 / $3) with lines lw 1 lc rgb "#7570b3" title "55b35a3", \
     dir."/drag_main_2.csv" using 15:(1000.0 / $3) with lines lw 1 lc rgb "#1b9e77" title "main (quarter)", \
     dir."/drag_new_2.csv" using 15:(1000.0 / $3) with lines lw 1 lc rgb "#d95f02" title "sixteenth", \
     dir."/drag_new_2.csv" using 15:($14 == 1 ? 0.2 : NaN) with points pt 5 ps 0.3 lc rgb "#999999" title "held"
set ylabel "fps, after the drop"
set xlabel "simulated time (s)"
plot dir."/settle_base55_2.csv" using 15:(1000.0 / $3) with lines lw 1 lc rgb "#7570b3" title "55b35a3", \
     dir."/settle_main_2.csv" using 15:(1000.0 / $3) with lines lw 1 lc rgb "#1b9e77" title "main (quarter)", \
     dir."/settle_new_2.csv" using 15:(1000.0 / $3) with lines lw 1 lc rgb "#d95f02" title "sixteenth"
set ylabel "PSNR (dB)"
set xlabel "frame"
set yrange [25:102]
plot dir."/drag_check_new.csv" using 1:($16 > 0 ? $16 : NaN) with points pt 7 ps 0.6 lc rgb "#d95f02" title "drag, sixteenth", \
     dir."/drag_check_quarter.csv" using 1:($16 > 0 ? $16 : NaN) with points pt 6 ps 0.6 lc rgb "#1b9e77" title "drag, quarter", \
     dir."/settle_check_new.csv" using 1:($16 > 0 ? $16 : NaN) with points pt 9 ps 0.6 lc rgb "#e6ab02" title "after the drop, sixteenth", \
     38 with lines dt 3 lc rgb "#1b9e77" title "mean aim 38 dB", \
     32 with lines dt 2 lc rgb "#e7298a" title "floor 32 dB"
unset multiplot
