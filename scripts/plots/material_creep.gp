# Creep and recovery of the whole body under a constant twist (a body force along the n = 2 torsional
# mode, switched on and off while the Maxwell branch was frozen), as twist / instantaneous elastic
# twist, against the standard linear solid's closed form with τ_c = τ (μ∞ + μ1)/μ∞
# (`slime bench material`, docs/material.md).
load "scripts/plots/_style.gp"
set output dir."/material_creep.png"
stats rows(dir."/material_creep.csv", 1, "creep") using 6:7 nooutput
creepTau = STATS_mean_x; materialTau = STATS_mean_y
stats rows(dir."/material_creep.csv", 1, "recovery") using 6 nooutput
recoveryTau = STATS_mean
set title sprintf("Whole-body creep under a constant twist, then recovery without it: fitted τ %.3f s (creep), %.3f s (recovery); material τ_c %.3f s", \
                  creepTau, recoveryTau, materialTau)
set xlabel "time since the twist came on (s; the elastic settling before the recovery left out)"
set ylabel "twist / instantaneous elastic twist"
stats rows(dir."/material_creep.csv", 1, "recovery") using 2 nooutput  # (before any range: stats honours them)
set yrange [-0.1:3.4]
set arrow from STATS_min, graph 0 to STATS_min, graph 1 nohead dt 3 lc rgb "#888888"
set label "twist removed:\nthe elastic part springs back" at STATS_min + 0.8, first 1.35
set key inside right top box opaque spacing 1.3
plot rows(dir."/material_creep.csv", 1, "creep") using 2:3 with lines lw 2.5 lc rgb "#1b9e77" title "creep, measured", \
     rows(dir."/material_creep.csv", 1, "recovery") using 2:3 with lines lw 2.5 lc rgb "#d95f02" title "recovery, measured", \
     rows(dir."/material_creep.csv", 1, "creep") using 2:5 with lines lw 1.5 dt 2 lc rgb "#222222" title "closed form: 1/L − (1/L − 1) e^{−t/τ_c},  L = μ_∞/G,  τ_c = τ G/μ_∞", \
     rows(dir."/material_creep.csv", 1, "recovery") using 2:5 with lines lw 1.5 dt 4 lc rgb "#222222" title "closed form: (creep(t_1) − 1) e^{−(t−t_1)/τ_c}"
