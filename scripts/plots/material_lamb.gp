# Lamb's oracle: the measured frequency of the free elastic ball's n = 2 torsional and spheroidal modes
# over Lamb's (1882) f = η √(G/ρ) / (2πR), ρ = mass / volume of the tetrahedral ball, against the body's
# resolution, with the ±5 % band the issue asks for (`slime bench material`, docs/material.md).
load "scripts/plots/_style.gp"
set output dir."/material_lamb.png"
set title "Lamb's n = 2 modes of the free elastic ball: measured / theoretical frequency against the body's resolution"
set xlabel "body resolution (tetrahedral mesh nodes)"
set ylabel "measured / theoretical frequency"
stats dir."/material.csv" using 2 nooutput  # the resolutions run
set xrange [STATS_min - 0.5:STATS_max + 0.5]
set xtics 1
set key inside right top box opaque spacing 1.3
set yrange [0.9:1.12]
set ytics 0.02
set format y "%.2f"
set style fill transparent solid 0.15 noborder
plot 0.95 with filledcurves y1=1.05 lc rgb "#1b9e77" title "±5 %", \
     1.0 with lines dt 2 lc rgb "#444444" title "theory (Lamb 1882)", \
     rows(dir."/material.csv", 1, "torsional_n2") using 2:6:xtic(sprintf("%d (%d)", $2, $3)) with linespoints pt 7 ps 1.4 lc rgb "#d95f02" title "torsional n = 2 (η = 2.5011)", \
     rows(dir."/material.csv", 1, "spheroidal_n2") using 2:6 with linespoints pt 5 ps 1.4 lc rgb "#7570b3" title "spheroidal n = 2 (ν = 0.4)"
