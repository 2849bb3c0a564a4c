#!/usr/bin/env bash
# Builds sable and runs the whole test suite (unit tests + decks + bad decks), printing the time of each.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/install_deps.sh
t0=$(date +%s)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
t1=$(date +%s)
ctest --test-dir build --output-on-failure -j"$(nproc)"
t2=$(date +%s)
echo "build: $((t1 - t0)) s, tests: $((t2 - t1)) s ($(nproc) cores)"
