# Issue 28: the viewer's frame rate over the scripted drag at 1280×720, this branch's build beside
# main's on the same machine in the same session (frame logs of `slime view --size 1280x720 --scenario
# tests/scenarios/drag_top_in_circles_6s.json --frames 260 --frame-log`), and below, the PSNR of the
# checked frames (`--check-every 10`) of this build against the full trace of the same state.
# Frame log columns: 3 frame_ms, 14 grabbed, 15 simulated_s, 16 check_psnr_db.
# Run from the repository root: gnuplot -e 'dir="docs/bench/issue28"' scripts/plots/comparisons/viewer_drag_issue28.gp
load "scripts/plots/_style.gp"
main = dir."/drag_main.csv"
this = dir."/drag_this.csv"
check = dir."/drag_check.csv"
set output dir."/viewer_drag_issue28.png"
stats main using ($14 == 1 ? $15 : NaN) name "grabbed" nooutput
set object 1 rectangle from grabbed_min, graph 0 to grabbed_max, graph 1 behind fc rgb "#fff1c2" fs solid noborder
set xrange [0:12]  # the drag (held 2.5–9.5 s) and the first seconds after the release
set lmargin 10
set rmargin 4
set multiplot title "Viewer over the scripted drag, 1280×720 window, AMD EPYC family 25 (2 cores, AVX2), machine shared with other builds\n{/*0.85 one run of each build, in turn; the shaded stretch: the slime held}"
set size 1, 0.62
set origin 0, 0.36
set bmargin 0
set format x ""
set key inside right top box opaque
set ylabel "frames per second"
set yrange [0:*]
plot main using 15:(1000.0 / $3) with lines lw 1 lc rgb "#7570b3" title "main (2db995b)", \
     this using 15:(1000.0 / $3) with lines lw 1 lc rgb "#d95f02" title "this branch"
set size 1, 0.36
set origin 0, 0.0
set tmargin 0
set bmargin 3.5
set format x "%g"
set xlabel "simulated time (s)"
set ylabel "PSNR of checked frames (dB)"
set yrange [25:102]
set key inside right bottom box opaque
plot check using 15:($16 > 0 ? $16 : NaN) with points pt 7 ps 0.6 lc rgb "#d95f02" title "shown vs full trace (100: identical)", \
     38 with lines dt 3 lc rgb "#1b9e77" title "mean aim 38 dB", \
     32 with lines dt 2 lc rgb "#e7298a" title "floor 32 dB"
unset multiplot
