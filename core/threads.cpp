#include "core/threads.h"

#include <cstdlib>

namespace sable {

static int max_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

// Below ~4000 grains a step takes a few hundred microseconds or less: the
// fork/join and barrier of a parallel region eat much of the gain, and when
// the cores are shared (ctest -j, other jobs) a spinning OpenMP barrier can
// cost whole scheduler time slices per step. Small systems stay serial.
int pair_thread_count(std::size_t natoms, std::size_t entries) {
  if (natoms < 4096 || entries < 8192) return 1;
  return max_threads();
}

int loop_thread_count(std::size_t n, std::size_t cost) {
  if (n * cost < 32768) return 1;
  return max_threads();
}

bool simd_avx2() {
#if defined(__x86_64__) && defined(__GNUC__)
  static const bool yes = __builtin_cpu_supports("avx2") && !std::getenv("SABLE_NO_AVX2");
  return yes;
#else
  return false;
#endif
}

}  // namespace sable
