#!/bin/sh
# Runs the engine benchmark once and prints, from that one run, ns per impact (median of
# interleaved repetitions, CPU time of the benchmark thread) of the engine-convention headers,
# checked and _unchecked, and of the hand-written formula specialised the same way, with each
# compiler, and the speed of each header relative to the hand formula (hand ns / header ns;
# targets: checked >= 0.7, unchecked >= 1.0).
# Usage: engine_ratios.sh path/to/impactgen_engine_bench [benchmark args]
#   REPETITIONS (default 9) and MIN_TIME (seconds per repetition, default 0.1).
set -e
BENCH=${1:?usage: engine_ratios.sh path/to/impactgen_engine_bench [benchmark args]}
shift
OUT=$(mktemp)
LOG=$(mktemp)
trap 'rm -f "$OUT" "$LOG"' EXIT
"$BENCH" --benchmark_format=csv --benchmark_min_time="${MIN_TIME:-0.1}" --benchmark_repetitions="${REPETITIONS:-9}" \
  --benchmark_enable_random_interleaving=true "$@" > "$OUT" 2> "$LOG" ||
  { cat "$LOG" >&2; exit 1; }
grep -vE '^("|name,)' "$OUT" | grep -E "^engine-" || true
awk -F, '
  /^name,/ { for (i = 1; i <= NF; ++i) { h[i] = $i; gsub(/"/, "", h[i]) } next }
  /_median"/ {
    name = $1; gsub(/"/, "", name); sub(/_median$/, "", name)
    for (i = 1; i <= NF; ++i) if (h[i] == "ns_per_impact") ns[name] = $i * 1e9
    next
  }
  /^"/ && !/_(mean|stddev|cv)"/ {  # one repetition: the fastest of them per benchmark
    name = $1; gsub(/"/, "", name)
    for (i = 1; i <= NF; ++i) if (h[i] == "ns_per_impact" && $i != "") {
      x = $i * 1e9
      if (!(name in lo) || x < lo[name]) lo[name] = x
    }
  }
  function r(a, b, fmt) { return (a > 0 && b > 0) ? sprintf(fmt, a / b) : "-" }
  function f(x, fmt) { return x > 0 ? sprintf(fmt, x) : "-" }
  END {
    printf "\n(ns per impact, median; speed relative to the hand formula = hand / header; fastest repetitions in brackets)\n"
    printf "%-8s %-22s %8s %8s %10s %20s %20s\n", "compiler", "class", "hand", "checked", "unchecked", "checked (>= 0.7)", "unchecked (>= 1.0)"
    split("gcc clang", cc, " ")
    split("planar-engine noncentral-3d-engine", ec, " ")
    for (k = 1; k <= 2; ++k) for (m = 1; m <= 2; ++m) {
      p = "engine-" cc[k] "/" ec[m] "/"
      if (!((p "hand") in ns)) continue
      hd = ns[p "hand"]; c = ns[p "checked"]; u = ns[p "unchecked"]
      printf "%-8s %-22s %8s %8s %10s %20s %20s\n", cc[k], ec[m], f(hd, "%.2f"), f(c, "%.2f"), f(u, "%.2f"),
        r(hd, c, "%.2fx") " (" r(lo[p "hand"], lo[p "checked"], "%.2fx") ")", r(hd, u, "%.2fx") " (" r(lo[p "hand"], lo[p "unchecked"], "%.2fx") ")"
    }
  }' "$OUT"
