#!/bin/sh
# Runs the benchmark once and prints, from that one run, ns per impact (median of
# three repetitions) and the ratios the issue asks for. Usage: run_ratios.sh path/to/impactgen_bench [benchmark args]
set -e
BENCH=${1:?usage: run_ratios.sh path/to/impactgen_bench}
shift
OUT=$(mktemp)
# Three repetitions of each benchmark, interleaved, and their median: one noisy
# stretch on a shared machine then moves one figure less.
"$BENCH" --benchmark_format=csv --benchmark_min_time=0.3 --benchmark_repetitions=3 \
  --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true "$@" > "$OUT"
grep -E "generated:" "$OUT" || true
awk -F, '
  /^"(generated|generated\+energy|eigen|handwritten|batch|batch\+energy)\/.*_median"/ {
    name = $1; gsub(/"/, "", name); sub(/_median$/, "", name)
    for (i = 1; i <= NF; ++i) if (h[i] == "ns_per_impact") ns[name] = $i * 1e9  # the counter is in seconds
  }
  /^name,/ { for (i = 1; i <= NF; ++i) { h[i] = $i; gsub(/"/, "", h[i]) } }
  END {
    split("central-direct central-oblique noncentral-3d massive-3d planar pinned-planar noncentral-3d-engine planar-engine", cls, " ")
    printf "\n(generated, batch: without energy_lost, the outputs Eigen and handwritten compute; +energy: all outputs)\n"
    printf "%-22s %12s %12s %12s %12s %12s %11s %10s %10s\n", "class", "generated", "+energy", "eigen", "handwritten", "batch", "eigen/gen", "hand/gen", "hand/+en"
    for (k = 1; k <= 8; ++k) {
      c = cls[k]; g = ns["generated/" c]; ga = ns["generated+energy/" c]; e = ns["eigen/" c]; hw = ns["handwritten/" c]; b = ns["batch/" c]
      printf "%-22s %10.2fns %10.2fns %10.2fns %10.2fns %10.2fns %11s %10s %10s\n", c, g, ga, e, hw, b,
        (e > 0 ? sprintf("%.1fx", e / g) : "-"), (hw > 0 ? sprintf("%.2fx", hw / g) : "-"), (hw > 0 ? sprintf("%.2fx", hw / ga) : "-")
    }
    g = ns["generated/noncentral-3d"]; e = ns["eigen/noncentral-3d"]
    ge = ns["generated/noncentral-3d-engine"]; he = ns["handwritten/noncentral-3d-engine"]
    gp = ns["generated/planar"]; ep = ns["eigen/planar"]; bp = ns["batch/planar"]; bpe = ns["batch/planar-engine"]
    printf "\nTargets (one run, same inputs):\n"
    printf "  noncentral-3d, tensor inputs: Eigen / generated          = %6.1fx  (target >= 40)\n", e / g
    printf "  noncentral-3d, engine inputs (1/m, I^-1): hand / generated = %6.2fx  (target >= 1)\n", he / ge
    printf "  planar: Eigen / generated                               = %6.1fx  (target >= 50)\n", ep / gp
    printf "  (with energy_lost too: noncentral-3d %.1fx, planar %.1fx)\n", e / ns["generated+energy/noncentral-3d"], ep / ns["generated+energy/planar"]
    printf "  batch planar, tensor inputs (m, I; 2 div/impact)        = %6.0f M impacts/s  (target >= 300)\n", 1000 / bp
    printf "  batch planar, engine inputs (1/m, 1/I; 1 div/impact)    = %6.0f M impacts/s  (target >= 300)\n", 1000 / bpe
    printf "  (with energy_lost too: tensor inputs %.0f, engine inputs %.0f M impacts/s)\n", 1000 / ns["batch+energy/planar"], 1000 / ns["batch+energy/planar-engine"]
    printf "  (batch: SoA, 1024 impacts, 64-byte aligned arrays in L2, one core)\n"
  }' "$OUT"
rm -f "$OUT"
