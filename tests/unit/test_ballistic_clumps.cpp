// ballistic_deposit ... clump beta B [body ID] (issue 44 item 1): ballistic
// deposition of petit2017's 3-disk clumps (Appendix B, Fig. 15) in a 2D box
// periodic in x. Checked on the deposit itself: each clump's geometry (an
// equilateral triangle of side r = 2 beta R, one R per clump), body IDs and
// image counters, no overlap between clumps (periodic images included), every
// clump touching the floor or an earlier clump, most at rest on contacts either
// side of their centre of mass, seeds, counts, errors.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "core/engine/error.h"
#include "tests/unit/ballistic_scene.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_ballistic_clumps {

using sable::test::Deck;
using sable::test::error_of;

namespace {

struct Disk {
  double x, y, r;
  long id;
  int ix;
  double body;
};

// A 2D box [0, W] x [0, H], x periodic, radii gaussian mean 1, sigma 0.5 cut at
// +-1 sigma (delta 0.5), the body IDs in fix property/atom bid.
std::string deck(double W, double H, double beta, const std::string& count, long seed = 32452843,
                 const std::string& extra = " body bid") {
  return sable::test::ballistic_box(W, H) +
         "fix pt all particletemplate/sphere 15485863 density constant 2650 radius gaussian number 1.0 0.5 cut 1\n"
         "fix bid all property/atom bodyid scalar no no no 0\n"
         "ballistic_deposit " + count + " pt seed " + std::to_string(seed) + " clump beta " + std::to_string(beta) +
         extra + "\n";
}

std::vector<Disk> disks(Deck& d) {
  std::vector<Disk> out;
  const auto& a = d->atoms;
  const int h = a.find_column("f_bid");
  for (std::size_t i = 0; i < a.n; ++i)
    out.push_back({a.x[3 * i], a.x[3 * i + 1], a.radius[i], a.id[i], a.image[3 * i], h >= 0 ? a.column(h)[i] : 0.0});
  return out;
}

// Centre distance of i and j over ri + rj, j's x image nearest i's.
double gap(const Disk& i, const Disk& j, double W, double* jx = nullptr) {
  return sable::test::periodic_gap(i, j, W, jx);
}

// Clump k: disks 3k, 3k+1, 3k+2 (consecutive IDs).
long clump_of(std::size_t i) { return static_cast<long>(i / 3); }

// Smallest gap between disks of different clumps; the floor (y = 0) as r / y.
double min_gap(const std::vector<Disk>& g, double W) {
  double worst = 1e300;
  for (std::size_t i = 0; i < g.size(); ++i) {
    worst = std::min(worst, g[i].y / g[i].r);
    for (std::size_t j = i + 1; j < g.size(); ++j)
      if (clump_of(i) != clump_of(j)) worst = std::min(worst, gap(g[i], g[j], W));
  }
  return worst;
}

// Largest deviation of a clump's mutual centre distances from 2 beta R (and
// of its radii from one another), unwrapped with the image counters.
double geometry_error(const std::vector<Disk>& g, double W, double beta) {
  double worst = 0;
  for (std::size_t k = 0; k + 2 < g.size(); k += 3) {
    const double R = g[k].r, r = 2 * beta * R;
    for (int m = 0; m < 3; ++m) {
      const Disk& p = g[k + m];
      const Disk& q = g[k + (m + 1) % 3];
      worst = std::max(worst, std::abs(p.r - R));
      const double d = std::hypot((p.x + p.ix * W) - (q.x + q.ix * W), p.y - q.y);
      worst = std::max(worst, std::abs(d - r));
    }
  }
  return worst;
}

// Per clump: does it touch (within 1e-9 relative) the floor or an earlier
// clump (unsupported counts those that do not), and do its contacts lie on both
// sides of its centre of mass in x (or one straight below it)? `straddling`
// counts those.
long unsupported(const std::vector<Disk>& g, double W, long* straddling = nullptr) {
  long bad = 0, both = 0;
  for (std::size_t k = 0; k + 2 < g.size(); k += 3) {
    double X = 0;  // centroid x, each disk's image next to disk k
    for (int m = 0; m < 3; ++m) X += g[k + m].x + W * std::round((g[k].x - g[k + m].x) / W);
    X /= 3;
    bool touch = false, left = false, right = false;
    for (int m = 0; m < 3; ++m) {
      const Disk& a = g[k + m];
      const double ax = a.x + W * std::round((g[k].x - a.x) / W);  // a's image next to disk k's
      if (std::abs(a.y - a.r) <= 1e-9 * a.r) {
        touch = true;
        left |= ax <= X, right |= ax >= X;
      }
      for (std::size_t j = 0; j < k; ++j) {
        double jx;
        if (std::abs(gap(a, g[j], W, &jx) - 1) > 1e-9) continue;
        touch = true;
        const double px = a.x + a.r / (a.r + g[j].r) * (jx - a.x) + (ax - a.x);
        left |= px <= X, right |= px >= X;
      }
    }
    bad += !touch;
    both += left && right;
  }
  if (straddling) *straddling = both;
  return bad;
}

}  // namespace

// 200 clumps at each of petit2017's angularities (0.25, 0.62, 0.90) and at the
// touching limit 1: geometry to 1e-12, consecutive IDs with one body ID per
// clump, no overlap between clumps or with the floor, every clump touching the
// floor or an earlier clump, at least 90 % at rest on contacts either side of
// the centre of mass (the rest wedged: see the command's header).
TEST(BallisticClumps, GeometryNoOverlapSupported) {
  for (double beta : {0.25, 0.62, 0.9, 1.0}) {
    Deck d;
    d(deck(40, 200, beta, "200"));
    const auto g = disks(d);
    ASSERT_EQ(g.size(), 600u) << beta;
    EXPECT_LE(geometry_error(g, 40, beta), 1e-12) << beta;
    for (std::size_t i = 0; i < g.size(); ++i) {
      EXPECT_EQ(g[i].id, static_cast<long>(i) + 1);
      EXPECT_EQ(g[i].body, static_cast<double>(clump_of(i) + 1));
      EXPECT_GE(g[i].x, 0.0);
      EXPECT_LT(g[i].x, 40.0);
      EXPECT_GE(g[i].r, 0.5);
      EXPECT_LE(g[i].r, 1.5);
    }
    EXPECT_GE(min_gap(g, 40), 1 - 1e-9) << beta;
    long straddling = 0;
    EXPECT_EQ(unsupported(g, 40, &straddling), 0) << beta;
    EXPECT_GE(straddling, 180) << beta;
    std::printf("beta %.2f: %ld of 200 clumps on contacts either side of the centre of mass\n", beta, straddling);
    for (std::size_t i = 0; i < d->atoms.n; ++i)
      for (int k = 0; k < 3; ++k) ASSERT_EQ(d->atoms.v[3 * i + k], 0.0);
  }
}

// The checks above can fail: one disk moved 1e-9 breaks the geometry; a clump
// moved down 1e-6 overlaps; the last clump lifted 1e-6 touches nothing.
TEST(BallisticClumps, CheckersCatchBrokenPackings) {
  Deck d;
  d(deck(30, 100, 0.62, "100"));
  auto g = disks(d);
  ASSERT_EQ(unsupported(g, 30), 0);
  auto moved = g;
  moved[151].x += 1e-9;
  EXPECT_GT(geometry_error(moved, 30, 0.62), 1e-12);
  moved = g;
  bool caught = false;
  for (std::size_t k = 0; k < 100 && !caught; ++k) {  // some clump touching one below it
    moved = g;
    for (int m = 0; m < 3; ++m) moved[3 * k + m].y -= 1e-6;
    caught = min_gap(moved, 30) < 1 - 1e-9;
  }
  EXPECT_TRUE(caught);
  moved = g;
  for (int m = 0; m < 3; ++m) moved[297 + m].y += 1e-6;
  EXPECT_EQ(unsupported(moved, 30), 1);
}

// A clump across the periodic boundary: its image counters unwrap it (fix
// rigid/small reads them); some clumps do cross in 300.
TEST(BallisticClumps, ImageCountersUnwrapClumps) {
  Deck d;
  d(deck(25, 200, 0.9, "300"));
  const auto g = disks(d);
  long crossing = 0;
  for (std::size_t k = 0; k < g.size(); k += 3) crossing += g[k].ix != 0 || g[k + 1].ix != 0 || g[k + 2].ix != 0;
  EXPECT_GT(crossing, 5);
  EXPECT_LE(geometry_error(g, 25, 0.9), 1e-12);
  EXPECT_GE(min_gap(g, 25), 1 - 1e-9);
  EXPECT_EQ(unsupported(g, 25), 0);
}

TEST(BallisticClumps, SameSeedSamePackingOtherSeedOther) {
  Deck a, b, c;
  a(deck(30, 120, 0.62, "150", 32452843));
  b(deck(30, 120, 0.62, "150", 32452843));
  c(deck(30, 120, 0.62, "150", 32452867));
  const auto ga = disks(a), gb = disks(b), gc = disks(c);
  ASSERT_EQ(ga.size(), gb.size());
  long same = 0;
  for (std::size_t i = 0; i < ga.size(); ++i) {
    EXPECT_EQ(ga[i].x, gb[i].x);
    EXPECT_EQ(ga[i].y, gb[i].y);
    EXPECT_EQ(ga[i].r, gb[i].r);
    EXPECT_EQ(ga[i].ix, gb[i].ix);
    same += ga[i].x == gc[i].x;
  }
  EXPECT_EQ(same, 0);
}

// fill: until the next clump would stick out; a second deposit (disks) lands on
// the clumps and a second clump deposit continues the body IDs.
TEST(BallisticClumps, FillAndSecondDeposit) {
  Deck d;
  d(deck(30, 60, 0.62, "fill"));
  const auto g = disks(d);
  EXPECT_GT(g.size(), 300u);
  EXPECT_EQ(g.size() % 3, 0u);
  double top = 0;
  for (const auto& k : g) top = std::max(top, k.y + k.r);
  EXPECT_LE(top, 60.0);
  EXPECT_GT(top, 50.0);
  EXPECT_EQ(unsupported(g, 30), 0);

  Deck e;
  e(deck(30, 120, 0.62, "100") + "ballistic_deposit 50 pt seed 32452867 clump beta 0.25 body bid\n");
  const auto h = disks(e);
  ASSERT_EQ(h.size(), 450u);
  EXPECT_EQ(h.back().body, 150.0);
  EXPECT_GE(min_gap(h, 30), 1 - 1e-9);
  EXPECT_EQ(unsupported(h, 30), 0);
  // Without 'body' the IDs still number the clumps: (id - 1) / 3.
  Deck f;
  f(deck(30, 120, 0.62, "10", 32452843, ""));
  EXPECT_EQ(f->atoms.n, 30u);
}

TEST(BallisticClumps, BadInput) {
  {
    Deck d;
    d("units si\natom_style granular\nboundary p f p\nregion box block 0 40 0 20 0 10 units box\ncreate_box 1 box\n"
      "fix pt all particletemplate/sphere 15485863 density constant 1 radius constant 1\n");
    const std::string e = error_of(d, "ballistic_deposit 10 pt seed 32452843 clump beta 0.5");
    EXPECT_NE(e.find("a 2D box"), std::string::npos) << e;
  }
  Deck d;
  d("units si\natom_style granular\ndimension 2\nboundary p f p\n"
    "region box block 0 40 0 20 -0.5 0.5 units box\ncreate_box 1 box\n"
    "fix pt all particletemplate/sphere 15485863 density constant 1 radius constant 1\n"
    "fix bid all property/atom bodyid scalar no no no 0\nfix bv all property/atom v vector no no no 0 0\n");
  for (const char* b : {"0", "-0.3", "1.01", "nan"}) {
    const std::string e = error_of(d, std::string("ballistic_deposit 10 pt seed 32452843 clump beta ") + b);
    EXPECT_NE(e.find("beta"), std::string::npos) << b << ": " << e;
  }
  std::string e = error_of(d, "ballistic_deposit 10 pt seed 32452843 clump 0.5");
  EXPECT_NE(e.find("'beta B' after clump"), std::string::npos) << e;
  e = error_of(d, "ballistic_deposit 10 pt seed 32452843 clump beta");
  EXPECT_NE(e.find("beta"), std::string::npos) << e;
  e = error_of(d, "ballistic_deposit 10 pt seed 32452843 body bid");
  EXPECT_NE(e.find("'body' only with 'clump beta B'"), std::string::npos) << e;
  e = error_of(d, "ballistic_deposit 10 pt seed 32452843 clump beta 0.5 body pt");
  EXPECT_NE(e.find("scalar fix property/atom"), std::string::npos) << e;
  e = error_of(d, "ballistic_deposit 10 pt seed 32452843 clump beta 0.5 body bv");
  EXPECT_NE(e.find("scalar fix property/atom"), std::string::npos) << e;
  e = error_of(d, "ballistic_deposit 10 pt seed 32452843 clump beta 0.5 body nope");
  EXPECT_NE(e.find("scalar fix property/atom"), std::string::npos) << e;
  e = error_of(d, "ballistic_deposit 10 pt seed 32452843 clump beta 0.5 spin 3");
  EXPECT_NE(e.find("seed, floor, clump, body"), std::string::npos) << e;
  e = error_of(d, "ballistic_deposit 200 pt seed 32452843 clump beta 0.5");
  EXPECT_NE(e.find("above the box top"), std::string::npos) << e;
  d("fix big all particletemplate/sphere 15485867 density constant 1 radius constant 2.6");
  e = error_of(d, "ballistic_deposit 10 big seed 32452843 clump beta 0.5");
  EXPECT_NE(e.find("wider than 16 largest radii"), std::string::npos) << e;
  EXPECT_EQ(d->atoms.n, 0u);
}

}  // namespace test_ballistic_clumps
