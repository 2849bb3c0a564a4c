#!/usr/bin/env bash
# Builds sable and runs the whole test suite (unit tests + decks + bad decks).
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/install_deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)"
