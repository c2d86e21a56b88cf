# The stability map: the largest stable time step against spring stiffness for each integrator
# (bisection on the blow-up criterion of app/bench/bench_stability.h), under the theoretical limits from
# ω_max of the mesh (power iteration on M⁻¹K) and the SPEC's estimate ω_max ≈ 2.48 √(k/m).
load "scripts/plots/_style.gp"
set output dir."/physics_stability.png"
set title "Stability map: largest stable time step vs spring stiffness (level 4, 2,562 vertices)"
set xlabel "elementary spring stiffness k_e (N/m)"
set ylabel "largest stable time step dt (s)"
set logscale xy
set format y "10^{%L}"
plot dir."/physics_theory.csv" using 1:4 with lines lw 2 lc rgb "#444444" title "theory: ω_{max} dt = 2 (symplectic Euler, seed's update)", \
     ""                        using 1:5 with lines lw 2 dt 2 lc rgb "#444444" title "theory: ω_{max} dt = 2.83 (RK4)", \
     ""                        using 1:6 with lines dt 3 lc rgb "#999999" title "SPEC estimate ω_{max} = 2.48 √(k/m): dt = 2/ω_{max}", \
     rows(dir."/physics_stability.csv", 1, "explicit_euler") using 2:3 with linespoints pt 7 lc rgb "#d95f02" title "explicit Euler (seed)", \
     rows(dir."/physics_stability.csv", 1, "symplectic_euler") using 2:3 with linespoints pt 5 lc rgb "#1b9e77" title "symplectic Euler", \
     rows(dir."/physics_stability.csv", 1, "rk4") using 2:3 with linespoints pt 9 lc rgb "#7570b3" title "RK4", \
     rows(dir."/physics_stability.csv", 1, "implicit_euler") using 2:3 with linespoints pt 11 lc rgb "#e7298a" title "implicit Euler (CG)", \
     rows(dir."/physics_stability.csv", 1, "xpbd") using 2:3 with linespoints pt 13 lc rgb "#66a61e" title "XPBD"
