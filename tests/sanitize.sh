#!/usr/bin/env bash
# Builds sable and its unit tests with AddressSanitizer + UndefinedBehaviorSanitizer in
# build-asan/ and runs the unit tests and a short deck fuzz (tests/fuzz/fuzz_decks.py)
# with them. Any sanitizer report fails the run (UBSan does not recover). Not part of
# ctest: the instrumented build alone takes longer than the whole CI budget on 2 cores.
#   bash tests/sanitize.sh            # JOBS=N to set build parallelism, FILTER=gtest-filter
set -euo pipefail
cd "$(dirname "$0")/.."
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# -O1 -g1 (line tables for the reports): the generated contact kernels compile 3x faster
# than at -O2 -g under the sanitizers (one kernel: 2.5 CPU minutes, against over 7).
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSABLE_NATIVE=OFF \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" \
  -DCMAKE_SHARED_LINKER_FLAGS="$flags" -DCMAKE_MODULE_LINKER_FLAGS="$flags"
cmake --build build-asan -j"${JOBS:-$(nproc)}" --target sable sable_tests example_contact_plugin
# Leak checking is off: libgomp's thread pool is never freed and would be reported.
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=0:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export OMP_NUM_THREADS=2 OMP_WAIT_POLICY=passive
# In the tests' build folder, as ctest runs them (some write scratch files where they run).
(cd build-asan/tests && ./sable_tests --gtest_filter="${FILTER:-*}") 2>&1 | tee build-asan/unit.log
status=${PIPESTATUS[0]}
if grep -qE "AddressSanitizer|runtime error:" build-asan/unit.log; then
  echo "sanitize.sh: sanitizer findings in the unit tests (build-asan/unit.log)"; exit 1
fi
[ "$status" -eq 0 ] || { echo "sanitize.sh: unit tests failed"; exit 1; }
# The fuzzer classifies any sanitizer report on stderr as a crash.
/usr/bin/env python3 tests/fuzz/fuzz_decks.py --sable build-asan/sable --count "${FUZZ_COUNT:-200}" --timeout 60
echo "sanitize.sh: no sanitizer finding"
