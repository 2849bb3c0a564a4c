// ballistic_deposit (issue 44 item 1): frictionless ballistic deposition of
// disks in a 2D box periodic in x. Checked on the deposit itself: radius
// moments, no overlap (periodic images included), every disk at rest on the
// floor or on two earlier disks on either side of its centre, seeds,
// packing fraction, errors.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/engine/error.h"
#include "tests/unit/ballistic_scene.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_ballistic_deposit {

using sable::test::Deck;
using sable::test::error_of;

namespace {

struct Disk {
  double x, y, r;
  long id;
};

// A 2D box [0, W] x [0, H], x periodic, one template (mean radius 1).
std::string deck(double W, double H, double sigma, const std::string& count, long seed = 32452843,
                 const std::string& radius_extra = " cut 1") {
  const std::string radius = sigma > 0 ? "radius gaussian number 1.0 " + std::to_string(sigma) + radius_extra
                                       : "radius constant 1.0";
  return sable::test::ballistic_box(W, H) +
         "fix pt all particletemplate/sphere 15485863 density constant 2650 " + radius + "\n" +
         "ballistic_deposit " + count + " pt seed " + std::to_string(seed) + "\n";
}

std::vector<Disk> disks(Deck& d) {
  std::vector<Disk> out;
  const auto& a = d->atoms;
  for (std::size_t i = 0; i < a.n; ++i) out.push_back({a.x[3 * i], a.x[3 * i + 1], a.radius[i], a.id[i]});
  return out;
}

// Centre distance of i and j over ri + rj, j's x image nearest i's (the box is
// wider than 4 radii, so no disk touches two images of another).
double gap(const Disk& i, const Disk& j, double W, double* jx = nullptr) {
  return sable::test::periodic_gap(i, j, W, jx);
}

double min_gap(const std::vector<Disk>& g, double W) {
  double worst = 1e300;
  for (std::size_t i = 0; i < g.size(); ++i)
    for (std::size_t j = i + 1; j < g.size(); ++j) worst = std::min(worst, gap(g[i], g[j], W));
  return worst;
}

// Number of disks not at rest: neither on the floor (y = r within 1e-9 r) nor
// touching (within 1e-9 relative) an earlier disk on each side of its centre.
long unsupported(const std::vector<Disk>& g, double W, long* on_floor = nullptr) {
  long bad = 0, floor = 0;
  for (std::size_t i = 0; i < g.size(); ++i) {
    if (std::abs(g[i].y - g[i].r) <= 1e-9 * g[i].r) {
      ++floor;
      continue;
    }
    bool left = false, right = false;
    for (std::size_t j = 0; j < g.size(); ++j) {
      if (g[j].id >= g[i].id) continue;
      double jx;
      if (std::abs(gap(g[i], g[j], W, &jx) - 1) > 1e-9) continue;
      left |= jx < g[i].x;
      right |= jx > g[i].x;
    }
    if (!(left && right)) ++bad;
  }
  if (on_floor) *on_floor = floor;
  return bad;
}

// Variance of a normal truncated at +-K sigma over sigma^2.
double variance_factor(double K) {
  const double phi = std::exp(-0.5 * K * K) / std::sqrt(2 * std::numbers::pi);
  return 1 - 2 * K * phi / std::erf(K / std::sqrt(2.0));
}

}  // namespace

// delta = 0.5 cut at +-1 sigma, 3000 disks (W = 80, H = 160 R_av): mean and
// variance of the deposited radii within 5 standard errors of the truncated
// law (sd/sqrt(n); (K sigma)^2/sqrt(n) for the variance: |r - mu| <= K sigma).
TEST(BallisticDeposit, RadiusMomentsAreTheTruncatedGaussians) {
  Deck d;
  d(deck(80, 160, 0.5, "3000"));
  const auto g = disks(d);
  ASSERT_EQ(g.size(), 3000u);
  double s = 0, s2 = 0;
  for (const auto& k : g) s += k.r, s2 += k.r * k.r;
  const double n = double(g.size()), mean = s / n, var = s2 / n - mean * mean;
  const double want = 0.25 * variance_factor(1.0);
  EXPECT_NEAR(mean, 1.0, 5 * std::sqrt(want / n));
  EXPECT_NEAR(var, want, 5 * 0.25 / std::sqrt(n));
  for (const auto& k : g) {
    EXPECT_GE(k.r, 0.5);
    EXPECT_LE(k.r, 1.5);
    EXPECT_EQ(d->atoms.type[0], 1);
  }
  for (std::size_t i = 0; i < d->atoms.n; ++i)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(d->atoms.v[3 * i + k], 0.0);
}

// No two disks overlap, periodic images in x included; every disk rests on the
// floor or on two earlier disks either side of its centre; all inside the box.
TEST(BallisticDeposit, NoOverlapAndEveryDiskRests) {
  for (double sigma : {0.0, 0.2, 0.5, 0.7}) {
    Deck d;
    d(deck(40, 80, sigma, "fill"));
    const auto g = disks(d);
    ASSERT_GT(g.size(), 500u) << sigma;
    EXPECT_GE(min_gap(g, 40), 1 - 1e-9) << "sigma " << sigma;
    long floor = 0;
    EXPECT_EQ(unsupported(g, 40, &floor), 0) << "sigma " << sigma;
    EXPECT_GT(floor, 5) << sigma;
    EXPECT_LT(floor, 40) << sigma;  // one layer at most on a floor 40 wide
    for (const auto& k : g) {
      EXPECT_GE(k.x, 0.0);
      EXPECT_LT(k.x, 40.0);
      EXPECT_LE(k.y + k.r, 80.0);
    }
  }
}

// The checks above can fail: a disk moved by 1e-6 of its radius, or one
// added on a single support, is caught.
TEST(BallisticDeposit, CheckersCatchBrokenPackings) {
  Deck d;
  d(deck(20, 40, 0.5, "100"));
  auto g = disks(d);
  ASSERT_EQ(unsupported(g, 20), 0);
  auto moved = g;
  moved[60].y -= 1e-6;
  EXPECT_LT(min_gap(moved, 20), 1 - 1e-9);
  moved = g;
  moved.back().y += 1e-6;  // the last disk: nothing rests on it
  EXPECT_EQ(unsupported(moved, 20), 1);
}

// A narrow box (W = 5 > 4 r_max): disks touch images across the period.
TEST(BallisticDeposit, NarrowPeriodicBox) {
  Deck d;
  d(deck(5.2, 40, 0.1, "fill"));
  const auto g = disks(d);
  ASSERT_GT(g.size(), 20u);
  EXPECT_GE(min_gap(g, 5.2), 1 - 1e-9);
  EXPECT_EQ(unsupported(g, 5.2), 0);
}

TEST(BallisticDeposit, SameSeedSamePackingOtherSeedOther) {
  Deck a, b, c;
  a(deck(30, 60, 0.5, "400", 32452843));
  b(deck(30, 60, 0.5, "400", 32452843));
  c(deck(30, 60, 0.5, "400", 32452867));
  const auto ga = disks(a), gb = disks(b), gc = disks(c);
  ASSERT_EQ(ga.size(), gb.size());
  long same = 0;
  for (std::size_t i = 0; i < ga.size(); ++i) {
    EXPECT_EQ(ga[i].x, gb[i].x);
    EXPECT_EQ(ga[i].y, gb[i].y);
    EXPECT_EQ(ga[i].r, gb[i].r);
    same += ga[i].x == gc[i].x;
  }
  EXPECT_EQ(same, 0);
}

// Monodisperse disks, W = 100 R: area fraction of the bulk (centres counted
// between 10 R above the floor and 10 R below the deposit top). A loose bound
// of our own (no literature figure checked; Jullien & Meakin, J. Phys. I 1,
// 1263 (1991) study such packings): above 0.75 and below the triangular
// crystal's pi/(2 sqrt 3) = 0.9069. Equal disks make exact ties (a disk
// dropped midway between two touching ones lands on both): no overlap, all at rest.
TEST(BallisticDeposit, MonodisperseBulkFraction) {
  Deck d;
  d(deck(100, 200, 0.0, "fill"));
  const auto g = disks(d);
  EXPECT_GE(min_gap(g, 100), 1 - 1e-9);
  EXPECT_EQ(unsupported(g, 100), 0);
  double top = 0;
  for (const auto& k : g) top = std::max(top, k.y);
  const double lo = 10, hi = top - 10;
  long n = 0;
  for (const auto& k : g) n += k.y >= lo && k.y < hi;
  const double phi = n * std::numbers::pi / (100 * (hi - lo));
  EXPECT_GT(phi, 0.75);
  EXPECT_LT(phi, 0.9069);
  std::printf("monodisperse bulk area fraction %.4f (%zu disks)\n", phi, g.size());
}

// A second deposit (other seed, other template) lands on the first: grains
// already in the box are obstacles. `floor 5`: the lowest disks rest at y = 5 + r.
TEST(BallisticDeposit, SecondDepositOnFirstAndFloorHeight) {
  Deck d;
  d(deck(30, 80, 0.5, "300") + "fix small all particletemplate/sphere 15485867 density constant 1 radius constant 0.4\n"
                               "ballistic_deposit 300 small seed 32452867\n");
  ASSERT_EQ(d->atoms.n, 600u);
  auto g = disks(d);
  EXPECT_GE(min_gap(g, 30), 1 - 1e-9);
  EXPECT_EQ(unsupported(g, 30), 0);
  double low1 = 1e300, low2 = 1e300;
  for (const auto& k : g) (k.id <= 300 ? low1 : low2) = std::min(k.id <= 300 ? low1 : low2, k.y);
  EXPECT_GT(low2, low1);  // the small disks sit in and on the first deposit
  Deck f;
  f(deck(30, 80, 0.0, "100").substr(0, deck(30, 80, 0.0, "100").rfind("ballistic")) +
    "ballistic_deposit 100 pt seed 32452843 floor 5\n");
  double low = 1e300;
  for (const auto& k : disks(f)) low = std::min(low, k.y);
  EXPECT_DOUBLE_EQ(low, 6.0);
}

TEST(BallisticDeposit, BadInput) {
  const std::string box2d = "units si\natom_style granular\ndimension 2\nboundary p f p\n"
                            "region box block 0 10 0 20 -0.5 0.5 units box\ncreate_box 1 box\n"
                            "fix pt all particletemplate/sphere 15485863 density constant 1 radius constant 1\n";
  {
    Deck d;
    d("units si\natom_style granular\nboundary p f p\nregion box block 0 10 0 20 0 10 units box\ncreate_box 1 box\n"
      "fix pt all particletemplate/sphere 15485863 density constant 1 radius constant 1\n");
    const std::string e = error_of(d, "ballistic_deposit 10 pt seed 32452843");
    EXPECT_NE(e.find("a 2D box"), std::string::npos) << e;
    EXPECT_NE(e.find("test:1"), std::string::npos) << e;
  }
  {
    Deck d;
    d("units si\natom_style granular\ndimension 2\nboundary f f p\nregion box block 0 10 0 20 -0.5 0.5 units box\n"
      "create_box 1 box\nfix pt all particletemplate/sphere 15485863 density constant 1 radius constant 1\n");
    EXPECT_NE(error_of(d, "ballistic_deposit 10 pt seed 32452843").find("periodic in x"), std::string::npos);
  }
  Deck d;
  d(box2d);
  EXPECT_NE(error_of(d, "ballistic_deposit 0 pt seed 32452843").find("N > 0"), std::string::npos);
  EXPECT_NE(error_of(d, "ballistic_deposit -3 pt seed 32452843").find("N > 0"), std::string::npos);
  EXPECT_NE(error_of(d, "ballistic_deposit 10 nope seed 32452843").find("particletemplate/sphere"), std::string::npos);
  EXPECT_NE(error_of(d, "ballistic_deposit 10 pt").find("seed S"), std::string::npos);
  EXPECT_NE(error_of(d, "ballistic_deposit 10 pt seed 12").find("prime"), std::string::npos);
  EXPECT_NE(error_of(d, "ballistic_deposit 10 pt seed 32452843 floor 30").find("floor height"), std::string::npos);
  EXPECT_NE(error_of(d, "ballistic_deposit 10 pt seed 32452843 speed 3").find("seed, floor"), std::string::npos);
  const std::string tall = error_of(d, "ballistic_deposit 500 pt seed 32452843");
  EXPECT_NE(tall.find("above the box top"), std::string::npos) << tall;
  d("fix big all particletemplate/sphere 15485867 density constant 1 radius constant 2.6");
  const std::string narrow = error_of(d, "ballistic_deposit 10 big seed 32452843");
  EXPECT_NE(narrow.find("wider than 4 largest radii"), std::string::npos) << narrow;
  EXPECT_EQ(d->atoms.n, 0u);
}

}  // namespace test_ballistic_deposit
