#pragma once
// Threading and SIMD choices shared by the hot loops.
//
// OpenMP (SABLE_OPENMP, on by default) threads the force pass, the neighbour
// build, the integrator, walls and gravity. Every threaded loop gives the same
// bits as the serial one, whatever the thread count (each value is computed
// once and summed in a fixed order); below a size threshold a loop runs on one
// thread, where the fork/join would cost more than it saves. The thread count
// is OpenMP's (OMP_NUM_THREADS).
//
// When the cores are shared (other jobs, ctest -j), libgomp's default
// spin-waiting at barriers can cost whole scheduler time slices per step:
// there, run with OMP_WAIT_POLICY=passive (or one thread).
#include <cstddef>
#include <cstdio>
#include <functional>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace sable {

// Vector width of the contact loops (the laws' column loops, contact_models/kernel.h).
enum class Simd { SSE2, AVX2, AVX512 };

// Size thresholds and the SIMD switch. Tests lower the thresholds to run the
// threaded paths on small systems and narrow the SIMD width to compare the variants.
struct ThreadSettings {
  std::size_t pair_atoms = 4096;    // pair pass threaded from this many grains ...
  std::size_t pair_entries = 8192;  // ... and list entries
  std::size_t loop_work = 32768;    // per-atom loops: atoms x cost units
  std::size_t wall_block = 256;     // near-wall grains per block of FixWallGran's force sum
  Simd simd = Simd::AVX512;         // widest contact loops allowed (the CPU and SABLE_SIMD may allow less)
};
ThreadSettings& thread_settings();

// Threads to use for the pair force pass over `natoms` atoms with `entries` list entries (1: serial).
int pair_thread_count(std::size_t natoms, std::size_t entries);

// Threads for a loop over `n` items of about `cost` cheap operations each (1: serial).
int loop_thread_count(std::size_t n, std::size_t cost = 1);

// Threading of a pass over every atom (integrator, force fixes, checks). All
// such passes take the same decision and the same split (AtomSplit), so each
// thread meets the atoms whose cache lines it touched last. Even a serial read
// costs: the lines are then shared with the first core, and the owner's next
// write waits for a remote invalidation per line.
inline bool atom_pass_threaded(std::size_t n) { return loop_thread_count(n, 8) > 1; }

// The atom ranges of the threads in per-atom passes: those of the threaded
// pair pass (balanced by its measured work) while they describe n atoms and
// the thread count, else equal parts. Any split gives the same results.
struct AtomSplit {
  std::size_t n = 0;
  std::vector<int> lo;  // threads + 1 bounds
  // Range [lo, hi) of thread t of nt over n atoms.
  void range(std::size_t natoms, int t, int nt, std::size_t& a, std::size_t& b) const {
    if (n == natoms && lo.size() == static_cast<std::size_t>(nt) + 1) {
      a = static_cast<std::size_t>(lo[t]);
      b = static_cast<std::size_t>(lo[t + 1]);
    } else {
      a = natoms * t / nt;
      b = natoms * (t + 1) / nt;
    }
  }
};

// How evenly the threads shared the threaded passes of one kind during a run:
// each thread's busy seconds and the passes' wall seconds (the rest of the
// wall time a thread waited for the others). The run summary prints them.
struct ThreadBalance {
  std::vector<double> busy;  // per thread
  double wall = 0.0;
  long calls = 0;
  void clear() { *this = ThreadBalance{}; }
  // Before a region of `threads` threads (each then adds to its own slot).
  void begin(int threads) {
    if (busy.size() < static_cast<std::size_t>(threads)) busy.resize(threads, 0.0);
  }
};
enum class PassKind { Pair, Atoms };
ThreadBalance& thread_balance(PassKind k);

// Per-pass timing of the threaded pair pass, for diagnosing the threads'
// waiting: one line per pass in the file named by SABLE_PAIR_TRACE (absent:
// nothing is recorded). sable_tools/bench/pair_trace.py summarises it.
class PairTrace {
 public:
  static PairTrace* get();  // nullptr unless SABLE_PAIR_TRACE is set
  // Seconds from the pass's start, per thread: start, end of phase A (cross
  // entries), start of phase B (after the barrier), end. Filled by the threads.
  std::vector<double> t;
  void begin(int threads) { t.assign(4 * static_cast<std::size_t>(threads), 0.0); }
  // plan: seconds spent choosing the split; kind: 0 kept, 1 re-split, 2 new list.
  void write(double plan, int kind, double wall);

 private:
  explicit PairTrace(std::FILE* f) : out_(f) {}
  std::FILE* out_;
};

// Per-atom work on the atoms [lo, hi) of thread t's range (Pair::compute_then).
using RangeTail = std::function<void(int t, std::size_t lo, std::size_t hi)>;

// Runs body(t, lo, hi) once per thread t on its range [lo, hi) of the n atoms
// (one call, t = 0, over all of them when the pass is not threaded).
template <class Body>
void for_atom_ranges([[maybe_unused]] const AtomSplit& split, std::size_t n, Body&& body) {
#ifdef _OPENMP
  if (atom_pass_threaded(n)) {
    ThreadBalance& tb = thread_balance(PassKind::Atoms);
    tb.begin(omp_get_max_threads());
    const double t0 = omp_get_wtime();
#pragma omp parallel
    {
      const int t = omp_get_thread_num();
      std::size_t lo, hi;
      split.range(n, t, omp_get_num_threads(), lo, hi);
      const double s0 = omp_get_wtime();
      body(t, lo, hi);
      tb.busy[t] += omp_get_wtime() - s0;
    }
    tb.wall += omp_get_wtime() - t0;
    ++tb.calls;
    return;
  }
#endif
  body(0, std::size_t{0}, n);
}

// Inside a for_atom_ranges body: waits until every thread of the pass got here.
inline void atom_pass_barrier() {
#ifdef _OPENMP
#pragma omp barrier
#endif
}

// Threads a for_atom_ranges pass may use (size of per-thread result arrays).
inline int atom_pass_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

// Per-thread results of an atom pass that a fix keeps until its end(): each
// thread fills its own part (a T aligned to a cache line never shares one).
template <class T>
class ThreadParts {
 public:
  // A part per thread of the coming atom pass, each reset(part) (a serial pass fills only the first).
  template <class Reset>
  void start(Reset&& reset) {
    const std::size_t n = static_cast<std::size_t>(atom_pass_threads());
    if (parts_.size() < n) parts_.resize(n);
    for (T& p : parts_) reset(p);
  }
  T& operator[](int t) { return parts_[static_cast<std::size_t>(t)]; }
  const T& operator[](int t) const { return parts_[static_cast<std::size_t>(t)]; }
  int size() const { return static_cast<int>(parts_.size()); }
  auto begin() const { return parts_.begin(); }
  auto end() const { return parts_.end(); }

 private:
  std::vector<T> parts_;
};

// The contact loops' variant: the widest that the CPU has and that
// thread_settings().simd and the environment (SABLE_SIMD=sse2|avx2|avx512)
// allow. All give identical results: they differ in vector width only (no FMA
// contraction, -ffp-contract=off; no reassociation).
Simd simd_level();

}  // namespace sable
