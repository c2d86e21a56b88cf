# What the slime's physics costs: CPU ms per simulated second of the drop-and-grab (landing, floor
# contact, a grab and a drag, with the program's automatic substeps) — the bulk body beside the seed's
# membrane, Bullet's btSoftBody (peers/bullet_ball, a drop without a grab) and Jolt's soft body as SPEC §9
# quotes it; on the right also Bullet's finite elements on the body's own tetrahedra (peers/bullet_tets)
# and Jolt on them as issue 27 quotes it (AMD EPYC family 23). Left: against the drawn vertices; right: against the simulated points. Reads physics.csv.
load "scripts/plots/_style.gp"
if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
  set terminal pngcairo size 1500,680 enhanced font "DejaVu Sans,11" linewidth 1.5
} else {
  set terminal png size 1500,680
}
set output dir."/physics_cost.png"
file = dir."/physics.csv"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xrange [20:100000]
set yrange [3:100000]
set ylabel "CPU ms per simulated second (log; 1000 = one core in real time)"
set key inside left top box opaque spacing 1.15 font ",10"
set multiplot layout 1,2 title "Physics cost per simulated second, grab and contact included (CPU time; the machine was shared: see physics.json)"
aim = 250
set arrow 1 from graph 0, first aim to graph 1, first aim nohead dt 2 lc rgb "#c00000"
set label 1 "aim: 0.25 s of one core" at graph 0.98, first aim*1.25 right tc rgb "#c00000" font ",9"
set arrow 2 from graph 0, first 1000 to graph 1, first 1000 nohead dt 3 lc rgb "#888888"
set label 2 "real time on one core" at graph 0.98, first 1250 right tc rgb "#888888" font ",9"

set title "against the drawn vertices (icosphere levels 3–6)"
set xlabel "drawn vertices"
plot rows(file, 1, "bulk_level") using 8:10 with linespoints pt 7 ps 1.3 lc rgb "#1b9e77" title "bulk body, resolution 2 (487 points)", \
     rows(file, 1, "bulk_level") using 8:10:(sprintf("L%d", $5)) with labels offset 0,-1.1 font ",9" tc rgb "#1b9e77" notitle, \
     rows(file, 1, "membrane") using 8:10 with linespoints pt 5 lc rgb "#d95f02" title "membrane (the seed's skin)", \
     rows(file, 1, "bullet") using 8:10 with linespoints pt 9 ps 1.3 lc rgb "#7570b3" title "Bullet btSoftBody (measured; no grab)", \
     rows(file, 1, "jolt") using 8:10:11:12 with yerrorlines pt 13 ps 1.3 lc rgb "#e7298a" title "Jolt soft body (quoted, SPEC §9)"

set title "against the simulated points (bulk: resolutions at drawn level 4)"
set xlabel "simulated mass points"
plot rows(file, 1, "bulk_resolution") using 7:10 with linespoints pt 7 ps 1.3 lc rgb "#1b9e77" title "bulk body, symplectic Euler, resolutions 1–3", \
     rows(file, 1, "bulk_resolution") using 7:10:(sprintf("R%d", $6)) with labels offset 0,-1.1 font ",9" tc rgb "#1b9e77" notitle, \
     rows(file, 1, "bulk_integrator") using 7:10:(strcol(4) eq "rk4" ? "RK4" : "explicit Euler") with labels point pt 6 ps 1.3 lc rgb "#1b9e77" offset -1,0 right font ",9" tc rgb "#1b9e77" noenhanced title "bulk body, resolution 2, other integrators", \
     rows(file, 1, "membrane") using 7:10 with linespoints pt 5 lc rgb "#d95f02" title "membrane (simulated = drawn)", \
     rows(file, 1, "bullet") using 7:10 with linespoints pt 9 ps 1.3 lc rgb "#7570b3" title "Bullet btSoftBody (measured; no grab)", \
     rows(file, 1, "bullet_tets") using 7:10 with linespoints pt 11 ps 1.3 lc rgb "#66a61e" title "Bullet FEM on the body's tetrahedra (measured; no grab)", \
     rows(file, 1, "jolt") using 7:10:11:12 with yerrorlines pt 13 ps 1.3 lc rgb "#e7298a" title "Jolt soft body (quoted, SPEC §9)", \
     rows(file, 1, "jolt_tets") using 7:10 with linespoints pt 12 ps 1.3 lc rgb "#e6ab02" title "Jolt on the body's tetrahedra (quoted, issue 27, F23)"
unset multiplot
