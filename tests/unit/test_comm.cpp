// The processor grid (core/engine/comm.h): LAMMPS' `processors` with '*' chooses the
// factorisation with the least subdomain surface; explicit counts must multiply to the
// rank count; the subdomains tile the box exactly; the grid line after the box.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "core/engine/atoms.h"
#include "core/engine/comm.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_comm {

using sable::Comm;
using sable::Grid;
using sable::choose_grid;
using sable::test::Deck;
using sable::test::error_of;
using sable::test::printed;

namespace {

const Grid kFree{0, 0, 0};

double surface(const std::array<double, 3>& l, const Grid& g) {
  const double a = l[0] / g[0], b = l[1] / g[1], c = l[2] / g[2];
  return a * b + b * c + c * a;
}

// Every factorisation of n into three counts.
std::vector<Grid> factorisations(int n) {
  std::vector<Grid> out;
  for (int x = 1; x <= n; ++x)
    for (int y = 1; x * y <= n; ++y)
      if (n % (x * y) == 0) out.push_back({x, y, n / (x * y)});
  return out;
}

sable::Domain box(std::array<double, 3> lo, std::array<double, 3> hi, int dimension = 3) {
  sable::Domain d;
  for (int k = 0; k < 3; ++k) d.lo[k] = lo[k], d.hi[k] = hi[k];
  d.dimension = dimension;
  d.box_exists = true;
  return d;
}

}  // namespace

TEST(Comm, WithoutMpiStartedIsRankZeroOfOne) {
  const Comm c;  // the unit tests never call MPI_Init
  EXPECT_EQ(c.rank(), 0);
  EXPECT_EQ(c.size(), 1);
}

TEST(Comm, ElongatedBoxSplitsAlongItsLongAxis) {
  EXPECT_EQ(choose_grid(4, {1, 1, 4}, kFree, 3), (Grid{1, 1, 4}));
  EXPECT_EQ(choose_grid(4, {4, 1, 1}, kFree, 3), (Grid{4, 1, 1}));
  EXPECT_EQ(choose_grid(8, {2, 2, 2}, kFree, 3), (Grid{2, 2, 2}));
  EXPECT_EQ(choose_grid(1, {1, 5, 3}, kFree, 3), (Grid{1, 1, 1}));
  EXPECT_EQ(choose_grid(7, {1, 1, 1}, kFree, 3), (Grid{1, 1, 7}));  // a prime: the first of three ties
}

// Six ranks in a cube: 1 x 2 x 3 and its permutations tie; the least surface wins and
// the tie goes to the first in Px, then Py order.
TEST(Comm, SixRanksInACubeTakeTheLeastSurface) {
  const std::array<double, 3> cube{1, 1, 1};
  const Grid g = choose_grid(6, cube, kFree, 3);
  Grid sorted = g;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, (Grid{1, 2, 3}));
  for (const Grid& other : factorisations(6)) EXPECT_LE(surface(cube, g), surface(cube, other) * (1 + 1e-12));
  EXPECT_EQ(g, (Grid{1, 2, 3}));
}

// Against every factorisation, on boxes of several shapes and rank counts.
TEST(Comm, ChosenGridHasTheLeastSurfaceOfAll) {
  for (const std::array<double, 3> l : {std::array<double, 3>{1, 2, 3}, {10, 1, 1}, {0.3, 0.3, 2.1}, {5, 5, 0.5}})
    for (int n = 1; n <= 24; ++n) {
      const Grid g = choose_grid(n, l, kFree, 3);
      ASSERT_EQ(g[0] * g[1] * g[2], n);
      for (const Grid& other : factorisations(n)) EXPECT_LE(surface(l, g), surface(l, other) * (1 + 1e-12)) << n;
    }
}

TEST(Comm, FixedCountsAndTwoDimensions) {
  EXPECT_EQ(choose_grid(4, {4, 4, 1}, {0, 0, 1}, 3), (Grid{2, 2, 1}));
  EXPECT_EQ(choose_grid(6, {1, 1, 1}, {0, 0, 6}, 3), (Grid{1, 1, 6}));
  EXPECT_EQ(choose_grid(4, {1, 1, 10}, kFree, 2), (Grid{2, 2, 1}));  // 2D: never along z
  EXPECT_EQ(choose_grid(6, {1, 1, 1}, {4, 0, 0}, 3), (Grid{0, 0, 0}));  // 4 does not divide 6
}

// The subdomains tile the box: the outer faces are the box's, inner faces shared to the bit.
// Every rank's Comm of an n-rank run, each decomposed over d.
std::vector<Comm> ranks_over(const sable::Domain& d, int n) {
  std::vector<Comm> ranks;
  for (int r = 0; r < n; ++r) {
    ranks.emplace_back(r, n);
    ranks.back().decompose(d);
  }
  return ranks;
}

TEST(Comm, SubdomainsCoverTheBoxExactly) {
  const sable::Domain d = box({-0.3, 0.1, 1e-3}, {1.7, 0.4, 2.9});
  const int n = 12;
  const std::vector<Comm> ranks = ranks_over(d, n);
  const Grid g = ranks[0].grid;
  ASSERT_EQ(g[0] * g[1] * g[2], n);
  double volume = 0;
  for (const Comm& c : ranks) {
    EXPECT_EQ(c.grid, g);
    EXPECT_EQ(c.coord[0] + g[0] * (c.coord[1] + g[1] * c.coord[2]), c.rank());
    volume += (c.subhi[0] - c.sublo[0]) * (c.subhi[1] - c.sublo[1]) * (c.subhi[2] - c.sublo[2]);
    for (int k = 0; k < 3; ++k) {
      if (c.coord[k] == 0) {
        EXPECT_EQ(c.sublo[k], d.lo[k]);
      }
      if (c.coord[k] == g[k] - 1) {
        EXPECT_EQ(c.subhi[k], d.hi[k]);
      }
      EXPECT_LT(c.sublo[k], c.subhi[k]);
      for (const Comm& o : ranks) {  // the next one along k starts where this one ends
        Grid next = c.coord;
        ++next[k];
        if (o.coord == next) {
          EXPECT_EQ(o.sublo[k], c.subhi[k]);
        }
      }
    }
  }
  EXPECT_NEAR(volume, d.volume(), 1e-12 * d.volume());
}

TEST(Comm, GridLineAfterTheBox) {
  Deck d;
  const std::string out = printed("region box block 0 1 0 1 0 4 units box\ncreate_box 1 box", d);
  EXPECT_NE(out.find("  1 by 1 by 1 MPI processor grid\n"), std::string::npos) << out;
}

// The deck's grid meets the rank count (a Comm of 4 or 3 ranks put in place).
TEST(Comm, ProcessorsCommandSetsTheGrid) {
  Deck d;
  d->comm = Comm(1, 4);
  d("processors * * 1\nregion box block 0 4 0 4 0 4 units box\ncreate_box 1 box");
  EXPECT_EQ(d->comm.grid, (Grid{2, 2, 1}));
  EXPECT_EQ(d->comm.coord, (Grid{1, 0, 0}));
  EXPECT_EQ(d->comm.sublo[0], 2.0);
  EXPECT_EQ(d->comm.subhi[1], 2.0);
  EXPECT_EQ(d->comm.grid_line(), "  2 by 2 by 1 MPI processor grid");
}

TEST(Comm, ProcessorsErrorsNameLineAndWord) {
  Deck d;
  d->comm = Comm(0, 3);
  EXPECT_EQ(error_of(d, "processors 2 1 1"),
            "test:1: '2' in 'processors 2 1 1': expected counts whose product is the number of MPI ranks, 3 "
            "(2 x 1 x 1; '*' lets sable choose)");
  EXPECT_NE(error_of(d, "processors * 2 *").find("test:1: '2' in 'processors * 2 *': expected counts whose product "
                                                   "divides the number of MPI ranks, 3"),
            std::string::npos);
  EXPECT_NE(error_of(d, "processors 0 * *").find("'0' in 'processors 0 * *': expected a processor count >= 1 or *"),
            std::string::npos);
  EXPECT_NE(error_of(d, "processors * * * map xyz").find("'map' in"), std::string::npos);
  EXPECT_EQ(error_of(d, "processors * * 3"), "(no error)");
  d("region box block 0 1 0 1 0 1 units box\ncreate_box 1 box");
  EXPECT_EQ(d->comm.grid, (Grid{1, 1, 3}));
  EXPECT_NE(error_of(d, "processors * * *").find("processors must come before the box is created"),
            std::string::npos);
}

TEST(Comm, TwoDimensionalBoxKeepsOneLayer) {
  Deck d;
  d->comm = Comm(0, 2);
  d("dimension 2");
  EXPECT_NE(error_of(d, "processors 1 1 2").find("'2' in 'processors 1 1 2': expected 1 or * (Pz of a 2D box)"),
            std::string::npos);
  Deck e;  // processors before dimension: refused when the box is made
  e->comm = Comm(0, 2);
  e("processors 1 1 2\ndimension 2\nregion box block 0 1 0 1 -0.5 0.5 units box");
  EXPECT_EQ(error_of(e, "create_box 1 box"), "test:1: Pz = 2 in a 2D box: expected 1 or *");
}

// Every position belongs to the rank whose subdomain holds it, faces to the bit
// (the lower face is the subdomain's, the upper the next one's), the box's top face
// to the last rank.
TEST(Comm, OwnerOfAPositionIsTheRankWhoseSubdomainHoldsIt) {
  const sable::Domain d = box({-0.3, 0.1, 1e-3}, {1.7, 0.4, 2.9});
  const std::vector<Comm> ranks = ranks_over(d, 12);
  for (const Comm& c : ranks) {
    const double mid[3] = {0.5 * (c.sublo[0] + c.subhi[0]), 0.5 * (c.sublo[1] + c.subhi[1]),
                           0.5 * (c.sublo[2] + c.subhi[2])};
    EXPECT_EQ(ranks[0].owner_of(mid, d), c.rank());
    EXPECT_EQ(ranks[5].owner_of(c.sublo, d), c.rank());
    for (int k = 0; k < 3; ++k) {
      double x[3] = {mid[0], mid[1], mid[2]};
      x[k] = c.subhi[k];
      const int next = ranks[0].owner_of(x, d);
      if (c.subhi[k] == d.hi[k]) {
        EXPECT_EQ(next, c.rank());
      } else {
        EXPECT_EQ(ranks[next].sublo[k], c.subhi[k]);
        EXPECT_NE(next, c.rank());
      }
    }
  }
}

// Ghosts sit after the owned atoms; a record carries every column; an owned atom's
// index wins over a ghost copy of the same id; adding an atom drops the ghosts.
TEST(Comm, GhostsFollowTheOwnedAtomsAndCarryEveryColumn) {
  sable::Atoms a;
  const int col = a.add_column("extra", 2, 7.0);
  const double x0[3] = {1, 2, 3}, x1[3] = {4, 5, 6};
  a.add(11, 1, x0, 0.5, 2000);
  a.add(12, 2, x1, 0.25, 3000);
  a.v[3] = -1.5;
  a.column(col)[3] = 9.0;
  std::vector<double> rec;
  a.pack(1, rec);
  ASSERT_EQ(rec.size(), a.record_size());
  const std::size_t g = a.add_ghosts(2);
  EXPECT_EQ(g, 2u);
  EXPECT_EQ(a.n, 2u);
  EXPECT_EQ(a.nall(), 4u);
  a.unpack(2, rec.data());
  rec[0] = 11;  // a ghost copy of the owned atom 11
  a.unpack(3, rec.data());
  EXPECT_EQ(a.id[2], 12);
  EXPECT_EQ(a.type[2], 2);
  EXPECT_EQ(a.x[3 * 2 + 1], 5.0);
  EXPECT_EQ(a.v[3 * 2], -1.5);
  EXPECT_EQ(a.radius[2], 0.25);
  EXPECT_EQ(a.column(col)[2 * 2 + 1], 9.0);
  EXPECT_EQ(a.index_of(11), 0u);
  EXPECT_EQ(a.index_of(12), 1u);
  a.add(13, 1, x0, 0.5, 2000);
  EXPECT_EQ(a.nghost, 0u);
  EXPECT_EQ(a.x.size(), 9u);
  EXPECT_EQ(a.column(col).size(), 6u);
}

// balance ... shift (Comm::rebalance) on rank 0 of a 2-rank grid along z, before the grains
// are split (every rank holds them all, as here): 90 grains spread over z in [0, 0.4] and 30
// over [0.8, 1]. Even counts put the cut between the 60th and the 61st grain from below
// (z = 0.2644 and 0.2689); a ghost cutoff of 0.6 (wider than half the box) leaves it at 0.5.
TEST(Comm, BalanceShiftCutsWhereTheGrainsSplitEvenly) {
  Deck d;
  d->comm = Comm(0, 2);
  d("processors 1 1 2\nregion box block 0 1 0 1 0 1 units box\ncreate_box 1 box");
  for (int i = 0; i < 120; ++i) {
    const double z = i < 90 ? (i + 0.5) / 90 * 0.4 : 0.8 + (i - 90 + 0.5) / 30 * 0.2;
    const double x[3] = {0.5, 0.5, z};
    d->atoms.add(i + 1, 1, x, 0.001, 2500);
  }
  EXPECT_EQ(d->comm.imbalance(d->comm.grains_per_rank(*d)), 1.5);  // 90 below the middle
  d("neighbor 0.001 bin\nbalance 1.1 shift z 5 1.1");
  const double cut = d->comm.face_at(d->domain, 2, 1);
  EXPECT_GT(cut, (59 + 0.5) / 90 * 0.4);
  EXPECT_LT(cut, (60 + 0.5) / 90 * 0.4);
  EXPECT_EQ(d->comm.grains_per_rank(*d), (std::vector<double>{60, 60}));
  EXPECT_EQ(d->comm.subhi[2], cut);
  d("balance 1.1 shift z 5 1.1");  // balanced now: the cuts stay
  EXPECT_EQ(d->comm.face_at(d->domain, 2, 1), cut);
  d->atoms.radius.assign(120, 0.2995);  // ghost cutoff 2 x 0.2995 + 0.001 = 0.6
  d->comm.cut[2].clear();
  d->comm.split(d->domain);
  d->comm.rebalance(*d, 1.0, "z");
  EXPECT_EQ(d->comm.face_at(d->domain, 2, 1), 0.5);
}

}  // namespace test_comm
