#!/bin/sh
# Runs the friction benchmark once and prints ns per impact (median of the repetitions,
# CPU time) and the ratios: generated vs the Eigen reference numeric/friction_solver.hpp.
# Usage: friction_ratios.sh path/to/impactgen_friction_bench [benchmark args]
#   REPETITIONS (default 5) and MIN_TIME (seconds per repetition, default 0.2).
set -e
BENCH=${1:?usage: friction_ratios.sh path/to/impactgen_friction_bench [benchmark args]}
shift
OUT=$(mktemp)
LOG=$(mktemp)
trap 'rm -f "$OUT" "$LOG"' EXIT
"$BENCH" --benchmark_format=csv --benchmark_min_time="${MIN_TIME:-0.2}" --benchmark_repetitions="${REPETITIONS:-5}" \
  --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true "$@" > "$OUT" 2> "$LOG" ||
  { cat "$LOG" >&2; exit 1; }
grep -vE '^("|name,)' "$OUT" | grep -E "impacts:" || true
awk -F, '
  /^name,/ { for (i = 1; i <= NF; ++i) { h[i] = $i; gsub(/"/, "", h[i]) } next }
  /_median"/ {
    name = $1; gsub(/"/, "", name); sub(/_median$/, "", name)
    for (i = 1; i <= NF; ++i) if (h[i] == "ns_per_impact") ns[name] = $i * 1e9
  }
  function r(a, b, fmt) { return (a > 0 && b > 0) ? sprintf(fmt, a / b) : "-" }
  function f(x, fmt) { return x > 0 ? sprintf(fmt, x) : "-" }
  END {
    split("planar-friction ball-floor-friction noncentral-3d-friction", cls, " ")
    printf "\n(ns per impact, median; generated and batch without energy_lost, the outputs the reference computes)\n"
    printf "%-24s %10s %10s %10s %10s %12s\n", "class", "generated", "+energy", "eigen", "batch", "eigen/gen"
    for (k = 1; k <= 3; ++k) {
      c = cls[k]; g = ns["generated/" c]; ga = ns["generated+energy/" c]; e = ns["eigen/" c]; b = ns["batch/" c]
      printf "%-24s %10s %10s %10s %10s %12s\n", c, f(g, "%.1f"), f(ga, "%.1f"), f(e, "%.0f"), f(b, "%.1f"), r(e, g, "%.1fx")
    }
    printf "\nTargets (one run, same inputs):\n"
    printf "  planar-friction: eigen / generated        = %8s  (target >= 30)\n", r(ns["eigen/planar-friction"], ns["generated/planar-friction"], "%.1fx")
    printf "  noncentral-3d-friction: eigen / generated = %8s  (target >= 10)\n", r(ns["eigen/noncentral-3d-friction"], ns["generated/noncentral-3d-friction"], "%.1fx")
    printf "  noncentral-3d-friction: generated         = %8s ns (target <= 150)\n", f(ns["generated/noncentral-3d-friction"], "%.1f")
    printf "  batch/planar-friction                     = %8s ns\n", f(ns["batch/planar-friction"], "%.1f")
  }' "$OUT"
