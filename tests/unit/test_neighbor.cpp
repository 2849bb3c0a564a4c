// The half Verlet list against an O(N^2) search over periodic images (and the
// order of each atom's entries), and contact history carried across rebuilds,
// sorting and periodic wraps.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <tuple>

#include "core/engine/atoms.h"
#include "core/engine/domain.h"
#include "core/engine/neighbor.h"
#include "tests/unit/neighbor_pairs.h"

#ifdef _OPENMP
#include <omp.h>

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_neighbor {
#endif

using namespace sable;
using sable::test::brute;
using sable::test::listed;
using sable::test::random_moves;
using sable::test::Scene;

namespace {

// Random polydisperse grains in a box with the given periodicity.
void fill(Scene& s, int dim, bool px, bool py, bool pz, int n, unsigned seed) {
  s.domain.dimension = dim;
  s.domain.periodic[0] = px;
  s.domain.periodic[1] = py;
  s.domain.periodic[2] = pz;
  s.domain.lo[0] = s.domain.lo[1] = s.domain.lo[2] = 0.0;
  s.domain.hi[0] = 1.0;
  s.domain.hi[1] = 0.8;
  s.domain.hi[2] = dim == 3 ? 0.6 : 0.1;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < n; ++i) {
    double x[3] = {u(rng) * 1.0, u(rng) * 0.8, dim == 3 ? u(rng) * 0.6 : 0.0};
    s.atoms.add(i + 1, 1, x, 0.01 + 0.02 * u(rng), 2500.0);
  }
  s.neighbor.skin = 0.005;
}

}  // namespace

// Bins of a sparse scene are capped at ~8 per atom. In a tall thin box (4 cm wide,
// 1e12 m high: a fuzzed deck) the short axes keep one bin each and the cap falls
// on the tall one; spreading it over all three axes asked for ~1e11 bins.
TEST(Neighbor, TallThinBoxKeepsTheBinCap) {
  Scene s;
  s.domain.lo[0] = s.domain.lo[1] = -0.02;
  s.domain.hi[0] = s.domain.hi[1] = 0.02;
  s.domain.lo[2] = 0.0;
  s.domain.hi[2] = 1e12;
  const double a[3] = {0, 0, 0.01}, b[3] = {0, 0.0019, 0.01}, c[3] = {0, 0, 5e11};
  s.atoms.add(1, 1, a, 0.001, 2500.0);
  s.atoms.add(2, 1, b, 0.001, 2500.0);
  s.atoms.add(3, 1, c, 0.001, 2500.0);
  s.neighbor.skin = 0.0005;
  s.neighbor.build(s.atoms, s.domain, nullptr, 0);
  EXPECT_EQ(listed(s), brute(s));
  EXPECT_EQ(s.neighbor.list.size(), 1u);
}

class NeighborVsBruteForce : public ::testing::TestWithParam<std::tuple<int, bool, bool, bool>> {};

TEST_P(NeighborVsBruteForce, SamePairsAfterRandomMoves) {
  auto [dim, px, py, pz] = GetParam();
  Scene s;
  fill(s, dim, px, py, pz, dim == 3 ? 600 : 300, 7);
  for (int round = 0; round < 4; ++round) {
    s.neighbor.build(s.atoms, s.domain, nullptr, round);
    // brute force sees the wrapped positions the list was built from
    const auto expected = brute(s);
    EXPECT_GT(expected.size(), 50u) << "scene too sparse to test anything";
    EXPECT_EQ(listed(s), expected) << "round " << round;
    // Each atom's entries by partner, then image: the threaded force pass takes
    // an atom's entries into a later thread's range as its last ones.
    const NeighborList& l = s.neighbor.list;
    for (std::size_t i = 0; i < s.atoms.n; ++i)
      for (int k = l.first[i] + 1; k < l.first[i + 1]; ++k)
        ASSERT_TRUE(l.j[k - 1] < l.j[k] || (l.j[k - 1] == l.j[k] && l.shift[k - 1] < l.shift[k]))
            << "atom " << i << " entries " << k - 1 << ", " << k << " out of order (round " << round << ")";
    random_moves(s, 100 + round, 0.05);
  }
}

INSTANTIATE_TEST_SUITE_P(Boxes, NeighborVsBruteForce,
                         ::testing::Values(std::make_tuple(3, false, false, false), std::make_tuple(3, true, true, true),
                                           std::make_tuple(3, true, false, true), std::make_tuple(2, false, false, true),
                                           std::make_tuple(2, true, true, true), std::make_tuple(2, true, false, true)));

// A flat periodic bed (40 x 40 x 4 bins): sorted with the short axis fastest,
// a grain's partners lie within a 40 x 4-bin slab ahead (about n / 40 atoms),
// not a 40 x 40-bin layer (n / 4). The force pass prefetches `span` atoms ahead.
TEST(Neighbor, SortKeepsPartnersWithinASlabOfTheShortAxes) {
  Scene s;
  s.domain.periodic[0] = s.domain.periodic[1] = true;
  s.domain.hi[0] = s.domain.hi[1] = 1.0;
  s.domain.hi[2] = 0.1;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const double x[3] = {u(rng), u(rng), 0.1 * u(rng)};
    s.atoms.add(i + 1, 1, x, 0.01, 2500.0);
  }
  s.neighbor.skin = 0.005;  // cutoff 0.025: 40 x 40 x 4 bins
  s.neighbor.build(s.atoms, s.domain, nullptr, 0);
  const NeighborList& l = s.neighbor.list;
  int span = 0;
  for (int i = 0; i < n; ++i)
    for (int k = l.first[i]; k < l.first[i + 1]; ++k)
      if (l.shift[k] == NeighborList::kNoShift) span = std::max(span, l.j[k] - i);
  EXPECT_GT(l.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(l.span, span);
  EXPECT_LT(span, n / 8) << "partners spread over a whole layer: the longest axis is not the slowest";
}

TEST(Neighbor, RebuildDecisionFollowsHalfSkin) {
  Scene s;
  fill(s, 3, false, false, false, 50, 3);
  s.neighbor.build(s.atoms, s.domain, nullptr, 0);
  EXPECT_FALSE(s.neighbor.decide(s.atoms, 1));
  s.atoms.x[0] += 0.49 * s.neighbor.skin;
  EXPECT_FALSE(s.neighbor.decide(s.atoms, 2));
  s.atoms.x[0] += 0.02 * s.neighbor.skin;  // now beyond skin/2
  EXPECT_TRUE(s.neighbor.decide(s.atoms, 3));
  s.neighbor.delay = 10;
  EXPECT_FALSE(s.neighbor.decide(s.atoms, 3));  // within the delay
  s.neighbor.delay = 0;
  s.atoms.x[0] -= 0.51 * s.neighbor.skin;  // back where it was built: no rebuild ...
  EXPECT_FALSE(s.neighbor.decide(s.atoms, 4));
  s.atoms.x[4] = std::nan("");  // ... but a position turned NaN: rebuild (which checks positions)
  EXPECT_TRUE(s.neighbor.decide(s.atoms, 4));
  s.atoms.x[4] = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(s.neighbor.decide(s.atoms, 5));
}

// With varying radii (fix adapt) a pair's gap also closes by both growths: grain
// i may move skin/2 - dr_i (LIGGGHTS' rule), and a change of radius beyond skin/2
// rebuilds alone. Another grain's growth does not shorten i's room.
TEST(Neighbor, RebuildDecisionCountsEachGrainsGrowth) {
  Scene s;
  fill(s, 3, false, false, false, 50, 3);
  s.neighbor.radii_vary = true;
  s.neighbor.build(s.atoms, s.domain, nullptr, 0);
  const double skin = s.neighbor.skin;
  s.atoms.radius[0] += 0.2 * skin;
  s.atoms.x[0] += 0.29 * skin;
  EXPECT_FALSE(s.neighbor.decide(s.atoms, 1));
  s.atoms.x[0] += 0.02 * skin;  // 0.31 skin + 0.2 skin > skin/2
  EXPECT_TRUE(s.neighbor.decide(s.atoms, 2));
  s.atoms.x[0] -= 0.31 * skin;
  s.atoms.x[3] += 0.45 * skin;  // grain 1 moved 0.45 skin, grain 0 grew 0.2 skin: each within its room
  EXPECT_FALSE(s.neighbor.decide(s.atoms, 3));
  s.atoms.x[3] -= 0.45 * skin;
  s.atoms.radius[0] -= 0.2 * skin;
  s.atoms.radius[1] -= 0.51 * skin;  // shrunk beyond skin/2
  EXPECT_TRUE(s.neighbor.decide(s.atoms, 4));
  s.atoms.radius[1] += 0.51 * skin;
  EXPECT_FALSE(s.neighbor.decide(s.atoms, 5));
  s.atoms.radius[2] = std::nan("");
  EXPECT_TRUE(s.neighbor.decide(s.atoms, 6));
}

TEST(ContactStore, HistorySurvivesRebuildSortAndPeriodicWrap) {
  // Two touching grains straddling the periodic x boundary, plus a third far away.
  Scene s;
  s.domain.periodic[0] = s.domain.periodic[1] = s.domain.periodic[2] = true;
  s.domain.hi[0] = s.domain.hi[1] = s.domain.hi[2] = 1.0;
  const double a[3] = {0.995, 0.5, 0.5}, b[3] = {0.012, 0.5, 0.5}, c[3] = {0.5, 0.5, 0.5};
  s.atoms.add(1, 1, a, 0.01, 1000);
  s.atoms.add(2, 1, b, 0.01, 1000);
  s.atoms.add(3, 1, c, 0.01, 1000);
  s.neighbor.skin = 0.002;
  ContactStore store;
  store.configure({{"shearx", true}, {"sheary", true}, {"count", false}});
  s.neighbor.build(s.atoms, s.domain, &store, 0);
  ASSERT_EQ(s.neighbor.list.size(), 1u);
  // Record history as seen from the listed orientation.
  const int k = 0;
  const long idi = [&] {
    for (std::size_t i = 0; i < s.atoms.n; ++i)
      if (s.neighbor.list.first[i + 1] > k && s.neighbor.list.first[i] <= k) return s.atoms.id[i];
    return -1L;
  }();
  double* h = store.begin_contact(k);
  h[0] = 0.25;
  h[1] = -0.5;
  h[2] = 7.0;
  // Move grain 1 across the boundary (it wraps to the low side) and rebuild: the
  // orientation of the pair in the list may change; flagged slots flip with it.
  for (std::size_t i = 0; i < s.atoms.n; ++i)
    if (s.atoms.id[i] == 1) s.atoms.x[3 * i] += 0.01;
  s.neighbor.build(s.atoms, s.domain, &store, 10);
  ASSERT_EQ(s.neighbor.list.size(), 1u);
  const double* h1 = store.history(0);
  ASSERT_NE(h1, nullptr);
  long now_i = -1;
  for (std::size_t i = 0; i < s.atoms.n; ++i)
    if (s.neighbor.list.first[i + 1] > 0 && s.neighbor.list.first[i] <= 0) now_i = s.atoms.id[i];
  const double sign = now_i == idi ? 1.0 : -1.0;
  EXPECT_EQ(h1[0], sign * 0.25);
  EXPECT_EQ(h1[1], sign * -0.5);
  EXPECT_EQ(h1[2], 7.0);  // not flagged: never flips
  // The wrapped grain is back inside the box with its image counter advanced.
  for (std::size_t i = 0; i < s.atoms.n; ++i)
    if (s.atoms.id[i] == 1) {
      EXPECT_LT(s.atoms.x[3 * i], 0.1);
      EXPECT_EQ(s.atoms.image[3 * i], 1);
    }
  // Separate the grains: after the next rebuild the pair is gone, and so is its history.
  for (std::size_t i = 0; i < s.atoms.n; ++i)
    if (s.atoms.id[i] == 2) s.atoms.x[3 * i] = 0.3;
  s.neighbor.build(s.atoms, s.domain, &store, 20);
  EXPECT_EQ(s.neighbor.list.size(), 0u);
}

// Contacts that begin and end many times between rebuilds use up rows; the
// compaction before a force pass must keep each entry's history and never let
// a pass run out of rows (one new contact per entry at most).
TEST(ContactStore, CompactionKeepsEachEntrysHistory) {
  ContactStore s;
  s.configure({{"a", false}, {"b", true}});
  const std::size_t entries = 5;
  s.resize(entries);
  std::vector<double> expect(entries, -1.0);  // -1: not in contact
  int compactions = 0;
  for (int pass = 0; pass < 200; ++pass) {
    const std::size_t before = s.rows_used();
    s.make_room();
    compactions += s.rows_used() < before;
    ASSERT_LE(s.rows_used() + entries, s.capacity()) << "pass " << pass;
    for (std::size_t k = 0; k < entries; ++k) {
      if ((pass + k) % 3 == 0 && s.row[k] >= 0) {  // contact ends
        s.row[k] = ContactStore::kNone;
        expect[k] = -1.0;
      } else if (s.row[k] < 0) {  // contact begins
        double* h = s.begin_contact(k);
        EXPECT_EQ(h[0], 0.0);
        EXPECT_EQ(h[1], 0.0);
        h[0] = h[1] = expect[k] = 100.0 * pass + k;
      }
    }
    for (std::size_t k = 0; k < entries; ++k) {
      const double* h = s.history(k);
      ASSERT_EQ(h != nullptr, expect[k] >= 0) << "entry " << k << " pass " << pass;
      if (h) {
        EXPECT_EQ(h[1], expect[k]);
      }
    }
  }
  EXPECT_GT(compactions, 5);
  EXPECT_EQ(s.contacts(), static_cast<std::size_t>(std::count_if(expect.begin(), expect.end(), [](double v) { return v >= 0; })));
}

#ifdef _OPENMP
// Two threads starting contacts in strict alternation (the worst case: with
// one shared row counter every cache line of new rows would hold rows of both,
// which both then rewrite at every step) get rows from blocks of their own:
// distinct, zeroed, within capacity, and few cache lines shared.
TEST(ContactStore, ThreadsTakeRowsInBlocksOfTheirOwn) {
  ContactStore s;
  s.configure({{"a", false}, {"b", true}, {"c", true}});
  const std::size_t entries = 4000;
  s.resize(entries);
  s.make_room();
  std::atomic<int> turn{0};
#pragma omp parallel num_threads(2)
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    for (std::size_t k = t; k < entries; k += 2) {
      while (nt == 2 && turn.load() % 2 != t) {
      }
      double* h = s.begin_contact(k);
      EXPECT_TRUE(h[0] == 0.0 && h[1] == 0.0 && h[2] == 0.0);
      h[0] = h[1] = h[2] = static_cast<double>(k);
      turn.fetch_add(1);
    }
  }
  EXPECT_LE(s.rows_used(), s.capacity());
  std::set<int> rows;
  std::set<std::uintptr_t> lines[2];  // 64-byte lines each thread's rows touch
  for (std::size_t k = 0; k < entries; ++k) {
    ASSERT_GE(s.row[k], 0);
    rows.insert(s.row[k]);
    const double* h = s.history(k);
    EXPECT_EQ(h[2], static_cast<double>(k));  // no row written by two contacts
    for (int m = 0; m < 3; ++m) lines[k % 2].insert(reinterpret_cast<std::uintptr_t>(h + m) / 64);
  }
  EXPECT_EQ(rows.size(), entries);
  std::size_t shared = 0;
  for (std::uintptr_t l : lines[0]) shared += lines[1].count(l);
  // At most the two ends of each block; alternating single rows shared ~all of
  // the 1500 lines.
  EXPECT_LE(shared, 2 * (s.rows_used() / 64 + 1)) << "of " << lines[0].size() << " lines";
}
#endif

// Grains on a cubic lattice filling the part of the box [0, L) below `top` on
// each axis: spacing 0.0125, radius 0.003, skin 0.019, so the bins are
// 0.025-0.026 wide and hold two lattice layers each (box lengths 0.51, 0.11,
// 0.36: 20, 4 and 14 bins).
Scene lattice(const double L[3], const double top[3], bool px, bool py, bool pz) {
  Scene s;
  s.domain.dimension = 3;
  const bool per[3] = {px, py, pz};
  for (int k = 0; k < 3; ++k) {
    s.domain.periodic[k] = per[k];
    s.domain.lo[k] = 0.0;
    s.domain.hi[k] = L[k];
  }
  long id = 0;
  for (double x = 0.00625; x < top[0]; x += 0.0125)
    for (double y = 0.00625; y < top[1]; y += 0.0125)
      for (double z = 0.00625; z < top[2]; z += 0.0125) {
        const double p[3] = {x, y, z};
        s.atoms.add(++id, 1, p, 0.003, 2500.0);
      }
  s.neighbor.skin = 0.019;
  return s;
}

// The threads' ranges are contiguous in bin order, so the slowest bin axis is
// the one they cut across: among the axes with the most bins (within 20 %),
// the one whose middle slab holds the fewest grains. A drum's bed (20 x 20 x
// 4 bins, grains in half the box along x, periodic along its thin z) is cut
// across y, where a slab holds half as many grains as across x; the same bed
// turned (half the box along y) across x. A flat bed periodic along x and y
// (20 x 20 x 14 bins, grains in the lower 12) keeps x or y, although its z
// slab (1/12 of the grains) is thinner than theirs (1/20, counted twice: the
// ranges meet again across the wrap): z has too few bins for the cache order.
TEST(Neighbor, SlowestBinAxisCutsTheThinnestSlab) {
  const double drum[3] = {0.51, 0.51, 0.11}, half_x[3] = {0.25, 0.51, 0.11}, half_y[3] = {0.51, 0.25, 0.11};
  Scene a = lattice(drum, half_x, false, false, true);
  a.neighbor.build(a.atoms, a.domain, nullptr, 0);
  EXPECT_EQ(a.neighbor.slow_axis(), 1);
  Scene t = lattice(drum, half_y, false, false, true);
  t.neighbor.build(t.atoms, t.domain, nullptr, 0);
  EXPECT_EQ(t.neighbor.slow_axis(), 0);
  const double box[3] = {0.51, 0.51, 0.36}, bed[3] = {0.51, 0.51, 0.3};
  Scene b = lattice(box, bed, true, true, false);
  b.neighbor.build(b.atoms, b.domain, nullptr, 0);
  EXPECT_NE(b.neighbor.slow_axis(), 2);
}

}  // namespace test_neighbor
