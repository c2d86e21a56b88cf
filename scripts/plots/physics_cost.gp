# ms per 1 ms step for each integrator against the vertex count (levels 3-6), substeps included.
load "scripts/plots/_style.gp"
set output dir."/physics_cost.png"
set title "Physics cost per 1 ms step, with the substeps each integrator needs (1 thread; symplectic Euler at level 6 on 2 TBB threads)"
set xlabel "mass points (icosphere levels 3–6)"
set ylabel "ms per step of 1 ms (log)"
set logscale xy
set arrow from graph 0, first 1 to graph 1, first 1 nohead dt 3 lc rgb "#888888"
plot rows(dir."/physics.csv", 1, "explicit_euler") using 3:4 with linespoints pt 7 lc rgb "#d95f02" title "explicit Euler (seed)", \
     rows(dir."/physics.csv", 1, "symplectic_euler") using 3:4 with linespoints pt 5 lc rgb "#1b9e77" title "symplectic Euler", \
     rows(dir."/physics.csv", 1, "rk4") using 3:4 with linespoints pt 9 lc rgb "#7570b3" title "RK4", \
     rows(dir."/physics.csv", 1, "implicit_euler") using 3:4 with linespoints pt 11 lc rgb "#e7298a" title "implicit Euler (CG)", \
     rows(dir."/physics.csv", 1, "xpbd") using 3:4 with linespoints pt 13 lc rgb "#66a61e" title "XPBD"
