#!/usr/bin/env bash
# Soak runs (issue 6), not part of CTest because they take minutes:
#  1. `slime sim` for SOAK_SIM_SECONDS simulated seconds (default 600) of random grabs, drags, presses
#     and parameter changes from a seeded random scenario, then 5 s untouched. Passes when no NaN is
#     ever reported, no vertex goes below the floor, the volume is back within 2 % at the end and the
#     process's resident memory stays flat (last sample within 5 % of the sample a tenth of the way in,
#     plus the report's own series: 32 bytes per 10 ms sample, which the user asked for).
#  2. the viewer under Xvfb for SOAK_VIEW_SECONDS wall seconds (default 240) of random mouse drags,
#     wheel turns and camera keys, with the same memory rule, then Esc: exit code 0 and a finite report.
# Usage: scripts/soak.sh [build dir, default build/release]   (SOAK_SEED picks the random sequence)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
slime=$build/app/slime
out=$build/soak
mkdir -p "$out"
seed=${SOAK_SEED:-1}
simSeconds=${SOAK_SIM_SECONDS:-600}
viewSeconds=${SOAK_VIEW_SECONDS:-240}

fail() { echo "soak: FAIL: $*" >&2; exit 1; }

# rss_watch PID FILE: appends the process's resident set (kB) to FILE every second while it runs.
rss_watch() {
  while kill -0 "$1" 2>/dev/null; do
    awk '/^VmRSS/ {print $2}' "/proc/$1/status" 2>/dev/null >> "$2" || true
    sleep 1
  done
}

# memory_flat FILE WHAT [ALLOWANCE_KB]: the last RSS sample within 5 % (+ ALLOWANCE_KB) of the one a
# tenth of the way in.
memory_flat() {
  awk -v what="$2" -v allowance="${3:-0}" '{ s[NR] = $1 } END {
      if (NR < 10) { print "soak: " what ": too few memory samples (" NR ")"; exit 1 }
      early = s[int(NR / 10) + 1]; late = s[NR]
      printf "soak: %s resident memory %d kB after warm-up, %d kB at the end (%d samples)\n", what, early, late, NR
      if (late > early * 1.05 + allowance) { print "soak: " what ": memory grew by more than 5 %"; exit 1 } }' "$1"
}

# --- 1. headless physics with a random scenario ----------------------------------------------------
scenario=$out/random_scenario.json
awk -v seed="$seed" -v seconds="$simSeconds" 'BEGIN {
  srand(seed); t = 0.5; n = 0
  keys[0] = "slime.stiffness"; low[0] = 20;   high[0] = 500
  keys[1] = "slime.damping";   low[1] = 0.01; high[1] = 1
  keys[2] = "slime.mass";      low[2] = 0.05; high[2] = 1
  keys[3] = "slime.pressure";  low[3] = 1;    high[3] = 5
  keys[4] = "slime.friction";  low[4] = 0;    high[4] = 2
  printf "{\"events\": [\n"
  while (t < seconds) {
    kind = rand()
    if (kind < 0.45) {          # grab somewhere near the ball, pull it anywhere within 15 cm, let go
      printf "{\"t\": %.3f, \"grab\": {\"point\": [%.4f, %.4f, %.4f], \"radius\": %.4f}},\n", t,
             (rand() - 0.5) * 0.1, (rand() - 0.5) * 0.1, rand() * 0.1, 0.01 + rand() * 0.02
      d = 0.05 + rand() * 0.5
      printf "{\"t\": %.3f, \"drag\": {\"to\": [%.4f, %.4f, %.4f], \"duration\": %.3f}},\n", t,
             (rand() - 0.5) * 0.3, (rand() - 0.5) * 0.3, rand() * 0.15, d
      printf "{\"t\": %.3f, \"release\": {}},\n", t + d + rand() * 0.5
      t += d + 0.6
    } else if (kind < 0.7) {    # press in from above or the side
      printf "{\"t\": %.3f, \"press\": {\"point\": [%.4f, %.4f, 0.1], \"direction\": [%.3f, %.3f, -1], \"depth\": %.4f, \"duration\": %.3f}},\n",
             t, (rand() - 0.5) * 0.04, (rand() - 0.5) * 0.04, (rand() - 0.5), (rand() - 0.5), rand() * 0.05, 0.05 + rand() * 0.3
      t += 0.8
    } else {                    # change a material parameter
      k = int(rand() * 5)
      printf "{\"t\": %.3f, \"set\": {\"%s\": %.4f}},\n", t, keys[k], low[k] + rand() * (high[k] - low[k])
      t += 0.2 + rand()
    }
  }
  # The last event puts the defaults back, so the end state can be compared with the rest shape.
  printf "{\"t\": %.3f, \"set\": {\"slime.stiffness\": 100, \"slime.damping\": 0.1, \"slime.mass\": 0.268, \"slime.pressure\": 3, \"slime.friction\": 0.6}}\n]}\n", seconds
}' > "$scenario"
echo "soak: sim, $simSeconds s simulated with $(grep -c '"t"' "$scenario") random events (seed $seed)"
: > "$out/sim_rss.txt"
"$slime" sim --seconds "$((simSeconds + 5))" --scenario "$scenario" --report "$out/sim_report.json" > "$out/sim.txt" &
pid=$!
rss_watch "$pid" "$out/sim_rss.txt" &
wait "$pid" || fail "slime sim exited with $?"
cat "$out/sim.txt"
jq -e '.nan == false' "$out/sim_report.json" > /dev/null || fail "the sim reported NaN"
jq -e '.range.min_z >= 0' "$out/sim_report.json" > /dev/null || fail "a vertex went below the floor"
jq -e '(.final.volume_ratio - 1) | fabs < 0.02' "$out/sim_report.json" > /dev/null || fail "volume not back within 2 %"
echo "soak: sim rollbacks $(jq .rollbacks "$out/sim_report.json"), volume range $(jq -c '[.range.volume_ratio_min, .range.volume_ratio_max]' "$out/sim_report.json")"
seriesKb=$(( (simSeconds + 5) * 100 * 32 / 1024 ))
memory_flat "$out/sim_rss.txt" "sim" "$seriesKb" || fail "sim memory"

# --- 2. the viewer under Xvfb with random input -------------------------------------------------------
cat > "$out/drive_viewer.sh" <<'DRIVE'
set -u
slime=$1; out=$2; seconds=$3; seed=$4
"$slime" view --size 480x360 --report "$out/view_report.json" > "$out/view.txt" 2>&1 &
pid=$!
window=$(timeout 30 xdotool search --sync --name '^Slime$' | head -1)
[ -n "$window" ] || { echo "no viewer window"; kill $pid; exit 1; }
: > "$out/view_rss.txt"
( while kill -0 $pid 2>/dev/null; do awk '/^VmRSS/ {print $2}' /proc/$pid/status >> "$out/view_rss.txt" 2>/dev/null; sleep 1; done ) &
RANDOM=$seed
end=$((SECONDS + seconds))
keys=(w a s d q e r f)
while [ $SECONDS -lt $end ]; do
  case $((RANDOM % 4)) in
    0) xdotool mousemove --window "$window" $((180 + RANDOM % 120)) $((120 + RANDOM % 140)) mousedown 1
       xdotool mousemove --window "$window" $((RANDOM % 480)) $((RANDOM % 360)); sleep 0.3; xdotool mouseup 1 ;;
    1) xdotool mousemove --window "$window" $((RANDOM % 480)) $((RANDOM % 360)) click $((4 + RANDOM % 2)) ;;
    2) xdotool key --window "$window" --delay 150 "${keys[$((RANDOM % 8))]}" ;;
    3) xdotool mousemove --window "$window" $((200 + RANDOM % 80)) $((150 + RANDOM % 80)) mousedown 1 keydown shift
       xdotool mousemove --window "$window" $((200 + RANDOM % 80)) $((200 + RANDOM % 100)); sleep 0.2
       xdotool keyup shift mouseup 1 ;;
  esac
  sleep 0.$((RANDOM % 5))
done
xdotool key --window "$window" Escape
wait $pid
DRIVE
echo "soak: viewer, $viewSeconds s of random input under Xvfb"
xvfb-run -a -s "-screen 0 640x480x24" bash "$out/drive_viewer.sh" "$slime" "$out" "$viewSeconds" "$seed" ||
  fail "the viewer did not exit cleanly: $(tail -5 "$out/view.txt")"
jq -e '.frames > 0 and (.metrics.volume_ratio | isnormal) and .metrics.min_z >= 0' "$out/view_report.json" > /dev/null ||
  fail "bad viewer report: $(cat "$out/view_report.json")"
echo "soak: viewer ran $(jq .frames "$out/view_report.json") frames at $(jq .fps "$out/view_report.json") fps, $(jq .grabs "$out/view_report.json") grabs"
memory_flat "$out/view_rss.txt" "viewer" || fail "viewer memory"
echo "soak: passed"
