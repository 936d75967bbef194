#!/usr/bin/env bash
# The matcher benchmarks, rusoar and the official Soar 9.6 kernel, one after the other
# on this machine, ending with the side-by-side table (scripts/bench_official.py --ours).
#   1. cargo bench --features internals --bench rete, its figures also written as JSON (RETE_BENCH_JSON);
#   2. the official kernel on the same generated rules and changes;
#   3. `rusoar --source` of the 100,000-rule file, three runs, wall time and peak RSS.
# Usage: scripts/bench_side_by_side.sh [OUTDIR]   (default: a new temporary directory)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-$(mktemp -d)}
mkdir -p "$out"
echo "writing to $out"
RETE_BENCH_JSON="$out/ours.json" cargo bench --features internals --bench rete 2>&1 | tee "$out/rete-bench.txt"
python3 scripts/bench_official.py --json "$out/official.json" --ours "$out/ours.json" \
    2>&1 | tee "$out/official.txt"
python3 scripts/gen_rules.py nomatch 100000 > "$out/nomatch-100000.soar"
cargo build --release --bin rusoar
for i in 1 2 3; do
    /usr/bin/time -f "rusoar --source nomatch-100000.soar: %e s wall, %U s user, %S s sys, %M KB peak" \
        target/release/rusoar --source "$out/nomatch-100000.soar" > /dev/null
done 2>&1 | tee "$out/source-100k.txt"
