// sable_core_probe: what synchronising two threads costs on this machine now.
//
// On a 2-vCPU VM the hypervisor places the two vCPUs on cores that share an
// L3 or on cores that do not, and moves them over minutes; a cache line then
// crosses between them in 0.05-0.1 us or in 0.3 us and more. sable's threaded
// step synchronises its threads about six times (regions and barriers) and
// shares the cache lines of the atoms at its split, so its two-thread speed-up
// follows that placement while two independent jobs do not. bench.py runs this
// before each repeat and prints it next to the speed-ups.
//
// Prints one line: core_probe: threads N round_trip_us R barrier_us B region_us P
// (medians of 7 batches: a cache line passed to the other thread and back, an
// OpenMP barrier, an empty OpenMP parallel region).
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <vector>

namespace {

constexpr int kBatches = 7;
constexpr int kReps = 20000;

template <class F>
double median_us(F&& batch) {
  std::vector<double> t;
  for (int b = 0; b < kBatches; ++b) {
    const double t0 = omp_get_wtime();
    batch();
    t.push_back((omp_get_wtime() - t0) / kReps * 1e6);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main() {
  const int nt = std::min(omp_get_max_threads(), 2);
  if (nt < 2) {
    std::printf("core_probe: threads 1 (no second thread: nothing to measure)\n");
    return 0;
  }
#pragma omp parallel num_threads(nt)
  {
  }  // start the team before timing
  alignas(64) std::atomic<int> flag{0};
  const double round_trip = median_us([&] {
    flag.store(0);
#pragma omp parallel num_threads(nt)
    {
      const int me = omp_get_thread_num();
      for (int k = 0; k < kReps; ++k) {  // thread 0 waits for 2k, thread 1 for 2k + 1
        while (flag.load(std::memory_order_acquire) != 2 * k + me) {
        }
        flag.store(2 * k + me + 1, std::memory_order_release);
      }
    }
  });
  const double barrier = median_us([&] {
#pragma omp parallel num_threads(nt)
    for (int k = 0; k < kReps; ++k) {
#pragma omp barrier
    }
  });
  const double region = median_us([&] {
    for (int k = 0; k < kReps; ++k) {
#pragma omp parallel num_threads(nt)
      asm volatile("" ::: "memory");  // an empty region is compiled away
    }
  });
  std::printf("core_probe: threads %d round_trip_us %.3f barrier_us %.3f region_us %.3f\n", nt, round_trip, barrier,
              region);
  return 0;
}
