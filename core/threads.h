#pragma once
// Threading and SIMD choices shared by the hot loops.
//
// OpenMP (SABLE_OPENMP, on by default) threads the force pass, the neighbour
// build, the integrator, walls and gravity. Every threaded loop gives the same
// bits as the serial one, whatever the thread count (each value is computed
// once and summed in a fixed order); below a size threshold a loop runs on one
// thread, where the fork/join would cost more than it saves. The thread count
// is OpenMP's (OMP_NUM_THREADS).
#include <cstddef>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace sable {

// Threads to use for the pair force pass over `natoms` atoms with `entries` list entries (1: serial).
int pair_thread_count(std::size_t natoms, std::size_t entries);

// Threads available to a loop over `n` items of about `cost` cheap operations each (1: serial).
int loop_thread_count(std::size_t n, std::size_t cost = 1);

// True when the contact loops may use their AVX2 variant (the CPU has it and
// SABLE_NO_AVX2 is not set). Both variants give identical results: they differ
// in vector width only (no FMA contraction, no reassociation).
bool simd_avx2();

}  // namespace sable
