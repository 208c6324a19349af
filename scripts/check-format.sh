#!/usr/bin/env bash
# The library's C++ sources (the .cpp and .hpp files git tracks under symbolic/ expr/ codegen/
# print/ figure/ exercises/ names/ numeric/ cli/ adapters/) against the committed .clang-format:
# prints each file that clang-format would change and exits 1 if there is one. Not checked:
# generated/ (written by impactgen codegen), tests/, bench/ and examples/.
#   CLANG_FORMAT=<program>  the clang-format to run (default: clang-format, Debian's 14)
# To apply the style to a file: clang-format -i <file>.
set -euo pipefail
cd "$(dirname "$0")/.."
clang_format=${CLANG_FORMAT:-clang-format}
if ! command -v "$clang_format" >/dev/null; then
  echo "check-format: $clang_format not found (scripts/install-deps.sh --tests installs it)" >&2
  exit 2
fi
mapfile -t files < <(git ls-files -- {symbolic,expr,codegen,print,figure,exercises,names,numeric,cli,adapters}/'*'.{cpp,hpp})
if [[ ${#files[@]} -eq 0 ]]; then
  echo "check-format: no sources found (not a git checkout?)" >&2
  exit 2
fi
differ=0
for f in "${files[@]}"; do
  if ! "$clang_format" --style=file "$f" | cmp -s - "$f"; then
    echo "check-format: $f differs from .clang-format (clang-format -i $f)"
    differ=$((differ + 1))
  fi
done
if [[ $differ -gt 0 ]]; then
  echo "check-format: $differ of ${#files[@]} files differ ($("$clang_format" --version))" >&2
  exit 1
fi
echo "check-format: ${#files[@]} files match .clang-format"
