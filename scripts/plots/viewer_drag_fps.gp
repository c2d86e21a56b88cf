# The viewer's frame rate over a scripted drag at 1280×720 (issue 15): every frame of `slime view
# --size 1280x720 --scenario tests/scenarios/drag_top_in_circles_6s.json --frames 700 --frame-log`: enough frames on a
# fast machine to see the release at 9.5 s and the slime settle after it,
# at full resolution (viewer_drag.csv) and with the adaptive resolution's 30 fps target
# (viewer_drag_adaptive.csv), against simulated time (the physics keeps real time); below, the scale
# each run traced its image at. Frame log columns: 3 frame_ms, 13 scale, 14 grabbed, 15 simulated_s.
# Only the full bench run writes these logs; without them there is no chart.
load "scripts/plots/_style.gp"
full = dir."/viewer_drag.csv"
adaptive = dir."/viewer_drag_adaptive.csv"
if (system(sprintf("test -s '%s' && test -s '%s' && echo yes", full, adaptive)) ne "yes") {
  print sprintf("viewer_drag_fps.gp: no %s or %s (the full scripts/bench.sh writes them); no chart", full, adaptive)
  exit
}
set output dir."/viewer_drag_fps.png"
# The grabbed stretch, shaded in both panels: the first and last frame the slime was held.
stats full using ($14 == 1 ? $15 : NaN) name "grabbed" nooutput
set object 1 rectangle from grabbed_min, graph 0 to grabbed_max, graph 1 behind fc rgb "#fff1c2" fs solid noborder
set xrange [0:grabbed_max + 2.5]  # the drag and the first seconds after it
set lmargin 10
set rmargin 4

set multiplot title "Viewer frame rate over a scripted drag, 1280×720 window (higher is better)\n{/*0.85 every frame of one run each; software OpenGL (Xvfb) draws the panels; the image is 947×720 at full resolution}"
set size 1, 0.66
set origin 0, 0.30
set bmargin 0
set format x ""
set key inside right top horizontal maxrows 2 box opaque
set label 1 "slime grabbed and dragged in circles" at grabbed_min, graph 0.05 offset 0.5,0
set ylabel "frames per second"
# Room above the fastest frames for the key (a frame with nothing new to trace waits up to 1/60 s).
set yrange [0:*]
set offsets 0, 0, graph 0.22, 0
plot full using 15:(1000.0 / $3) with lines lw 1 lc rgb "#d95f02" title "full resolution (the default)", \
     adaptive using 15:(1000.0 / $3) with lines lw 1 lc rgb "#1b9e77" title "adaptive resolution, target 30 fps", \
     30 with lines dt 3 lw 1.5 lc rgb "#e7298a" title "30 fps aim"

set size 1, 0.30
set origin 0, 0.0
set tmargin 0
set bmargin 3.5
set format x "%g"
unset label 1
set xlabel "simulated time (s)"
set ylabel "image scale"
set yrange [0:1.1]
set ytics 0.25
set key inside right bottom horizontal box opaque
plot full using 15:13 with steps lw 1 lc rgb "#d95f02" title "full resolution", \
     adaptive using 15:13 with steps lw 1 lc rgb "#1b9e77" title "adaptive"
unset multiplot
