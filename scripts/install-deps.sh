#!/usr/bin/env bash
# Installs what impactgen needs from Debian's packages, only what is missing.
#   install-deps.sh          build and run dependencies
#   install-deps.sh --tests  also GoogleTest, Google Benchmark, pdflatex, TikZ, Chromium, clang-format and Ninja for the test suite
set -euo pipefail
packages=(cmake make g++ pkg-config libginac-dev libcln-dev libeigen3-dev nlohmann-json3-dev libcli11-dev)
if [[ "${1:-}" == "--tests" ]]; then
  # clang: the second compiler of the header tests and the compiler of the sanitizer pass
  # (libclang-rt-14-dev has its ASan and UBSan runtimes, only recommended by clang; llvm-14
  # its llvm-symbolizer: without it every sanitized program warns on stderr at exit).
  # clang-format: scripts/check-format.sh, the library against the committed .clang-format.
  # ninja-build: the generator of scripts/test.sh's builds (it schedules the 2 cores better than make).
  packages+=(libgtest-dev libbenchmark-dev libbox2d-dev texlive-latex-base texlive-pictures clang libclang-rt-14-dev llvm-14 chromium zlib1g-dev
             clang-format ninja-build)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "impactgen: installing ${missing[*]}"
  SUDO=""
  [[ $(id -u) -ne 0 ]] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
