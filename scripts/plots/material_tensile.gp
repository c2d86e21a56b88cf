# The tensile test (`slime bench material`, app/bench/material/bench_tensile.h, docs/material.md), two charts:
# left, a tetrahedral cylinder of the slime's material, its ends held and pulled apart at three constant
# strain rates, its nominal stress against the strain of its middle half (solid), with the standard
# linear solid's closed form σ = E∞ε + E₁ε̇τ(1 − e^{−ε/(ε̇τ)}) dashed and the uniform material point dotted; right, the slime itself pulled apart by two hands at three
# speeds, the hands' pull against the extension of the held parts. Faster needs more force in both.
load "scripts/plots/_style.gp"
set output dir."/material_tensile.png"
set multiplot layout 1,2 title "Tensile test: faster pulls need more force (the Maxwell branch has no time to relax)"
set key inside left top box opaque spacing 1.2
set title "(a) a tetrahedral cylinder (ends held) at a constant strain rate"
set xlabel "engineering strain ε of the middle half"
set ylabel "nominal stress (Pa)"
bar = dir."/material_tensile.csv"
meshed = dir."/material_tensile_bar.csv"
plot rows(meshed, 1, "5") using 3:4 with lines lw 2.5 lc rgb "#d95f02" title "ε̇ = 5 /s", \
     rows(meshed, 1, "0.5") using 3:4 with lines lw 2.5 lc rgb "#7570b3" title "ε̇ = 0.5 /s", \
     rows(meshed, 1, "0.05") using 3:4 with lines lw 2.5 lc rgb "#1b9e77" title "ε̇ = 0.05 /s", \
     rows(bar, 1, "5") using 2:3 with lines lw 1.2 dt 3 lc rgb "#d95f02" title "one material point", \
     rows(bar, 1, "0.5") using 2:3 with lines lw 1.2 dt 3 lc rgb "#7570b3" notitle, \
     rows(bar, 1, "0.05") using 2:3 with lines lw 1.2 dt 3 lc rgb "#1b9e77" notitle, \
     rows(bar, 1, "5") using 2:4 with lines lw 1.2 dt 2 lc rgb "#222222" title "closed form (small strain)", \
     rows(bar, 1, "0.5") using 2:4 with lines lw 1.2 dt 2 lc rgb "#222222" notitle, \
     rows(bar, 1, "0.05") using 2:4 with lines lw 1.2 dt 2 lc rgb "#222222" notitle
set title "(b) the slime pulled apart by two hands"
set xlabel "extension of the held parts (mm)"
set ylabel "each hand's pull (N)"
pull = dir."/material_pull.csv"
plot rows(pull, 1, "0.2") using ($2*1000):3 with lines lw 2.5 lc rgb "#d95f02" title "0.2 m/s apart", \
     rows(pull, 1, "0.1") using ($2*1000):3 with lines lw 2.5 lc rgb "#7570b3" title "0.1 m/s", \
     rows(pull, 1, "0.05") using ($2*1000):3 with lines lw 2.5 lc rgb "#1b9e77" title "0.05 m/s"
unset multiplot
