#!/usr/bin/env bash
# Configure (Release), build and run the inverse-dynamics benchmarks pinned to one core, then
# print the median figures as a Markdown table (see docs/performance.md).
#
#   scripts/bench.sh                      # build-bench/, 5 repetitions, core 0
#   BUILD_DIR=build-x REPS=10 CPU=1 scripts/bench.sh --benchmark_min_time=1
#
# Extra arguments are passed to mo2d_bench. Needs cmake, a C++20 compiler, Eigen 3.4,
# Google Benchmark (libbenchmark-dev), taskset (util-linux) and python3 (for the table).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${BUILD_DIR:-build-bench}
reps=${REPS:-5}
cpu=${CPU:-0}
cd "$root"

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DMO2D_BUILD_BENCH=ON >/dev/null
cmake --build "$build" --target mo2d_bench -j"$(nproc)"

json="$build/bench.json"
pin=()
if command -v taskset >/dev/null; then pin=(taskset -c "$cpu"); else echo "taskset not found: not pinned" >&2; fi
"${pin[@]}" "$build/bench/mo2d_bench" \
  --benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true \
  --benchmark_out="$json" --benchmark_out_format=json "$@"

echo
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), pinned to core ${cpu}"
echo "commit:  $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet HEAD -- src include mechanisms 2>/dev/null || echo ' (+ local changes)')"
echo
python3 - "$json" <<'EOF'
import json, sys
data = json.load(open(sys.argv[1]))
to_us = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}
med = {b["run_name"]: b for b in data["benchmarks"]
       if b.get("run_type") == "aggregate" and b.get("aggregate_name") == "median"}
cv = {b["run_name"]: b for b in data["benchmarks"]
      if b.get("run_type") == "aggregate" and b.get("aggregate_name") == "cv"}

def cpu_us(name):
    b = med[name]
    return b["cpu_time"] * to_us[b["time_unit"]]

def spread(name):
    c = cv.get(name)
    return f"{100 * c['cpu_time']:.1f} %" if c else "-"

rows = [
    ("Whitworth: one sample", "BM_Sample/whitworth", lambda n: f"{cpu_us(n):.2f} us", "<= 5 us",
     lambda n: "met" if cpu_us(n) <= 5 else "MISSED"),
    ("3RRR: one sample", "BM_Sample/rrr3", lambda n: f"{cpu_us(n):.2f} us", "<= 10 us",
     lambda n: "met" if cpu_us(n) <= 10 else "MISSED"),
    ("Whitworth: 501-sample run", "BM_Run/whitworth",
     lambda n: f"{cpu_us(n) / 1e3:.3f} ms ({cpu_us(n) / 501:.2f} us/sample)", "-", lambda n: "-"),
    ("3RRR: 501-sample run", "BM_Run/rrr3",
     lambda n: f"{cpu_us(n) / 1e3:.3f} ms ({cpu_us(n) / 501:.2f} us/sample)", "-", lambda n: "-"),
    ("Whitworth: build_model", "BM_BuildModel/whitworth", lambda n: f"{cpu_us(n):.1f} us", "-",
     lambda n: "-"),
    ("3RRR: build_model", "BM_BuildModel/rrr3", lambda n: f"{cpu_us(n):.1f} us", "-",
     lambda n: "-"),
]
print("| Benchmark | Median CPU time | CV | Target | |")
print("|---|---|---|---|---|")
for label, name, fmt, target, verdict in rows:
    if name not in med:
        print(f"| {label} | (not run) | | {target} | |")
        continue
    print(f"| {label} | {fmt(name)} | {spread(name)} | {target} | {verdict(name)} |")
EOF
