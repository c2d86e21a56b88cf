# What an integrator's speed costs in jiggle (`slime bench material`, app/bench/material/bench_damping.h,
# docs/material.md): the free elastic ball started in Lamb's n = 2 torsional mode, nothing physical
# dissipating. Left, the damping ratio ζ the integrator adds against sim.dt, with backward Euler's closed
# form ln(1 + (ωh)²)/(2ωh) dashed (what projective dynamics, an implicit Euler step, tends to as its
# iterations converge); right, the measured frequency over Lamb's, with the ±5 % band.
load "scripts/plots/_style.gp"
set output dir."/material_damping.png"
damping = dir."/material_damping.csv"
# Rows of one method, its iterations and one mode.
method(name, iterations) = sprintf("< awk -F, 'NR > 1 && $1 == \"%s\" && $2 == %d && $3 == \"torsional_n2\"' %s", name, iterations, damping)
set multiplot layout 1,2 title "Numerical damping of Lamb's n = 2 torsional mode (free elastic ball, no physical dissipation)"
set key inside right center box opaque spacing 1.2
set logscale xy
set xrange [0.4:10]
set title "(a) damping ratio added by the integrator"
set xlabel "sim.dt (ms)"
set ylabel "damping ratio ζ"
set format y "10^{%L}"
plot method("symplectic_euler", 0) using ($4*1000):6 with linespoints pt 7 lw 2 lc rgb "#1b9e77" title "symplectic\\_euler (default)", \
     method("rk4", 0) using ($4*1000):6 with linespoints pt 5 lw 2 lc rgb "#666666" title "rk4", \
     method("projective", 1) using ($4*1000):6 with linespoints pt 9 lw 2 lc rgb "#e7298a" title "projective, 1 iteration", \
     method("projective", 3) using ($4*1000):6 with linespoints pt 11 lw 2 lc rgb "#7570b3" title "projective, 3 iterations", \
     method("projective", 10) using ($4*1000):6 with linespoints pt 13 lw 2 lc rgb "#d95f02" title "projective, 10 iterations", \
     method("projective", 10) using ($4*1000):9 with lines dt 2 lw 1.5 lc rgb "#222222" title "backward Euler, closed form"
unset logscale y
set format y "%.2f"
set title "(b) frequency against Lamb's"
set ylabel "measured / Lamb's frequency"
set key inside left bottom box opaque spacing 1.2
set yrange [0.3:1.1]
set style fill transparent solid 0.15 noborder
plot 0.95 with filledcurves y1=1.05 lc rgb "#1b9e77" title "±5 %", \
     method("symplectic_euler", 0) using ($4*1000):7 with linespoints pt 7 lw 2 lc rgb "#1b9e77" title "symplectic\\_euler", \
     method("rk4", 0) using ($4*1000):7 with linespoints pt 5 lw 2 lc rgb "#666666" title "rk4", \
     method("projective", 1) using ($4*1000):7 with linespoints pt 9 lw 2 lc rgb "#e7298a" title "projective, 1 it.", \
     method("projective", 3) using ($4*1000):7 with linespoints pt 11 lw 2 lc rgb "#7570b3" title "projective, 3 it.", \
     method("projective", 10) using ($4*1000):7 with linespoints pt 13 lw 2 lc rgb "#d95f02" title "projective, 10 it."
unset multiplot
