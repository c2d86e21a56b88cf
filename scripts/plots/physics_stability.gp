# The stability maps: the largest time step at which each integrator does not blow up (bisection on
# the criterion of app/bench/physics/bench_stability.h: one substep, automatic substeps off), as points, beside
# the limit the simulation predicts for itself (Simulation::largestStableStep, from ω_max by power
# iteration), as dashed lines of the same colour. Left: the bulk body against its shear modulus;
# right: the seed's membrane against its spring stiffness. Reads physics_stability.csv.
load "scripts/plots/_style.gp"
if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
  set terminal pngcairo size 1500,680 enhanced font "DejaVu Sans,11" linewidth 1.5
} else {
  set terminal png size 1500,680
}
set output dir."/physics_stability.png"
file = dir."/physics_stability.csv"
set logscale xy
set format y "10^{%L}"
set yrange [1e-5:0.1]
set ylabel "largest stable time step dt (s)"
set key inside left bottom box opaque spacing 1.15 font ",10"
set multiplot layout 1,2 title "Stability maps: measured blow-up step (points) against the predicted limit (dashed)"
set arrow 1 from graph 0, first 0.05 to graph 1, first 0.05 nohead dt 3 lc rgb "#888888"
set label 1 "top of the search: 50 ms" at graph 0.98, first 0.065 right tc rgb "#888888" font ",9"
set arrow 2 from graph 0, first 0.001 to graph 1, first 0.001 nohead dt 3 lc rgb "#bbbbbb"
set label 2 "sim.dt = 1 ms" at graph 0.98, first 0.0013 right tc rgb "#999999" font ",9"

set title "bulk body (slime.model=bulk, resolution 2), against the shear modulus"
set xlabel "modulus G (Pa)"
set format x "10^{%L}"
set xrange [30:150000]
set arrow 3 from 1200, graph 0 to 1200, graph 1 nohead dt 3 lc rgb "#bbbbbb"
set label 3 "default 1,200 Pa" at 1300, graph 0.96 left tc rgb "#999999" font ",9"
plot rows(file, 1, "bulk:symplectic_euler") using 4:5 with linespoints pt 5 ps 1.2 lc rgb "#1b9e77" title "symplectic Euler (default)", \
     rows(file, 1, "bulk:symplectic_euler") using 4:7 with lines dt 2 lc rgb "#1b9e77" title "  predicted 2/ω_{max}", \
     rows(file, 1, "bulk:explicit_euler") using 4:5 with linespoints pt 7 ps 1.2 lc rgb "#d95f02" title "explicit Euler (seed's)", \
     rows(file, 1, "bulk:explicit_euler") using 4:7 with lines dt 2 lc rgb "#d95f02" title "  predicted 4/(c+√(c²+4ω²))", \
     rows(file, 1, "bulk:rk4") using 4:5 with linespoints pt 9 ps 1.2 lc rgb "#7570b3" title "RK4", \
     rows(file, 1, "bulk:rk4") using 4:7 with lines dt 2 lc rgb "#7570b3" title "  predicted 2.78/(ω_{max}+c)"

set title "membrane (slime.model=membrane, the seed's skin), against spring stiffness"
set xlabel "elementary spring stiffness k_e (N/m)"
set format x "%g"
set xrange [7:2000]
unset arrow 3
unset label 3
plot rows(file, 1, "membrane:symplectic_euler") using 4:5 with linespoints pt 5 ps 1.2 lc rgb "#1b9e77" title "symplectic Euler", \
     rows(file, 1, "membrane:symplectic_euler") using 4:7 with lines dt 2 lc rgb "#1b9e77" notitle, \
     rows(file, 1, "membrane:symplectic_euler") using 4:9 with lines dt 3 lc rgb "#999999" title "SPEC §9 estimate ω_{max} ≈ 2.48 √(k/m)", \
     rows(file, 1, "membrane:explicit_euler") using 4:5 with linespoints pt 7 ps 1.2 lc rgb "#d95f02" title "explicit Euler (seed's)", \
     rows(file, 1, "membrane:explicit_euler") using 4:7 with lines dt 2 lc rgb "#d95f02" notitle, \
     rows(file, 1, "membrane:rk4") using 4:5 with linespoints pt 9 ps 1.2 lc rgb "#7570b3" title "RK4", \
     rows(file, 1, "membrane:rk4") using 4:7 with lines dt 2 lc rgb "#7570b3" notitle, \
     rows(file, 1, "membrane:implicit_euler") using 4:5 with linespoints pt 11 ps 1.2 lc rgb "#e7298a" title "implicit Euler (CG; no limit predicted)", \
     rows(file, 1, "membrane:xpbd") using 4:5 with linespoints pt 13 ps 1.2 lc rgb "#66a61e" title "XPBD", \
     rows(file, 1, "membrane:xpbd") using 4:7 with lines dt 2 lc rgb "#66a61e" notitle
unset multiplot
