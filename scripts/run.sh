#!/usr/bin/env bash
# The main job: install what is missing, build, then walk through the notes'
# worked example (a ball striking a hinged rod) and solve it as a problem file.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DIMPACTGEN_BUILD_TESTS=OFF -DIMPACTGEN_BUILD_BENCH=OFF >/dev/null
cmake --build build -j"$(nproc)" --target impactgen
./build/cli/impactgen list
echo
./build/cli/impactgen explain pinned-planar
echo
./build/cli/impactgen solve examples/problems/hinged-rod.json
