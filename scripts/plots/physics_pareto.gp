# Accuracy against cost of the integrators: RMS vertex error of the drop-and-grab against the RK4
# reference, against wall-clock time per simulated second; one point per time step dt.
load "scripts/plots/_style.gp"
set output dir."/physics_pareto.png"
set title "Physics: accuracy vs cost (drop and grab, level 4; lower left is better)"
set xlabel "wall-clock seconds per simulated second (1 = real time)"
set ylabel "RMS vertex error vs RK4 reference (mm)"
set logscale xy
set arrow from 1, graph 0 to 1, graph 1 nohead dt 3 lc rgb "#888888"
plot rows(dir."/physics_accuracy.csv", 1, "explicit_euler") using 6:4 with linespoints pt 7 lc rgb "#d95f02" title "explicit Euler (seed)", \
     rows(dir."/physics_accuracy.csv", 1, "symplectic_euler") using 6:4 with linespoints pt 5 lc rgb "#1b9e77" title "symplectic Euler", \
     rows(dir."/physics_accuracy.csv", 1, "rk4") using 6:4 with linespoints pt 9 lc rgb "#7570b3" title "RK4", \
     rows(dir."/physics_accuracy.csv", 1, "implicit_euler") using 6:4 with linespoints pt 11 lc rgb "#e7298a" title "implicit Euler (CG)", \
     rows(dir."/physics_accuracy.csv", 1, "xpbd") using 6:4 with linespoints pt 13 lc rgb "#66a61e" title "XPBD", \
     rows(dir."/physics_accuracy.csv", 3, "1") using 6:4:(sprintf("%g ms", $2*1000)) with labels offset 0.6,0.6 font ",8" tc rgb "#555555" notitle
