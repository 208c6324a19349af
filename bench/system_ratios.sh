#!/bin/sh
# Runs the system benchmark once and prints ns per impact (median of the repetitions, CPU time)
# and the ratios: generated vs the numeric LCP reference numeric/system_reference.hpp.
# Usage: system_ratios.sh path/to/impactgen_system_bench [benchmark args]
#   REPETITIONS (default 5) and MIN_TIME (seconds per repetition, default 0.2).
set -e
BENCH=${1:?usage: system_ratios.sh path/to/impactgen_system_bench [benchmark args]}
shift
OUT=$(mktemp)
LOG=$(mktemp)
trap 'rm -f "$OUT" "$LOG"' EXIT
"$BENCH" --benchmark_format=csv --benchmark_min_time="${MIN_TIME:-0.2}" --benchmark_repetitions="${REPETITIONS:-5}" \
  --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true "$@" > "$OUT" 2> "$LOG" ||
  { cat "$LOG" >&2; exit 1; }
awk -F, '
  /^name,/ { for (i = 1; i <= NF; ++i) { h[i] = $i; gsub(/"/, "", h[i]) } next }
  /_median"/ {
    name = $1; gsub(/"/, "", name); sub(/_median$/, "", name)
    for (i = 1; i <= NF; ++i) if (h[i] == "ns_per_impact") ns[name] = $i * 1e9
  }
  function r(a, b, fmt) { return (a > 0 && b > 0) ? sprintf(fmt, a / b) : "-" }
  function f(x, fmt) { return x > 0 ? sprintf(fmt, x) : "-" }
  END {
    split("compass-gait double-pendulum-struck three-balls-simultaneous box-four-corners", sys, " ")
    printf "(ns per impact, median of the repetitions; one run)\n"
    printf "%-26s %10s %10s %14s\n", "system", "generated", "reference", "reference/gen"
    for (k = 1; k <= 4; ++k) {
      c = sys[k]; g = ns["generated/" c]; e = ns["reference/" c]
      printf "%-26s %10s %10s %14s\n", c, f(g, "%.1f"), f(e, "%.0f"), r(e, g, "%.1fx")
    }
    printf "\nTargets: reference / generated >= 20 for each system; compass-gait generated = %s ns (target <= 100)\n", \
      f(ns["generated/compass-gait"], "%.1f")
  }' "$OUT"
