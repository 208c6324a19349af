#!/bin/sh
# Runs the benchmark once and prints, from that one run, ns per impact (median of the
# repetitions, CPU time of the benchmark thread: per core) and the ratios the issue asks
# for: generated vs Eigen vs hand-written, the generated Jacobian vs autodiff, and the
# batch loop of planar built by g++ and by clang++.
# Usage: run_ratios.sh path/to/impactgen_bench [benchmark args]
#   REPETITIONS (default 5) and MIN_TIME (seconds per repetition, default 0.2) in the
#   environment change how long it runs.
set -e
BENCH=${1:?usage: run_ratios.sh path/to/impactgen_bench [benchmark args]}
shift
OUT=$(mktemp)
LOG=$(mktemp)
trap 'rm -f "$OUT" "$LOG"' EXIT
# Repetitions of each benchmark, interleaved, and their median: one noisy stretch on a
# shared machine then moves one figure less.
"$BENCH" --benchmark_format=csv --benchmark_min_time="${MIN_TIME:-0.2}" --benchmark_repetitions="${REPETITIONS:-5}" \
  --benchmark_enable_random_interleaving=true "$@" > "$OUT" 2> "$LOG" ||
  { cat "$LOG" >&2; exit 1; }
# What the benchmark printed first: operation counts, the autodiff = Jacobian check,
# the compilers of the batch kernels.
grep -vE '^("|name,)' "$OUT" | grep -E "generated:|autodiff =|batch-" || true
awk -F, '
  /^name,/ { for (i = 1; i <= NF; ++i) { h[i] = $i; gsub(/"/, "", h[i]) } next }
  /_median"/ {
    name = $1; gsub(/"/, "", name); sub(/_median$/, "", name)
    for (i = 1; i <= NF; ++i) if (h[i] == "ns_per_impact") ns[name] = $i * 1e9  # the counter is in seconds
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
  function mps(x) { return x > 0 ? sprintf("%.0f", 1000 / x) : "-" }  # M impacts/s from ns per impact
  END {
    split("central-direct central-oblique noncentral-3d massive-3d planar pinned-planar noncentral-3d-engine planar-engine", cls, " ")
    printf "\n(ns per impact, median; generated, batch: without energy_lost, the outputs Eigen and handwritten compute; +energy: all outputs)\n"
    printf "%-22s %10s %10s %10s %10s %10s %10s %9s %9s\n", "class", "generated", "+energy", "eigen", "handwritten", "batch", "eigen/gen", "hand/gen", "hand/+en"
    for (k = 1; k <= 8; ++k) {
      c = cls[k]; g = ns["generated/" c]; ga = ns["generated+energy/" c]; e = ns["eigen/" c]; hw = ns["handwritten/" c]; b = ns["batch/" c]
      printf "%-22s %10s %10s %10s %10s %10s %10s %9s %9s\n", c, f(g, "%.2f"), f(ga, "%.2f"), f(e, "%.1f"), f(hw, "%.2f"), f(b, "%.2f"),
        r(e, g, "%.1fx"), r(hw, g, "%.2fx"), r(hw, ga, "%.2fx")
    }
    g = ns["generated/noncentral-3d"]; e = ns["eigen/noncentral-3d"]
    ge = ns["generated/noncentral-3d-engine"]; he = ns["handwritten/noncentral-3d-engine"]
    gp = ns["generated/planar"]; ep = ns["eigen/planar"]
    printf "\nTargets (one run, same inputs):\n"
    printf "  noncentral-3d, tensor inputs: Eigen / generated            = %7s  (target >= 40)\n", r(e, g, "%.1fx")
    printf "  noncentral-3d, engine inputs (1/m, I^-1): hand / generated = %7s  (target >= 1)\n", r(he, ge, "%.2fx")
    printf "  planar: Eigen / generated                                  = %7s  (target >= 50)\n", r(ep, gp, "%.1fx")
    printf "  (with energy_lost too: noncentral-3d %s, planar %s)\n", r(e, ns["generated+energy/noncentral-3d"], "%.1fx"), r(ep, ns["generated+energy/planar"], "%.1fx")

    printf "\n  Jacobian (generated <name>_jacobian) vs forward-mode autodiff of <name> (Eigen AutoDiffScalar, K = inputs):\n"
    split("noncentral-3d noncentral-3d-engine planar", jc, " ")
    for (k = 1; k <= 3; ++k) {
      c = jc[k]; j = ns["jacobian/" c]; a = ns["autodiff/" c]
      printf "    %-22s jacobian %8s ns  autodiff %8s ns  autodiff / jacobian = %7s%s\n", c, f(j, "%.1f"), f(a, "%.1f"), r(a, j, "%.1fx"),
        (c == "noncentral-3d" ? "  (target >= 5)" : "")
    }

    printf "\n  Small classes with every check vs the unchecked hand-written formula (hand / generated, target >= 0.9;\n"
    printf "  medians, and the ratio of the fastest repetitions: on a shared machine a busy neighbour slows the code with\n"
    printf "  more instructions more, and the medians of one binary move by 0.1 from run to run):\n"
    split("central-direct central-oblique planar pinned-planar", sc, " ")
    for (k = 1; k <= 4; ++k) {
      c = sc[k]
      printf "    %-22s %7s  fastest %7s  (with energy_lost: %s)\n", c, r(ns["handwritten/" c], ns["generated/" c], "%.2fx"),
        r(lo["handwritten/" c], lo["generated/" c], "%.2fx"), r(ns["handwritten/" c], ns["generated+energy/" c], "%.2fx")
    }

    printf "\n  Batch planar, M impacts/s per core (SoA, 1024 impacts, 64-byte aligned arrays in L2; target >= 300 with either compiler):\n"
    printf "    %-10s %18s %18s %18s %18s\n", "compiler", "tensor inputs", "engine (1/m, 1/I)", "tensor +energy", "engine +energy"
    split("gcc clang", cc, " ")
    for (k = 1; k <= 2; ++k) {
      id = cc[k]
      if (!(("batch-" id "/planar") in ns)) continue
      printf "    %-10s %18s %18s %18s %18s\n", id, mps(ns["batch-" id "/planar"]), mps(ns["batch-" id "/planar-engine"]),
        mps(ns["batch+energy-" id "/planar"]), mps(ns["batch+energy-" id "/planar-engine"])
    }
    if (("batch-gcc/planar" in ns) && ("batch-clang/planar" in ns))
      printf "    clang / g++ (tensor inputs) = %s\n", r(ns["batch-gcc/planar"], ns["batch-clang/planar"], "%.2fx")
    printf "    (batch/planar above: the loop inlined in the benchmark, built by the project'"'"'s compiler)\n"
  }' "$OUT"
