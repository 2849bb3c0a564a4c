#pragma once
// A reduction core provides to fixes: the sum of N-vectors over items with a
// position in a fixed order (an atom index, a contact's place in a wall's
// near list), taken in fixed blocks of that order: each block's items in
// order, then the blocks in order. Threads add the items of their own
// contiguous ranges of positions (any split); an item in a block that began
// in an earlier range is kept and added in finish(), after that range's. The
// total has the bits of one serial pass for any thread count.
//
//   sum.begin(npos, block, nranges);                          serial
//   sum.range(r, lo); sum.add(r, pos, v) ...                  range r, positions from lo, increasing
//   sum.finish(total);                                        serial
//   sum.total(total);                                         or on any thread, once every range is added
//
// AtomSum below is the form a fix's per-atom task asks for: positions are atom
// indices, the ranges the task's (Fix::AtomRange), block and range count core's.
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "core/engine/fix.h"
#include "core/engine/threads.h"

namespace sable {

template <int N>
class BlockSum {
 public:
  void begin(std::size_t npos, std::size_t block, int nranges) {
    block_ = std::max<std::size_t>(block, 1);
    sums_.assign((npos + block_ - 1) / block_, std::array<double, N>{});
    if (carry_.size() < static_cast<std::size_t>(nranges)) carry_.resize(nranges);
    for (Carry& c : carry_) c.clear();
  }
  // Range r's first position: a block it shares with an earlier range is carried.
  void range(int r, std::size_t lo) {
    Carry& c = carry_[r];
    c.clear();
    c.cut = lo % block_ != 0;
    c.block = lo / block_;
  }
  void add(int r, std::size_t pos, const double* v) {
    const std::size_t b = pos / block_;
    Carry& c = carry_[r];
    if (c.cut && b == c.block) {
      c.v.insert(c.v.end(), v, v + N);
    } else {
      for (int k = 0; k < N; ++k) sums_[b][k] += v[k];
    }
  }
  void finish(double* out) const { total(out); }
  // Each block's own items, then its carried ones (ranges in position order), then
  // the blocks in order. Reads only: every thread may take it in a second phase.
  void total(double* out) const {
    for (int k = 0; k < N; ++k) out[k] = 0.0;
    for (std::size_t b = 0; b < sums_.size(); ++b) {
      std::array<double, N> s = sums_[b];
      for (const Carry& c : carry_)
        if (c.block == b)
          for (std::size_t q = 0; q < c.v.size(); ++q) s[q % N] += c.v[q];
      for (int k = 0; k < N; ++k) out[k] += s[k];
    }
  }

 private:
  struct alignas(64) Carry {  // own cache lines: each thread grows its own
    bool cut = false;
    std::size_t block = 0;
    std::vector<double> v;  // N per item, in order
    void clear() {
      v.clear();
      cut = false;
    }
  };
  std::size_t block_ = 1;
  std::vector<std::array<double, N>> sums_;
  std::vector<Carry> carry_;
};

// A sum of N-vectors over atoms, for a fix's per-atom task: begin() in the
// task's begin(), range() first in each range(), add() per atom, total() in
// end() or in phase 1 of a two-phase task. The same bits for any thread count.
template <int N>
class AtomSum {
 public:
  void begin(std::size_t natoms) { sum_.begin(natoms, kBlock, atom_pass_threads()); }
  void range(const Fix::AtomRange& r) { sum_.range(r.thread, r.lo); }
  void add(const Fix::AtomRange& r, std::size_t i, const double* v) { sum_.add(r.thread, i, v); }
  void total(double* out) const { sum_.total(out); }

 private:
  static constexpr std::size_t kBlock = 1024;
  BlockSum<N> sum_;
};

}  // namespace sable
