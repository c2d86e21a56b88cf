#!/usr/bin/env bash
# Builds the libFuzzer targets with clang and runs each over its seed corpus for a bounded time
# (FUZZ_SECONDS, default 60 in all). Fails on any crash, hang, leak or sanitizer report.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-60}
cmake -S . -B build/fuzz -G Ninja -DSLIME_FUZZ=ON -DBUILD_TESTING=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ >/dev/null
cmake --build build/fuzz
fuzzers=(build/fuzz/tests/fuzz/*_fuzz)
per=$(( seconds / ${#fuzzers[@]} ))
for fuzzer in "${fuzzers[@]}"; do
  name=$(basename "$fuzzer" _fuzz)
  work=build/fuzz/corpus-$name
  mkdir -p "$work"
  echo "fuzz: $name for ${per}s"
  "$fuzzer" -artifact_prefix=build/fuzz/ -max_total_time="$per" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    "$work" "tests/fuzz/corpus/$name" 2>&1 | tail -n 12
done
echo "fuzz: no crashes"
