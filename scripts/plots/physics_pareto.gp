# Accuracy against cost: RMS distance of the drawn vertices from a much smaller-step RK4 reference over
# the pinch in the air (no contact: see app/bench/physics/bench_trajectory_error.h for why), against CPU seconds
# per simulated second; one point per substep h (labelled in ms), and a ringed point for each integrator
# at the program's own automatic substeps. Lower left is better. Left: the bulk body; right: the seed's
# membrane. Reads physics_accuracy.csv.
load "scripts/plots/_style.gp"
if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
  set terminal pngcairo size 1500,680 enhanced font "DejaVu Sans,11" linewidth 1.5
} else {
  set terminal png size 1500,680
}
set output dir."/physics_pareto.png"
file = dir."/physics_accuracy.csv"
stable(series) = sprintf("< awk -F, 'NR > 1 && $1 == \"%s\" && $8 == 1' %s", series, file)
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "CPU seconds per simulated second (1 = one core in real time)"
set ylabel "RMS error of the drawn vertices vs the RK4 reference (mm)"
set key inside right top box opaque spacing 1.15 font ",10"
set multiplot layout 1,2 title "Accuracy against cost: a pinch in the air at drawn level 4, 0.5 s (labels: substep h in ms; rings: the program's automatic substeps)"
set arrow 1 from 1, graph 0 to 1, graph 1 nohead dt 3 lc rgb "#888888"

ring(m) = sprintf("< awk -F, 'NR > 1 && $2 == \"%s\" && $7 == 1 && $8 == 1' %s", m, file)
steps(m) = sprintf("< awk -F, 'NR > 1 && $2 == \"%s\" && $7 == 0 && $8 == 1' %s", m, file)

set title "bulk body (resolution 2): symplectic Euler, explicit Euler, RK4"
plot stable("bulk:symplectic_euler") using 11:9 with linespoints pt 5 lc rgb "#1b9e77" title "symplectic Euler (default)", \
     stable("bulk:explicit_euler") using 11:9 with linespoints pt 7 lc rgb "#d95f02" title "explicit Euler (seed's)", \
     stable("bulk:rk4") using 11:9 with linespoints pt 9 lc rgb "#7570b3" title "RK4", \
     ring("bulk") using 11:9 with points pt 6 ps 3 lc rgb "#333333" title "automatic substeps (as the program runs)", \
     steps("bulk") using 11:9:(sprintf("%g", $4*1000)) with labels offset 0.2,0.8 font ",8" tc rgb "#555555" notitle

set title "membrane (the seed's skin)"
plot stable("membrane:symplectic_euler") using 11:9 with linespoints pt 5 lc rgb "#1b9e77" title "symplectic Euler", \
     stable("membrane:explicit_euler") using 11:9 with linespoints pt 7 lc rgb "#d95f02" title "explicit Euler (seed's)", \
     stable("membrane:rk4") using 11:9 with linespoints pt 9 lc rgb "#7570b3" title "RK4", \
     stable("membrane:implicit_euler") using 11:9 with linespoints pt 11 lc rgb "#e7298a" title "implicit Euler (CG)", \
     stable("membrane:xpbd") using 11:9 with linespoints pt 13 lc rgb "#66a61e" title "XPBD", \
     ring("membrane") using 11:9 with points pt 6 ps 3 lc rgb "#333333" title "automatic substeps (as the program runs)", \
     steps("membrane") using 11:9:(sprintf("%g", $4*1000)) with labels offset 0.2,0.8 font ",8" tc rgb "#555555" notitle
unset multiplot
