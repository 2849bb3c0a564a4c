#include "core/engine/contact_loop.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <thread>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace sable {
namespace {

// Thread partition of the half list for the parallel force pass (ContactLoopT::pair_forces).
struct PairPartition {
  long version = -1;
  int nparts = 0;
  std::size_t natoms = 0, nentries = 0;
  std::vector<int> lo;                   // nparts + 1 atom bounds of the ranges
  std::vector<int> cross_first;          // nparts + 1: cross entries of range t
  std::vector<int> cross_k, cross_i, cross_j;  // per cross entry (list order): entry, its atoms i and j
  std::vector<int> cross_u;              // per cross entry: the range of j, whose thread evaluates it
  std::vector<int> in_first, in_s;       // range u's incoming cross entries (j in u): in_s[in_first[u] ..], list order
  std::vector<std::uint8_t> on;          // cross entry touching this step
  // What range u's phase A wrote, one row per touching entry in in_s order:
  // only these lines go to the cores of the i ranges.
  struct Slots {
    std::vector<double> fi;  // 6 per row: force and torque on i (read by i's thread)
    std::vector<double> tj;  // 3 per row: torque on j (read by u's thread itself)
    std::vector<int> at;     // nparts: the first row of range t's entries
  };
  std::vector<Slots> slots;              // per range u
  std::vector<int> cursor;               // per range, padded to cache lines: apply_outgoing's next row per later u
  std::size_t cursor_stride() const { return (static_cast<std::size_t>(nparts) + 15) / 16 * 16; }
  std::vector<std::atomic<long>> done_a;  // per range: the last pass whose phase A is done
  long pass = 0;                         // threaded passes so far
  bool rehome = false;                   // a new list: phase A moves its cross entries' history rows
  // Balance from measured time (the results do not depend on the split):
  std::vector<double> cum;               // n + 1: cumulative work weight by atom
  std::vector<double> seg_u, seg_d;      // cost profile: range bounds as weight fractions, seconds per weight
  std::vector<double> busy;              // per range: seconds in phase B since the split
  int calls = 0;                         // force passes since the split
};


template <int kH>
class ContactLoopT final : public ContactLoop {
 public:
  explicit ContactLoopT(const ColumnLaw<kH>& law) : law_(law) {}
  void pair_forces(const PairBatch& b) override { pair_forces_staged(b); }
  void pair_records(const PairBatch& b, ContactRecords& out) override;
  void wall_forces(const WallBatch& b) const override { wall_forces_staged(b); }
  void wall_records(const WallBatch& b, ContactRecords& out) const override;

 private:
  using Chunk = PairChunk<kH>;
  const ColumnLaw<kH>& law_;
  PairPartition part_;

  // ---- The force pass -------------------------------------------------------
  //
  // Each stretch of the half list goes through three stages, a chunk of
  // PairChunk::kCap contacts at a time:
  //   1. filter: which entries touch (branch-free append; an ended contact
  //      forgets its history); the state of the touching pairs is copied into
  //      columns;
  //   2. evaluate: all sub-models on every column, a loop over independent
  //      contacts without branches that the compiler vectorises (AVX-512 or
  //      AVX2 where the CPU has it, SSE2 otherwise: the same operations lane by
  //      lane, so the same bits);
  //   3. scatter: forces and torques added to the grains in list order.
  //
  // Threads (OpenMP, when the list is long enough) own contiguous atom ranges
  // balanced by work. A contact whose j lies in a later range (a "cross"
  // entry) is evaluated into its own slot by the thread of j's range, first
  // (phase A), which then adds the slots aimed at its atoms and runs its range
  // (phase B). The thread of i's range runs its range (phase B) and adds the
  // slots of its own cross entries last, once phase A of the later ranges is
  // done (a flag each, long since set by then: no barrier). An atom's entries
  // are sorted by j (Neighbor::build), so its cross entries are the last of
  // them and phase B runs the serial loop on the rest. Every atom thus
  // receives exactly the serial sequence of additions: j-side contributions by
  // increasing list entry (all from lower atoms), then its own entries in list
  // order (nothing else adds to an atom once its own entries are done). The
  // result is bit-identical to the serial pass for any thread count, with no
  // atomics on forces and no per-thread force copies. Only j's thread reads the
  // other range's grains (i's), and only i's forces go back: the fewest cache
  // lines crossing between the cores.

  void pair_forces_staged(const PairBatch& b) {
    const int nparts = pair_thread_count(b.a.n, b.a.n ? static_cast<std::size_t>(b.first[b.a.n]) : 0);
    if (nparts <= 1) {
      if (b.split) b.split->n = 0;
      Chunk ch;
      pair_range(b, 0, static_cast<int>(b.a.n), nullptr, 0, ch);
      if (b.tail) for_atom_ranges(b.split ? *b.split : AtomSplit{}, b.a.n, *b.tail);  // equal ranges
      return;
    }
#ifdef _OPENMP
    const double w0 = omp_get_wtime();
    PairPartition& pp = part_;
    const long version0 = pp.version;
    const int calls0 = pp.calls;
    plan_partition(b, nparts);
    PairTrace* const trace = PairTrace::get();
    const double plan = omp_get_wtime() - w0;
    if (trace) trace->begin(nparts);
    ++pp.calls;
    const long pass = ++pp.pass;
    if (b.split) {
      b.split->n = b.a.n;
      b.split->lo = pp.lo;
    }
    ThreadBalance& tb = thread_balance(PassKind::Pair);
    tb.begin(nparts);
#pragma omp parallel num_threads(nparts)
    {
      const int nt = omp_get_num_threads(), tid = omp_get_thread_num();
      Chunk ch;
      // Phase A of all this thread's ranges before any waiting (fewer threads
      // than ranges must not wait on themselves).
      const double a0 = omp_get_wtime();
      for (int t = tid; t < nparts; t += nt) {
        const double t0 = omp_get_wtime();
        cross_range(b, pp, t, ch);
        pp.busy[t] += omp_get_wtime() - t0;
        pp.done_a[t].store(pass, std::memory_order_release);
      }
      double busy = omp_get_wtime() - a0;
      if (trace) {
        double* r = &trace->t[4 * static_cast<std::size_t>(tid)];
        r[0] = a0 - w0, r[1] = r[2] = a0 + busy - w0;
      }
      for (int t = tid; t < nparts; t += nt) {
        const double t0 = omp_get_wtime();
        apply_incoming(b, pp, t);
        pair_range(b, pp.lo[t], pp.lo[t + 1], &pp, t, ch);
        if (b.a.nghost) ghost_entries(b, pp.lo[t], pp.lo[t + 1], ch);
        if (b.tail) (*b.tail)(t, static_cast<std::size_t>(pp.lo[t]), static_cast<std::size_t>(pp.lo[t + 1]));
        const double dt = omp_get_wtime() - t0;
        pp.busy[t] += dt;
        busy += dt;
      }
      tb.busy[tid] += busy;
      if (trace) trace->t[4 * static_cast<std::size_t>(tid) + 3] = omp_get_wtime() - w0;
    }
    pp.rehome = false;
    tb.wall += omp_get_wtime() - w0;
    ++tb.calls;
    if (trace) trace->write(plan, pp.version != version0 ? 2 : pp.calls <= calls0 ? 1 : 0, omp_get_wtime() - w0);
#endif
  }

  // What stage 1 reads, copied out of the batch: locals cannot be aliased by
  // the byte stores into `touch`, so the compiler keeps them in registers.
  struct ListView {
    const double* x;
    const double* radius;
    const int* jlist;
    const std::uint8_t* shift;
    const double (*shift_vec)[3];
    int* row;
    ContactStore* store;
    bool forget;  // an ended contact loses its history now (else at the next rebuild)
  };
  static ListView list_view(const PairBatch& b) {
    return {b.a.x, b.a.radius, b.jlist, b.shift, b.shift_vec, b.row, b.store, !b.keep_until_rebuild || b.rebuilt};
  }

  // x_i - (x_j + image shift of entry k).
  [[gnu::always_inline]] static inline void separation(const ListView& L, double xi, double yi, double zi, int j, int k,
                                                       double& dx, double& dy, double& dz) {
    const double* xj = L.x + 3 * j;
    double xj0 = xj[0], xj1 = xj[1], xj2 = xj[2];
    const std::uint8_t code = L.shift[k];
    if (code != NeighborList::kNoShift) {  // periodic image: rare, so predictable
      const double* sh = L.shift_vec[code];
      xj0 += sh[0];
      xj1 += sh[1];
      xj2 += sh[2];
    }
    dx = xi - xj0;
    dy = yi - xj1;
    dz = zi - xj2;
  }

  // Stage 1 for list entry k of atom i: append to the columns (n: the chunk's
  // count, kept in a register by the caller) if touching; a new contact takes a
  // history row, an ended one forgets it.
  [[gnu::always_inline]] static inline void filter_entry(const ListView& L, Chunk& ch, int& n, int i, double xi,
                                                         double yi, double zi, double radi, int k) {
    const int j = L.jlist[k];
    double dx, dy, dz;
    separation(L, xi, yi, zi, j, k, dx, dy, dz);
    const double rsq = dx * dx + dy * dy + dz * dz;
    const double radj = L.radius[j], radsum = radi + radj;
    const bool touching = !(rsq >= radsum * radsum);
    // What the contact needs from the list, kept (the column is overwritten
    // unless the pair touches): the gather then reads no position again.
    ch.i[n] = i;
    ch.j[n] = j;
    ch.dx[n] = dx;
    ch.dy[n] = dy;
    ch.dz[n] = dz;
    ch.radi[n] = radi;
    ch.radj[n] = radj;
    if constexpr (kH > 0) {
      // Contact begun or ended. Rare, so the branch is predictable as long as
      // it does not test `touching` alone (a coin flip): hence the arithmetic.
      int r = L.row[k];
      const unsigned t = touching, has = r >= 0, gone = !t && has;
      if (__builtin_expect(((t & !has) | (gone & static_cast<unsigned>(L.forget))) != 0, 0))
        L.row[k] = r = t ? L.store->new_row() : ContactStore::kNone;
      ch.row[n] = r;
    }
    n += touching;
  }

  // Stage 1, second half: copy the rest of the touching pairs' state into columns.
  // Specialised for the common scene: no frozen grains, one atom type.
  void gather(const PairBatch& b, Chunk& ch) const {
    const bool types = b.a.stride > 2, general = types || b.a.freeze_bit != 0;
    ch.tp0 = types ? -1 : b.a.stride + 1;  // one atom type: one type pair
    // Without rotation (AtomView::rotation) the spins are not gathered: the law
    // reads none (but passes without update take the full kernel, ColumnLaw).
    const bool spin = b.a.rotation || !b.ctx.update;
#if defined(__x86_64__) && defined(__GNUC__)
    if (b.simd == Simd::AVX512) {
      if (spin) return general ? gather_columns_avx512<true, true>(b, ch) : gather_columns_avx512<false, true>(b, ch);
      return general ? gather_columns_avx512<true, false>(b, ch) : gather_columns_avx512<false, false>(b, ch);
    }
#endif
    if (spin) return general ? gather_columns<true, true>(b, ch) : gather_columns<false, true>(b, ch);
    return general ? gather_columns<true, false>(b, ch) : gather_columns<false, false>(b, ch);
  }
  template <bool kGeneral, bool kSpin>
  void gather_columns(const PairBatch& b, Chunk& ch) const {
    const AtomView& a = b.a;
    const double *v = a.v, *w = a.omega, *rmass = a.rmass;
    const int n = ch.n;
    for (int m = 0; m < n; ++m) {
      const int i = ch.i[m], j = ch.j[m];
      ch.mi[m] = rmass[i];
      ch.mj[m] = rmass[j];
      for (int d = 0; d < 3; ++d) {
        ch.vr[d][m] = v[3 * i + d] - v[3 * j + d];
        if constexpr (kSpin) {
          ch.wi[d][m] = w[3 * i + d];
          ch.wj[d][m] = w[3 * j + d];
        }
      }
      if constexpr (kGeneral) {
        ch.frozen[m] = ((a.mask[i] & a.freeze_bit) ? 1 : 0) | ((a.mask[j] & a.freeze_bit) ? 2 : 0);
        ch.itype[m] = a.type[i];
        ch.jtype[m] = a.type[j];
        ch.tp[m] = a.type[i] * a.stride + a.type[j];
      } else {  // one type (1), nothing frozen
        ch.frozen[m] = 0;
        ch.itype[m] = ch.jtype[m] = 1;
        ch.tp[m] = a.stride + 1;
      }
      if constexpr (kH > 0) {
        const double* h = b.hist + static_cast<std::size_t>(ch.row[m]) * kH;
        for (int q = 0; q < kH; ++q) ch.h[q][m] = h[q];
      }
    }
  }

#if defined(__x86_64__) && defined(__GNUC__)
  // gather_columns eight contacts at a time (AVX-512; three-double rows by
  // rows3, scalars by gathers): the same copies and the same differences, so
  // the same bits. Scalar, each column costs a load and a store per contact;
  // here a store per eight. Every column is
  // written in blocks of eight (the chunk has room; lanes past n are unused).
  [[gnu::target("avx512f,avx512vl"), gnu::always_inline]] static inline void put(int* p, __m256i x) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), x);
  }
  // Eight rows of three doubles (at base + 3 * idx[l]) into three columns:
  // eight masked loads and a transpose instead of three 8-lane gathers
  // (24 element loads); history.md has the measurement.
  [[gnu::target("avx512f,avx512vl"), gnu::always_inline]] static inline void rows3(const double* base, const int* idx,
                                                                                __m512d& cx, __m512d& cy, __m512d& cz) {
    __m512d z[4];
    for (int l = 0; l < 4; ++l) {  // lanes 0-3: row l, lanes 4-7: row l + 4 (the fourth double masked off)
      const __m512d lo = _mm512_maskz_loadu_pd(7, base + 3 * static_cast<std::ptrdiff_t>(idx[l]));
      const __m256d hi = _mm256_maskz_loadu_pd(7, base + 3 * static_cast<std::ptrdiff_t>(idx[l + 4]));
      z[l] = _mm512_mask_broadcast_f64x4(lo, 0xF0, hi);
    }
    // (permutes, not unpack / insert: GCC 12 warns on those intrinsics' undefined operand)
    const __m512i lo2 = _mm512_setr_epi64(0, 8, 2, 10, 4, 12, 6, 14), hi2 = _mm512_setr_epi64(1, 9, 3, 11, 5, 13, 7, 15);
    const __m512d t0 = _mm512_permutex2var_pd(z[0], lo2, z[1]), t1 = _mm512_permutex2var_pd(z[0], hi2, z[1]);
    const __m512d t2 = _mm512_permutex2var_pd(z[2], lo2, z[3]), t3 = _mm512_permutex2var_pd(z[2], hi2, z[3]);
    // t0: x0 x1 z0 z1 x4 x5 z4 z5, t2 the same for rows 2, 3, 6, 7; t1, t3: the y values
    const __m512i even = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13), odd = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
    cx = _mm512_permutex2var_pd(t0, even, t2);
    cy = _mm512_permutex2var_pd(t1, even, t3);
    cz = _mm512_permutex2var_pd(t0, odd, t2);
  }
  template <bool kGeneral, bool kSpin>
  [[gnu::target("avx512f,avx512dq,avx512vl")]] void gather_columns_avx512(const PairBatch& b, Chunk& ch) const {
    const AtomView& a = b.a;
    const __m512d zero = _mm512_setzero_pd();
    const int n = ch.n;
    for (int m = 0; m < n; m += 8) {
      const __mmask8 k = static_cast<__mmask8>(n - m >= 8 ? 0xFF : (1u << (n - m)) - 1);
      const __m256i i = _mm256_maskz_loadu_epi32(k, ch.i + m), j = _mm256_maskz_loadu_epi32(k, ch.j + m);
      _mm512_store_pd(ch.mi + m, _mm512_mask_i32gather_pd(zero, k, i, a.rmass, 8));
      _mm512_store_pd(ch.mj + m, _mm512_mask_i32gather_pd(zero, k, j, a.rmass, 8));
      alignas(32) int ii[8], jj[8];  // lanes past n read atom 0 (unused)
      _mm256_store_si256(reinterpret_cast<__m256i*>(ii), i);
      _mm256_store_si256(reinterpret_cast<__m256i*>(jj), j);
      __m512d ci[3], cj[3];
      rows3(a.v, ii, ci[0], ci[1], ci[2]);
      rows3(a.v, jj, cj[0], cj[1], cj[2]);
      for (int d = 0; d < 3; ++d) _mm512_store_pd(ch.vr[d] + m, _mm512_sub_pd(ci[d], cj[d]));
      if constexpr (kSpin) {
        rows3(a.omega, ii, ci[0], ci[1], ci[2]);
        rows3(a.omega, jj, cj[0], cj[1], cj[2]);
        for (int d = 0; d < 3; ++d) {
          _mm512_store_pd(ch.wi[d] + m, ci[d]);
          _mm512_store_pd(ch.wj[d] + m, cj[d]);
        }
      }
      if constexpr (kGeneral) {
        const __m256i z = _mm256_setzero_si256(), fb = _mm256_set1_epi32(static_cast<int>(a.freeze_bit));
        const int* mask = reinterpret_cast<const int*>(a.mask);
        const __m256i mi = _mm256_mmask_i32gather_epi32(z, k, i, mask, 4);
        const __m256i mj = _mm256_mmask_i32gather_epi32(z, k, j, mask, 4);
        const __m256i one = _mm256_set1_epi32(1), two = _mm256_set1_epi32(2);
        const __m256i fi = _mm256_maskz_mov_epi32(_mm256_test_epi32_mask(mi, fb), one);
        const __m256i fj = _mm256_maskz_mov_epi32(_mm256_test_epi32_mask(mj, fb), two);
        put(ch.frozen + m, _mm256_or_si256(fi, fj));
        const __m256i ti = _mm256_mmask_i32gather_epi32(z, k, i, a.type, 4);
        const __m256i tj = _mm256_mmask_i32gather_epi32(z, k, j, a.type, 4);
        put(ch.itype + m, ti);
        put(ch.jtype + m, tj);
        put(ch.tp + m, _mm256_add_epi32(_mm256_mullo_epi32(ti, _mm256_set1_epi32(a.stride)), tj));
      } else {  // one type (1), nothing frozen
        put(ch.frozen + m, _mm256_setzero_si256());
        put(ch.itype + m, _mm256_set1_epi32(1));
        put(ch.jtype + m, _mm256_set1_epi32(1));
        put(ch.tp + m, _mm256_set1_epi32(a.stride + 1));
      }
      if constexpr (kH == 3) {  // tangential history alone (the common model): a row is three doubles
        alignas(32) int rr[8];
        _mm256_store_si256(reinterpret_cast<__m256i*>(rr), _mm256_maskz_loadu_epi32(k, ch.row + m));
        __m512d h0, h1, h2;
        rows3(b.hist, rr, h0, h1, h2);
        _mm512_store_pd(ch.h[0] + m, h0);
        _mm512_store_pd(ch.h[1] + m, h1);
        _mm512_store_pd(ch.h[2] + m, h2);
      } else if constexpr (kH > 0) {  // 64-bit row offsets: row * kH may pass 2^31 doubles
        const __m512i r = _mm512_mullo_epi64(_mm512_maskz_cvtepi32_epi64(k, _mm256_maskz_loadu_epi32(k, ch.row + m)),
                                             _mm512_set1_epi64(kH));
        for (int q = 0; q < kH; ++q) _mm512_store_pd(ch.h[q] + m, _mm512_mask_i64gather_pd(zero, k, r, b.hist + q, 8));
      }
    }
  }
#endif

  // Stages 1b-3 for the chunk. Not inlined into the filter loop, which then
  // keeps its values in registers.
  // kOwned: the partners are ghosts (several ranks), whose forces nobody reads.
  template <bool kOwned = false>
  [[gnu::noinline]] void flush(const PairBatch& b, Chunk& ch) const {
    gather(b, ch);
    law_.evaluate(ch, b.ctx.dt, b.ctx.update, b.simd, b.a.kinematics());
    if (b.ctx.update)
      scatter_as<true, kOwned>(b, ch);
    else
      scatter_as<false, kOwned>(b, ch);
    ch.n = 0;
  }
  template <bool kUpdate, bool kOwned>
  void scatter_as(const PairBatch& b, const Chunk& ch) const {
    switch (b.a.kinematics()) {
      case Kinematics::Full: return scatter<kUpdate, true, false, kOwned>(b, ch);
      case Kinematics::Plane: return scatter<kUpdate, true, true, kOwned>(b, ch);
      case Kinematics::Frozen: return scatter<kUpdate, false, false, kOwned>(b, ch);
      case Kinematics::PlaneFrozen: return scatter<kUpdate, false, true, kOwned>(b, ch);
    }
  }

  // Stage 3: forces and torques onto the grains in list order; history back.
  // kSpin false: the law made no torque (no rotation), none is added; kPlane:
  // no z force and no in-plane torque (zeros in 2D) are added.
  template <bool kUpdate, bool kSpin, bool kPlane, bool kOwned>
  void scatter(const PairBatch& b, const Chunk& ch) const {
    double* f = b.a.f;
    double* t = b.a.torque;
    [[maybe_unused]] double* hist = b.hist;
    for (int e = 0; e < ch.n; ++e) {
      const int i = ch.i[e], j = ch.j[e];
      for (int d = 0; d < (kPlane ? 2 : 3); ++d) {
        f[3 * i + d] += ch.f[d][e];
        if constexpr (!kOwned) f[3 * j + d] -= ch.f[d][e];
      }
      if constexpr (kSpin) {
        for (int d = kPlane ? 2 : 0; d < 3; ++d) {
          t[3 * i + d] += ch.ti[d][e];
          if constexpr (!kOwned) t[3 * j + d] += ch.tj[d][e];
        }
      }
      if constexpr (kH > 0 && kUpdate) {
        const std::size_t r = static_cast<std::size_t>(ch.row[e]);
        for (int c = 0; c < kH; ++c) hist[r * kH + c] = ch.h[c][e];
      }
    }
  }

  static void store_history(const PairBatch& b, const Chunk& ch) {
    if constexpr (kH > 0) {
      double* hist = b.hist;
      const int n = ch.n;
      if (b.ctx.update)
        for (int m = 0; m < n; ++m)
          for (int q = 0; q < kH; ++q) hist[static_cast<std::size_t>(ch.row[m]) * kH + q] = ch.h[q][m];
    }
  }

  // Phase B (or the whole serial pass, pp null): the entries of atoms [lo, hi)
  // in list order. Threaded, an atom's entries with j >= hi (its last ones,
  // the list being sorted by j) were evaluated in phase A: their slots are
  // added after the range, when each atom's own entries are done.
  void pair_range(const PairBatch& b, int lo, int hi, PairPartition* pp, int t, Chunk& ch) const {
    ch.n = 0;
#if defined(__x86_64__) && defined(__GNUC__)
    if (b.simd == Simd::AVX512)
      pair_entries_avx512(b, lo, hi, pp != nullptr, ch);
    else
#endif
      pair_entries(b, lo, hi, pp != nullptr, ch);
    flush(b, ch);
    if (pp) apply_outgoing(b, *pp, t);
  }

  // Several ranks, threaded: the entries of atoms [lo, hi) whose partner is a ghost
  // (each atom's last ones, j >= n), after the atom's other entries and cross
  // slots, as the one-thread pass takes them; only the owned side is added.
  void ghost_entries(const PairBatch& b, int lo, int hi, Chunk& ch) const {
    const ListView L = list_view(b);
    const int owned = static_cast<int>(b.a.n);
    int n = 0;
    for (int i = lo; i < hi; ++i) {
      int k = b.first[i + 1];
      while (k > b.first[i] && L.jlist[k - 1] >= owned) --k;
      for (; k < b.first[i + 1]; ++k) {
        filter_entry(L, ch, n, i, L.x[3 * i], L.x[3 * i + 1], L.x[3 * i + 2], L.radius[i], k);
        if (n == Chunk::kCap) {
          ch.n = n;
          flush<true>(b, ch);
          n = 0;
        }
      }
    }
    ch.n = n;
    flush<true>(b, ch);
  }

  // Atom i's entries in phase B: all, or (`trim`) those with j < hi.
  static int entries_end(const ListView& L, const int* first, int i, int hi, bool trim) {
    int kend = first[i + 1];
    if (trim)
      while (kend > first[i] && L.jlist[kend - 1] >= hi) --kend;
    return kend;
  }

  // Stage 1 over the entries of atoms [lo, hi), flushing full chunks; the last,
  // partial chunk is left in `ch`.
  void pair_entries(const PairBatch& b, int lo, int hi, bool trim, Chunk& ch) const {
    const ListView L = list_view(b);
    const int* first = b.first;
    int n = 0;
    const int lead = prefetch_lead(b);
    for (int i = lo; i < hi; ++i) {
      if (i + lead < hi) prefetch_atom(b.a, i + lead);
      const double xi = L.x[3 * i], yi = L.x[3 * i + 1], zi = L.x[3 * i + 2], radi = L.radius[i];
      for (int k = first[i], kend = entries_end(L, first, i, hi, trim); k < kend; ++k) {
        filter_entry(L, ch, n, i, xi, yi, zi, radi, k);
        if (n == Chunk::kCap) {
          ch.n = n;
          flush(b, ch);
          n = 0;
        }
      }
    }
    ch.n = n;
  }

#if defined(__x86_64__) && defined(__GNUC__)
  // pair_entries eight entries at a time (AVX-512): partners' positions (rows3)
  // and radii (a gather) read, the touching lanes compressed into the columns. The same
  // arithmetic and tests as filter_entry, so the same contacts in the same
  // order; periodic images and contacts that begin or end (rare) are handled
  // lane by lane, in list order (history rows are taken in the same order).
  // The lanes of `m` packed to the front of 8 values at p (all 8 written: the
  // chunk keeps room; a compressing store to memory is much slower).
  [[gnu::target("avx512f,avx512vl"), gnu::always_inline]] static inline void put8(int* p, __mmask8 m, __m256i v) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), _mm256_maskz_compress_epi32(m, v));
  }
  [[gnu::target("avx512f"), gnu::always_inline]] static inline void put8(double* p, __mmask8 m, __m512d v) {
    _mm512_storeu_pd(p, _mm512_maskz_compress_pd(m, v));
  }
  // Eight consecutive list entries at a time, whatever atoms they belong to
  // (an atom has only a few: one atom per vector would leave most lanes
  // empty): each lane's i from first[] by a few vector compares; with `trim`
  // (phase B), lanes with j >= hi are dropped (an atom's last entries: the
  // list is sorted by j). The same tests in list order: the same contacts.
  [[gnu::target("avx512f,avx512dq,avx512vl,avx512bw")]] void pair_entries_avx512(const PairBatch& b, int lo, int hi,
                                                                                bool trim, Chunk& ch) const {
    const ListView L = list_view(b);
    const int* first = b.first;
    int n = 0;
    const int lead = prefetch_lead(b);
    const int kend = first[hi];
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), one = _mm256_set1_epi32(1);
    const __m256i hiv = _mm256_set1_epi32(trim ? hi : INT32_MAX);
    const __m128i noshift = _mm_set1_epi8(static_cast<char>(NeighborList::kNoShift));
    const __m512d zero = _mm512_setzero_pd();
    int i = lo, pf = lo;  // atom of entry k; atoms prefetched so far
    for (int k = first[lo]; k < kend; k += 8) {
      while (first[i + 1] <= k) ++i;  // (skips atoms without entries)
      if (n > Chunk::kCap - 8) {
        ch.n = n;
        flush(b, ch);
        n = 0;
      }
      const int cnt = std::min(8, kend - k);
      const __mmask8 all = static_cast<__mmask8>((1u << cnt) - 1);
      // lane l's atom: i plus the number of atom starts first[i + 1 ..] <= k + l
      const __m256i kl = _mm256_add_epi32(_mm256_set1_epi32(k), lane);
      __m256i iv = _mm256_set1_epi32(i);
      while (i + 1 < hi && first[i + 1] < k + cnt) {
        ++i;
        iv = _mm256_mask_add_epi32(iv, _mm256_cmpge_epi32_mask(kl, _mm256_set1_epi32(first[i])), iv, one);
      }
      for (; pf <= i && pf + lead < hi; ++pf) prefetch_atom(b.a, pf + lead);
      const __m256i j = _mm256_maskz_loadu_epi32(all, L.jlist + k);
      const __mmask8 m = _mm256_mask_cmplt_epi32_mask(all, j, hiv);
      alignas(32) int ii[8], jj[8];  // lanes past cnt read atom 0 (masked off below)
      _mm256_store_si256(reinterpret_cast<__m256i*>(ii), _mm256_maskz_mov_epi32(all, iv));
      _mm256_store_si256(reinterpret_cast<__m256i*>(jj), j);
      __m512d xi, yi, zi, xj, yj, zj;
      rows3(L.x, ii, xi, yi, zi);
      rows3(L.x, jj, xj, yj, zj);
      const __m128i code = _mm_maskz_loadu_epi8(all, L.shift + k);
      if (_mm_mask_cmpneq_epi8_mask(m, code, noshift)) {  // periodic images: x_j + shift, lane by lane
        alignas(64) double px[8], py[8], pz[8];
        _mm512_store_pd(px, xj);
        _mm512_store_pd(py, yj);
        _mm512_store_pd(pz, zj);
        for (int l = 0; l < cnt; ++l)
          if (((m >> l) & 1) && L.shift[k + l] != NeighborList::kNoShift) {
            const double* sh = L.shift_vec[L.shift[k + l]];
            px[l] += sh[0];
            py[l] += sh[1];
            pz[l] += sh[2];
          }
        xj = _mm512_load_pd(px);
        yj = _mm512_load_pd(py);
        zj = _mm512_load_pd(pz);
      }
      const __m512d dx = _mm512_sub_pd(xi, xj), dy = _mm512_sub_pd(yi, yj), dz = _mm512_sub_pd(zi, zj);
      const __m512d rsq =
          _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz));
      const __m512d radi = _mm512_mask_i32gather_pd(zero, m, iv, L.radius, 8);
      const __m512d radj = _mm512_mask_i32gather_pd(zero, m, j, L.radius, 8);
      const __m512d radsum = _mm512_add_pd(radi, radj);
      const __mmask8 touch = _mm512_mask_cmp_pd_mask(m, rsq, _mm512_mul_pd(radsum, radsum), _CMP_NGE_UQ);
      if constexpr (kH > 0) {
        __m256i r = _mm256_maskz_loadu_epi32(m, L.row + k);
        const __mmask8 has = _mm256_mask_cmpge_epi32_mask(m, r, _mm256_setzero_si256());
        const __mmask8 change = (touch & ~has) | (L.forget ? (m & ~touch & has) : 0);
        if (change) {  // contacts begin (a new, zeroed row) or end (no row), in list order
          for (int l = 0; l < cnt; ++l)
            if ((change >> l) & 1) L.row[k + l] = ((touch >> l) & 1) ? L.store->new_row() : ContactStore::kNone;
          r = _mm256_maskz_loadu_epi32(m, L.row + k);
        }
        put8(ch.row + n, touch, r);
      }
      put8(ch.i + n, touch, iv);
      put8(ch.j + n, touch, j);
      put8(ch.dx + n, touch, dx);
      put8(ch.dy + n, touch, dy);
      put8(ch.dz + n, touch, dz);
      put8(ch.radi + n, touch, radi);
      put8(ch.radj + n, touch, radj);
      n += __builtin_popcount(touch);
    }
    ch.n = n;
  }
#endif

  // Partners j > i lie up to `span` atoms ahead, a slab of bins, and are read
  // there for the first time since the last pass: irregular reads (touching
  // pairs only) that the hardware does not prefetch, and out of cache once N
  // outgrows it. So each atom's state is requested `lead` atoms before the
  // first i that can need it (x and radius, read for every entry, need no help).
  static int prefetch_lead(const PairBatch& b) { return b.span + 16; }
  [[gnu::always_inline]] static inline void prefetch_atom(const AtomView& a, int p) {
    __builtin_prefetch(a.v + 3 * p);
    __builtin_prefetch(a.omega + 3 * p);
    __builtin_prefetch(a.rmass + p);
    __builtin_prefetch(a.f + 3 * p, 1);
    __builtin_prefetch(a.torque + 3 * p, 1);
  }

  // Phase A of range u: the cross entries whose j lies in it, the touching
  // ones into rows of its slots.
  void cross_range(const PairBatch& b, PairPartition& pp, int u, Chunk& ch) const {
    const ListView L = list_view(b);
    PairPartition::Slots& out = pp.slots[u];
    if (pp.rehome) rehome_rows(b, pp, u);
    int n = 0, rows = 0, t = 0;
    for (int q = pp.in_first[u]; q < pp.in_first[u + 1]; ++q) {
      const int s = pp.in_s[q];
      while (t < u && s >= pp.cross_first[t + 1]) out.at[++t] = rows;  // range t's entries start here
      const int i = pp.cross_i[s], k = pp.cross_k[s];
      const int before = n;
      filter_entry(L, ch, n, i, L.x[3 * i], L.x[3 * i + 1], L.x[3 * i + 2], L.radius[i], k);
      pp.on[s] = static_cast<std::uint8_t>(n != before);
      ch.slot[before] = rows;
      rows += n != before;
      if (n == Chunk::kCap) {
        ch.n = n;
        cross_flush(b, out, ch);
        n = 0;
      }
    }
    while (t < u) out.at[++t] = rows;
    ch.n = n;
    cross_flush(b, out, ch);
  }

  // A new list's cross entries' history to rows of this thread's own (the
  // same values). The list hands out rows in list order, so a cross entry's
  // row sat among those of i's other contacts, which i's thread rewrites at
  // every step as this one rewrites it: each line went between the cores
  // twice a step.
  static void rehome_rows(const PairBatch& b, const PairPartition& pp, int u) {
    if constexpr (kH > 0) {
      if (!b.store) return;
      double* rows = b.store->rows();
      const std::size_t w = static_cast<std::size_t>(b.store->size);
      for (int q = pp.in_first[u]; q < pp.in_first[u + 1]; ++q) {
        int& r = b.row[pp.cross_k[pp.in_s[q]]];
        if (r < 0) continue;
        const int moved = b.store->new_row();
        std::copy(rows + r * w, rows + (r + 1) * w, rows + moved * w);
        r = moved;
      }
    }
  }

  [[gnu::noinline]] void cross_flush(const PairBatch& b, PairPartition::Slots& out, Chunk& ch) const {
    gather(b, ch);
    law_.evaluate(ch, b.ctx.dt, b.ctx.update, b.simd, b.a.kinematics());
    const bool spin = b.a.rotation;  // else no torque columns: the slots' torques are zeros
    for (int m = 0; m < ch.n; ++m) {
      const std::size_t r = static_cast<std::size_t>(ch.slot[m]);
      double* fi = &out.fi[6 * r];
      double* tj = &out.tj[3 * r];
      for (int d = 0; d < 3; ++d) {
        fi[d] = ch.f[d][m];
        fi[3 + d] = spin ? ch.ti[d][m] : 0.0;
        tj[d] = spin ? ch.tj[d][m] : 0.0;
      }
    }
    store_history(b, ch);
    ch.n = 0;
  }

  // Phase B, last: the i-side of range t's own cross entries, in list order,
  // once the later ranges' phase A has filled their slots.
  void apply_outgoing(const PairBatch& b, PairPartition& pp, int t) const {
    const int s0 = pp.cross_first[t], s1 = pp.cross_first[t + 1];
    if (s0 == s1) return;
    const long pass = pp.pass;
    for (int u = t + 1; u < pp.nparts; ++u)
      for (int spins = 0; pp.done_a[u].load(std::memory_order_acquire) != pass; ++spins)
        if (spins > 1000) std::this_thread::yield();  // more threads than cores
    int* next = &pp.cursor[pp.cursor_stride() * static_cast<std::size_t>(t)];
    for (int u = t + 1; u < pp.nparts; ++u) next[u - t - 1] = pp.slots[u].at[t];
    double* f = b.a.f;
    double* tq = b.a.torque;
    for (int s = s0; s < s1; ++s) {
      if (!pp.on[s]) continue;
      const int u = pp.cross_u[s], i = pp.cross_i[s];
      const double* fi = &pp.slots[u].fi[6 * static_cast<std::size_t>(next[u - t - 1]++)];
      for (int d = 0; d < 3; ++d) {
        f[3 * i + d] += fi[d];
        tq[3 * i + d] += fi[3 + d];
      }
    }
  }

  // Phase B, first: j-side contributions of cross entries to the atoms of
  // range t (evaluated by this thread in phase A). They come from earlier
  // ranges; taken in list order, each atom receives its own in list order, as
  // in the serial pass.
  void apply_incoming(const PairBatch& b, const PairPartition& pp, int t) const {
    double* f = b.a.f;
    double* tq = b.a.torque;
    const PairPartition::Slots& in = pp.slots[t];
    std::size_t r = 0;
    for (int q = pp.in_first[t]; q < pp.in_first[t + 1]; ++q) {
      const int s = pp.in_s[q];
      if (!pp.on[s]) continue;
      const int a = pp.cross_j[s];
      const double* fi = &in.fi[6 * r];
      const double* tj = &in.tj[3 * r];
      ++r;
      for (int d = 0; d < 3; ++d) {
        f[3 * a + d] -= fi[d];
        tq[3 * a + d] += tj[d];
      }
    }
  }

  // Ranges balanced by work: entries, touching ones counting 3 more, weighted
  // by the cost per weight each range took since the last split (cache misses,
  // threads slowed by the machine), re-split as soon as kLearnCalls passes show
  // the ranges more than 4 % apart: on a shared host one core can run at half
  // speed for 10-50 passes and then recover. A re-split costs a search per
  // bound and one look per atom for the cross entries, so following the host
  // is cheap. Any split gives the same bits.
  static constexpr int kLearnCalls = 3;  // passes measured before a re-split
  void plan_partition(const PairBatch& b, int nparts) {
    PairPartition& pp = part_;
    const std::size_t n = b.a.n, ne = static_cast<std::size_t>(b.first[n]);
    const bool same_list = pp.version == b.list_version && pp.nparts == nparts && pp.natoms == n && pp.nentries == ne;
    if (same_list && !(pp.calls >= kLearnCalls && unbalanced(pp))) return;
    learn_costs(pp);
    pp.version = b.list_version;
    pp.nparts = nparts;
    pp.natoms = n;
    pp.nentries = ne;
    if (!same_list) {  // weights in parallel, then their running sum
      pp.cum.resize(n + 1);
      pp.cum[0] = 0.0;
      const long nl = static_cast<long>(n);
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(nparts)
#endif
      for (long i = 0; i < nl; ++i) {
        int touching = 0;  // an integer count: no chain of dependent floating-point adds
        if constexpr (kH > 0)
          for (int k = b.first[i]; k < b.first[i + 1]; ++k) touching += b.row[k] >= 0;
        pp.cum[i + 1] = 1.0 + (b.first[i + 1] - b.first[i]) + 3.0 * touching;
      }
      for (std::size_t i = 0; i < n; ++i) pp.cum[i + 1] += pp.cum[i];
    }
    split(pp, nparts);
    cross_lists(b, pp);
    pp.rehome = !same_list;
    pp.busy.assign(nparts, 0.0);
    pp.calls = 0;
  }

  static bool unbalanced(const PairPartition& pp) {
    const auto [lo, hi] = std::minmax_element(pp.busy.begin(), pp.busy.end());
    return *hi > 1.04 * *lo;
  }

  // Seconds per unit of weight in each range since the last split.
  static void learn_costs(PairPartition& pp) {
    const int np = static_cast<int>(pp.busy.size());
    if (pp.calls < kLearnCalls || np != pp.nparts || pp.cum.size() != pp.natoms + 1 || pp.cum.back() <= 0.0) return;
    const double total = pp.cum.back();
    pp.seg_u.assign(np + 1, 1.0);
    pp.seg_d.assign(np, 0.0);
    for (int t = 0; t < np; ++t) {
      const double w = pp.cum[pp.lo[t + 1]] - pp.cum[pp.lo[t]];
      pp.seg_u[t] = pp.cum[pp.lo[t]] / total;
      pp.seg_d[t] = w > 0.0 ? pp.busy[t] / w : 0.0;
    }
    const double mean = std::accumulate(pp.busy.begin(), pp.busy.end(), 0.0) / total;
    for (double& d : pp.seg_d) d = d > 0.0 ? d : mean;  // an empty range: no measurement
    if (mean <= 0.0) pp.seg_u.clear();
  }

  // Range bounds with equal predicted time: weight times the learned cost of
  // its place (as a fraction of the total weight); equal weight before any.
  // The predicted time of the weight [0, c) is piecewise linear in c (slope
  // seg_d on each learned segment), so each bound is found by a search, with
  // no pass over the atoms.
  static void split(PairPartition& pp, int nparts) {
    const std::size_t n = pp.natoms;
    const double total = pp.cum[n];
    const std::size_t nseg = pp.seg_u.size() >= 2 && total > 0.0 ? pp.seg_d.size() : 0;
    std::vector<double> t0(nseg + 1, 0.0);  // predicted time at each segment's start
    for (std::size_t s = 0; s < nseg; ++s) t0[s + 1] = t0[s] + pp.seg_d[s] * (pp.seg_u[s + 1] - pp.seg_u[s]) * total;
    const double whole = nseg ? t0[nseg] : total;
    pp.lo.assign(nparts + 1, 0);
    for (int t = 1; t < nparts; ++t) {
      const double target = whole * t / nparts;
      double c = target;  // the weight whose predicted time is `target`
      if (nseg) {
        const std::size_t s = std::min<std::size_t>(std::upper_bound(t0.begin(), t0.end(), target) - t0.begin(), nseg) - 1;
        c = pp.seg_u[s] * total + (target - t0[s]) / pp.seg_d[s];
      }
      pp.lo[t] = static_cast<int>(std::lower_bound(pp.cum.begin(), pp.cum.end(), c) - pp.cum.begin());
      pp.lo[t] = std::clamp(pp.lo[t], pp.lo[t - 1], static_cast<int>(n));
    }
    pp.lo[nparts] = static_cast<int>(n);
  }

  // Cross entries (j in a later range) of each range, in list order. An atom's
  // entries are sorted by j, so its cross entries are a suffix, present only
  // when its last j lies beyond the range: one look per atom, cheap enough to
  // re-split whenever the threads drift apart.
  static void cross_lists(const PairBatch& b, PairPartition& pp) {
    const int nparts = pp.nparts;
    pp.cross_k.clear();
    pp.cross_i.clear();
    pp.cross_j.clear();
    pp.cross_first.assign(nparts + 1, 0);
    for (int t = 0; t + 1 < nparts; ++t) {
      const int hi = pp.lo[t + 1];
      const int owned = static_cast<int>(b.a.n);
      for (int i = pp.lo[t]; i < hi; ++i) {
        int k1 = b.first[i + 1];
        const int k0 = b.first[i];
        while (k1 > k0 && b.jlist[k1 - 1] >= owned) --k1;  // ghost partners: ghost_entries
        if (k1 == k0 || b.jlist[k1 - 1] < hi) continue;
        int k = k1;
        while (k > k0 && b.jlist[k - 1] >= hi) --k;
        for (; k < k1; ++k) {
          pp.cross_k.push_back(k);
          pp.cross_i.push_back(i);
          pp.cross_j.push_back(b.jlist[k]);
        }
      }
      pp.cross_first[t + 1] = static_cast<int>(pp.cross_k.size());
    }
    const int ncross = static_cast<int>(pp.cross_k.size());
    pp.cross_first[nparts] = ncross;
    // Each range's incoming entries, by a counting sort on j's range (stable:
    // list order within each).
    pp.cross_u.resize(ncross);
    pp.in_first.assign(nparts + 1, 0);
    for (int s = 0; s < ncross; ++s) {
      pp.cross_u[s] = static_cast<int>(std::upper_bound(pp.lo.begin(), pp.lo.end(), pp.cross_j[s]) - pp.lo.begin()) - 1;
      ++pp.in_first[pp.cross_u[s] + 1];
    }
    for (int u = 0; u < nparts; ++u) pp.in_first[u + 1] += pp.in_first[u];
    pp.in_s.resize(ncross);
    std::vector<int> at(pp.in_first.begin(), pp.in_first.end() - 1);
    for (int s = 0; s < ncross; ++s) pp.in_s[at[pp.cross_u[s]]++] = s;
    pp.on.resize(ncross);  // each entry's, and its slot row, written in phase A
    pp.slots.resize(nparts);
    for (int u = 0; u < nparts; ++u) {
      const std::size_t m = static_cast<std::size_t>(pp.in_first[u + 1] - pp.in_first[u]);
      pp.slots[u].fi.resize(6 * m);
      pp.slots[u].tj.resize(3 * m);
      pp.slots[u].at.assign(nparts, 0);
    }
    pp.cursor.resize(pp.cursor_stride() * static_cast<std::size_t>(nparts));
    if (pp.done_a.size() < static_cast<std::size_t>(nparts)) pp.done_a = std::vector<std::atomic<long>>(nparts);  // zeroed
  }

  // Wall contacts: gathered into columns and evaluated like pair contacts
  // (stage 2 above); forces added to the grains and written to b.force.
  void wall_forces_staged(const WallBatch& b) const {
    const AtomView& a = b.a;
    WallChunk<kH> ch;
    for (std::size_t k0 = 0; k0 < b.n; k0 += WallChunk<kH>::kCap) {
      wall_gather(b, k0, ch);
      law_.evaluate(ch, b.ctx.dt, b.ctx.update, b.simd, a.kinematics());
      for (int m = 0; m < ch.n; ++m) {
        const std::size_t k = k0 + m;
        const int i = b.atom[k];
        for (int d = 0; d < 3; ++d) {
          a.f[3 * i + d] += ch.f[d][m];
          if (a.rotation) a.torque[3 * i + d] += ch.ti[d][m];
          b.force[3 * k + d] = ch.f[d][m];
        }
        if constexpr (kH > 0)
          if (b.ctx.update) {
            double* h = b.hist + static_cast<std::size_t>(b.hist_index[k]) * b.hist_stride;
            for (int q = 0; q < kH; ++q) h[q] = ch.h[q][m];
          }
      }
    }
  }

  // Wall contacts [k0, k0 + kCap) of the batch into the columns.
  static void wall_gather(const WallBatch& b, std::size_t k0, WallChunk<kH>& ch) {
    const AtomView& a = b.a;
    ch.tp0 = a.stride > 2 ? -1 : a.stride + b.wall_type;  // one atom type (1): one type pair
    const int n = static_cast<int>(std::min<std::size_t>(WallChunk<kH>::kCap, b.n - k0));
    ch.n = n;
    for (int m = 0; m < n; ++m) {
      const std::size_t k = k0 + m;
      const int i = b.atom[k];
      for (int d = 0; d < 3; ++d) {
        ch.en[d][m] = b.en[3 * k + d];
        ch.vr[d][m] = a.v[3 * i + d] - b.vwall[3 * k + d];
        ch.wi[d][m] = a.omega[3 * i + d];  // (read only with rotation)
      }
      ch.deltan[m] = b.deltan[k];
      ch.radi[m] = a.radius[i];
      ch.mi[m] = a.rmass[i];
      ch.itype[m] = a.type[i];
      ch.jtype[m] = b.wall_type;
      ch.tp[m] = a.type[i] * a.stride + b.wall_type;
      if constexpr (kH > 0) {
        const double* h = b.hist + static_cast<std::size_t>(b.hist_index[k]) * b.hist_stride;
        for (int q = 0; q < kH; ++q) ch.h[q][m] = h[q];
      }
    }
  }

  // Appends the columns' contacts as records (the chunk evaluated without update).
  template <class Cols>
  static void append_records(const Cols& ch, ContactRecords& out, int j_or_wall, const int* i_of, const int* j_of,
                             const int* shift_of) {
    for (int m = 0; m < ch.n; ++m) {
      Contact c;
      ch.contact(m, c);  // the kinematics the law saw: overlap and normal
      ContactRecord r{i_of[m], j_of ? j_of[m] : j_or_wall, shift_of[m], {ch.f[0][m], ch.f[1][m], ch.f[2][m]},
                      {ch.ti[0][m], ch.ti[1][m], ch.ti[2][m]}, c.deltan, {c.en[0], c.en[1], c.en[2]}};
      out.rows.push_back(r);
      for (int q = 0; q < kH; ++q) out.hist.push_back(ch.h[q][m]);
    }
  }

};

// Per-contact records at the current state (compute pair/gran/local): the
// touching entries whose grains are both in b.groupbit, in list order,
// evaluated as the force pass does; history is copied, never written.
template <int kH>
void ContactLoopT<kH>::pair_records(const PairBatch& b, ContactRecords& out) {
  out.clear();
  out.hist_size = kH;
  const AtomView& a = b.a;
  Chunk ch;
  int shift[Chunk::kCap];
  // Each contact's history (zeros without a row) copied to row m of a local
  // table, which the gather then reads: the store is never touched.
  std::vector<double> rows(static_cast<std::size_t>(Chunk::kCap) * (kH > 0 ? kH : 1), 0.0);
  PairBatch local = b;
  local.hist = rows.data();
  ch.n = 0;
  auto flush_records = [&] {
    gather(local, ch);
    law_.evaluate(ch, b.ctx.dt, false, b.simd, Kinematics::Full);
    append_records(ch, out, 0, ch.i, ch.j, shift);
    ch.n = 0;
  };
  for (std::size_t i = 0; i < a.n; ++i) {
    if (!(a.mask[i] & b.groupbit)) continue;
    for (int k = b.first[i]; k < b.first[i + 1]; ++k) {
      const int j = b.jlist[k];
      const double* sh = b.shift_vec[b.shift[k]];
      const double dx = a.x[3 * i] - (a.x[3 * j] + sh[0]), dy = a.x[3 * i + 1] - (a.x[3 * j + 1] + sh[1]),
                   dz = a.x[3 * i + 2] - (a.x[3 * j + 2] + sh[2]);
      const double rsq = dx * dx + dy * dy + dz * dz, radsum = a.radius[i] + a.radius[j];
      if (rsq >= radsum * radsum || !(a.mask[j] & b.groupbit)) continue;
      const int m = ch.n++;
      ch.i[m] = static_cast<int>(i);
      ch.j[m] = j;
      ch.dx[m] = dx;
      ch.dy[m] = dy;
      ch.dz[m] = dz;
      ch.radi[m] = a.radius[i];
      ch.radj[m] = a.radius[j];
      if constexpr (kH > 0) {
        ch.row[m] = m;
        const int r = b.row[k];
        for (int q = 0; q < kH; ++q) rows[static_cast<std::size_t>(m) * kH + q] = r < 0 ? 0.0 : b.hist[static_cast<std::size_t>(r) * kH + q];
      }
      shift[m] = b.shift[k];
      if (ch.n == Chunk::kCap) flush_records();
    }
  }
  if (ch.n) flush_records();
}

// Per-contact records of wall contacts (compute wall/gran/local); history is copied, never written.
template <int kH>
void ContactLoopT<kH>::wall_records(const WallBatch& b, ContactRecords& out) const {
  out.clear();
  out.hist_size = kH;
  WallChunk<kH> ch;
  int atom[WallChunk<kH>::kCap], index[WallChunk<kH>::kCap];
  for (std::size_t k0 = 0; k0 < b.n; k0 += WallChunk<kH>::kCap) {
    wall_gather(b, k0, ch);
    law_.evaluate(ch, b.ctx.dt, false, b.simd, Kinematics::Full);
    for (int m = 0; m < ch.n; ++m) {
      atom[m] = b.atom[k0 + m];
      index[m] = static_cast<int>(k0 + m);
    }
    append_records(ch, out, -1, atom, nullptr, index);
  }
}

}  // namespace

template <int kH>
std::unique_ptr<ContactLoop> make_contact_loop(const ColumnLaw<kH>& law) {
  return std::make_unique<ContactLoopT<kH>>(law);
}
template std::unique_ptr<ContactLoop> make_contact_loop<0>(const ColumnLaw<0>&);
template std::unique_ptr<ContactLoop> make_contact_loop<1>(const ColumnLaw<1>&);
template std::unique_ptr<ContactLoop> make_contact_loop<2>(const ColumnLaw<2>&);
template std::unique_ptr<ContactLoop> make_contact_loop<3>(const ColumnLaw<3>&);
template std::unique_ptr<ContactLoop> make_contact_loop<4>(const ColumnLaw<4>&);
template std::unique_ptr<ContactLoop> make_contact_loop<5>(const ColumnLaw<5>&);
template std::unique_ptr<ContactLoop> make_contact_loop<6>(const ColumnLaw<6>&);
template std::unique_ptr<ContactLoop> make_contact_loop<7>(const ColumnLaw<7>&);
template std::unique_ptr<ContactLoop> make_contact_loop<8>(const ColumnLaw<8>&);
template std::unique_ptr<ContactLoop> make_contact_loop<9>(const ColumnLaw<9>&);

}  // namespace sable
