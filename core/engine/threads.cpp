#include "core/engine/threads.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace sable {

ThreadSettings& thread_settings() {
  static ThreadSettings s;
  return s;
}

static int max_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

// Below ~4000 grains a step takes a few hundred microseconds or less: the
// fork/join and barrier of a parallel region eat much of the gain, and when
// the cores are shared a spinning barrier can cost scheduler time slices.
int pair_thread_count(std::size_t natoms, std::size_t entries) {
  const ThreadSettings& s = thread_settings();
  if (natoms < s.pair_atoms || entries < s.pair_entries) return 1;
  return max_threads();
}

int loop_thread_count(std::size_t n, std::size_t cost) {
  if (n * cost < thread_settings().loop_work) return 1;
  return max_threads();
}

ThreadBalance& thread_balance(PassKind k) {
  static ThreadBalance pair, atoms;
  return k == PassKind::Pair ? pair : atoms;
}

PairTrace* PairTrace::get() {
  static PairTrace* trace = [] {
    const char* path = std::getenv("SABLE_PAIR_TRACE");
    if (!path || !*path) return static_cast<PairTrace*>(nullptr);
    std::FILE* f = std::fopen(path, "w");
    if (!f) {
      std::fprintf(stderr, "sable: SABLE_PAIR_TRACE=%s cannot be written; no pair trace\n", path);
      return static_cast<PairTrace*>(nullptr);
    }
    std::fprintf(f, "# plan_s kind wall_s, then per thread: start_s phaseA_end_s phaseB_start_s end_s (kind: 0 kept, 1 re-split, 2 new list)\n");
    return new PairTrace(f);  // lives to the end of the process
  }();
  return trace;
}

void PairTrace::write(double plan, int kind, double wall) {
  std::fprintf(out_, "%.9g %d %.9g", plan, kind, wall);
  for (double v : t) std::fprintf(out_, " %.9g", v);
  std::fputc('\n', out_);
  std::fflush(out_);  // a killed run keeps its lines
}

// The CPU's widest variant, capped by SABLE_SIMD.
static Simd simd_available() {
  Simd s = Simd::SSE2;
#if defined(__x86_64__) && defined(__GNUC__)
  if (__builtin_cpu_supports("avx2")) s = Simd::AVX2;
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512bw"))
    s = Simd::AVX512;
#endif
  if (const char* e = std::getenv("SABLE_SIMD")) {
    const std::string w = e;
    if (w == "sse2" || w == "avx2" || w == "avx512")
      s = std::min(s, w == "sse2" ? Simd::SSE2 : w == "avx2" ? Simd::AVX2 : Simd::AVX512);
    else
      std::fprintf(stderr, "sable: SABLE_SIMD=%s ignored (expected sse2, avx2 or avx512)\n", e);
  }
  return s;
}

Simd simd_level() {
  static const Simd cpu = simd_available();
  return std::min(cpu, thread_settings().simd);
}

}  // namespace sable
