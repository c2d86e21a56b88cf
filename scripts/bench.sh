#!/usr/bin/env bash
# Runs every benchmark and redraws every chart: the one command behind docs/bench and the README's
# benchmark section.
#   scripts/bench.sh           full run (about 10 minutes on a quiet 2-core machine) → docs/bench/
#   scripts/bench.sh --quick   one level, few frames, every code path once (CI) → build/bench-quick/
# Builds a Release tree of its own first (build/bench-release, or $SLIME_BENCH_BUILD: an existing tree
# there is built as configured), so that it never races another build. Progress bars appear when
# stderr is a terminal.
# Nothing about timing is asserted: the figures are only as good as the machine is quiet.
set -euo pipefail
cd "$(dirname "$0")/.."

quick=0
case "${1:-}" in
  --quick) quick=1 ;;
  "") ;;
  *) echo "usage: scripts/bench.sh [--quick]" >&2; exit 2 ;;
esac

bin=${SLIME_BENCH_BUILD:-build/bench-release}
# A tree given in SLIME_BENCH_BUILD that is already configured (CI passes the release preset's) is used
# as it is: configuring it again as plain Release would change its flags and rebuild every target.
if [ -z "${SLIME_BENCH_BUILD:-}" ] || [ ! -f "$bin/CMakeCache.txt" ]; then
  cmake -S . -B "$bin" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$bin" -j2 --target slime micro_bench
# The Bullet side-by-side exists only where Debian's libbullet-dev is installed.
cmake --build "$bin" -j2 --target bullet_ball bullet_tets >/dev/null 2>&1 || echo "bench: no Bullet, skipping bullet_ball and bullet_tets"
slime=$bin/app/slime

if [ "$quick" = 1 ]; then
  out=build/bench-quick
  mkdir -p "$out"
  # The brute force keeps its 3 samples after a warm-up (cheap at 160×120, level 2); with --brute-samples
  # below 3 the JSON's headline would say "quick".
  "$slime" bench render --levels 2 --threads 1 --frames 2 --warmup 1 --size 160x120 --brute-max-level 2 --bvh-levels 4 \
    --headline-sizes 160x120 --headline-level 2 --json "$out/render.json" --csv "$out/render.csv"
  # The frame-size chart reads the sizes run's headline table; the quick run's one size stands in for it.
  cp "$out/render_headline.csv" "$out/render_sizes_headline.csv"
  "$slime" bench physics --levels 2 --integrators symplectic_euler,implicit_euler --seconds 0.05 --stability-level 2 \
    --stiffnesses 40 --accuracy-level 2 --steps 1e-3,5e-3 --settle 0.1 --bullet-tets-seconds 0.05 --json "$out/physics.json" --csv "$out/physics.csv"
  "$slime" bench accuracy --levels 1,2 --depths 1,2 --frames 1 --size 160x120 --json "$out/accuracy.json" --csv "$out/accuracy.csv"
  "$slime" bench material --quick --json "$out/material.json" --csv "$out/material.csv"
  "$slime" bench caustics --photons 1000,2000 --frames 1 --csv "$out/caustics.csv"
  if [ -x "$bin/app/bench/bullet_ball" ]; then "$bin/app/bench/bullet_ball" --levels 2 --seconds 0.1 --json "$out/bullet.json"; fi
  "$bin/app/bench/micro_bench" --benchmark_min_time=0.01 --benchmark_filter='springForces/4|renderTile' >/dev/null
else
  out=docs/bench
  mkdir -p "$out"
  "$slime" bench render --levels 0-6 --frames 15 --warmup 2 --brute-max-level 4 --bvh-levels 4,6 \
    --json "$out/render.json" --csv "$out/render.csv"
  # Frame time against image size (issue 15): the headline frames alone, from 734×564 to 1920×1080.
  "$slime" bench render --levels 4 --threads 2 --frames 15 --warmup 2 --brute-max-level -1 --bvh-levels none \
    --headline-sizes 734x564,960x540,1280x720,1600x900,1920x1080 \
    --json "$out/render_sizes.json" --csv "$out/render_sizes.csv"
  "$slime" bench accuracy --levels 0-6 --depths 1-6 --frames 3 --images "$out" \
    --json "$out/accuracy.json" --csv "$out/accuracy.csv"
  "$slime" bench physics --levels 3-6 --seconds 1 --json "$out/physics.json" --csv "$out/physics.csv"
  "$slime" bench material --resolutions 1-4 --json "$out/material.json" --csv "$out/material.csv"
  "$slime" bench caustics --photons 2500,5000,10000,20000,40000 --frames 3 --csv "$out/caustics.csv"
  if [ -x "$bin/app/bench/bullet_ball" ]; then "$bin/app/bench/bullet_ball" --levels 4,6 --seconds 2 --json "$out/bullet.json"; fi
  "$bin/app/bench/micro_bench" --benchmark_out="$out/micro.json" --benchmark_out_format=json
  # The viewer over a scripted drag at 1280×720 (issue 15): every frame's time from the frame log, at
  # full resolution (the default) and with the adaptive resolution's 30 fps target. It needs a display:
  # Xvfb when there is none (software OpenGL draws the panels either way).
  viewer_drag() {  # viewer_drag NAME [extra options]
    local name=$1
    shift
    local run=("$slime" view --size 1280x720 --scenario tests/scenarios/drag_top_in_circles_6s.json --frames 700
               --report "$out/$name.json" --frame-log "$out/$name.csv" "$@")
    if [ -n "${DISPLAY:-}" ]; then "${run[@]}"
    else xvfb-run -a -s "-screen 0 1400x900x24" "${run[@]}"; fi
  }
  if [ -n "${DISPLAY:-}" ] || command -v xvfb-run >/dev/null; then
    viewer_drag viewer_drag
    viewer_drag viewer_drag_adaptive --target-fps 30
  else
    echo "bench: no DISPLAY and no xvfb-run (apt-get install xvfb): skipping the viewer drag" >&2
  fi
fi

# Charts: every scripts/plots/*.gp (but _style.gp) reads $out/*.csv and writes $out/<name>.png
# (scripts/plots/comparisons/ holds one-off comparisons, each reading its own data in docs/bench/).
# The quick run's tables are nearly empty: its charts only prove that the scripts run.
for plot in scripts/plots/[!_]*.gp; do
  if [ "$quick" = 1 ]; then gnuplot -e "dir='$out'" "$plot" 2>/dev/null; else gnuplot -e "dir='$out'" "$plot"; fi
done
echo "bench: results and charts in $out/"
