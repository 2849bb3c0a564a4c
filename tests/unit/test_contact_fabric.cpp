// compute contact/fabric and compute force/midline (2D, petit2017), against
// exact values: periodic triangular and square lattices of grains of d = 2 mm at
// spacing a = 1.98 mm (every contact F = kn (d - a), delta/(R_i+R_j) = 0.01),
// Love-Weber's tensor of a random overlapping packing against the sum over
// pairs written out here, the force of one contact across a line, and the
// repeated removal of rattlers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "core/engine/compute.h"
#include "tests/unit/deck_runner.h"
#include "tests/unit/lattice_deck_2d.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_contact_fabric {

using sable::test::Deck;
using sable::test::lattice_deck;
using sable::test::spring_scene_2d;

namespace {

constexpr double kA = 0.00198, kD = 0.002, kKn = 2000;
const double kF = kKn * (kD - kA);

// c_ID[k] (1-based) of the compute `id`.
double vec(Deck& d, const char* id, int k) { return d->find_compute(id)->vector(k); }

std::string fmt(const char* f, double a, double b = 0, double c = 0) {
  char s[200];
  std::snprintf(s, sizeof s, f, a, b, c);
  return s;
}

enum Out { kZ = 1, kRattlers = 2, kS = 3, kP = 4 };
// The entries after the N bins: sigma xx, yy, xy, yx, mean and max delta_rel, N_c, grains.
int after(int bins, int k) { return 3 + bins + k; }

}  // namespace

// Triangular lattice, horizontal rows (hex), 8 x 5 cells = 80 grains, 240
// contacts: Z = 6, no rattler, three directions -90, -30, +30 deg equally
// frequent, so S = ln 3 = 1.0986 on 36 bins (P = 1/3 at bins 0, 12, 24: the
// directions are bin centres), on 3 bins and on 4 (-30 and 30 fall in the bins
// of -45 and 45). Love-Weber over the box area: sqrt(3) F / a on the diagonal.
// The paper's S_tri = ln 4 = 1.386 is not a binning of these angles (three
// equal weights give at most ln 3): it is recovered from the local rows by the
// per-grain closed-upper-half-plane counting (each horizontal contact twice, at
// -90 and +90 deg), as the header of compute_contact_fabric.cpp says.
TEST(ContactFabric, TriangularLattice) {
  Deck d;
  d(lattice_deck("dimension 2", true, kA, 8, 5));
  ASSERT_EQ(d->atoms.n, 80u);
  d("compute f all contact/fabric\ncompute f3 all contact/fabric bins 3\ncompute f4 all contact/fabric bins 4\nrun 0");
  EXPECT_NEAR(vec(d, "f", kZ), 6.0, 1e-12);
  EXPECT_EQ(vec(d, "f", kRattlers), 0.0);
  EXPECT_EQ(vec(d, "f", after(36, 7)), 240.0);
  EXPECT_EQ(vec(d, "f", after(36, 8)), 80.0);
  EXPECT_NEAR(vec(d, "f", kS), std::log(3.0), 1e-12);
  double sum = 0;
  for (int k = 0; k < 36; ++k) {
    const double p = vec(d, "f", kP + k);
    sum += p;
    EXPECT_NEAR(p, (k == 0 || k == 12 || k == 24) ? 1.0 / 3 : 0.0, 1e-15) << "bin " << k;
  }
  EXPECT_NEAR(sum, 1.0, 1e-14);
  EXPECT_NEAR(vec(d, "f3", kS), std::log(3.0), 1e-12);
  EXPECT_NEAR(vec(d, "f4", kS), std::log(3.0), 1e-12);
  const double sig = std::sqrt(3.0) * kF / kA;
  EXPECT_NEAR(vec(d, "f", after(36, 1)), sig, 1e-9 * sig);
  EXPECT_NEAR(vec(d, "f", after(36, 2)), sig, 1e-9 * sig);
  EXPECT_LT(std::fabs(vec(d, "f", after(36, 3))), 1e-9 * sig);
  EXPECT_LT(std::fabs(vec(d, "f", after(36, 4))), 1e-9 * sig);
  EXPECT_NEAR(vec(d, "f", after(36, 5)), 0.01, 1e-12);
  EXPECT_NEAR(vec(d, "f", after(36, 6)), 0.01, 1e-12);
  // Local rows: id_i id_j phi delta_rel fn. phi in [-pi/2, pi/2); the per-grain
  // upper-half-plane count gives the paper's ln 4.
  sable::Compute* c = d->find_compute("f");
  c->local_now();
  ASSERT_EQ(c->local_rows(), 240u);
  std::vector<double> counts(4, 0.0);  // -90, -30, 30, +90
  for (std::size_t r = 0; r < c->local_rows(); ++r) {
    const double* row = &c->local[r * 5];
    const double deg = row[2] * 180 / M_PI;
    EXPECT_GE(row[2], -M_PI / 2);
    EXPECT_LT(row[2], M_PI / 2);
    EXPECT_NEAR(row[3], 0.01, 1e-12);
    EXPECT_NEAR(row[4], kF, 1e-12 * kF);
    if (std::fabs(deg + 90) < 1e-9) counts[0] += 1, counts[3] += 1;
    else counts[deg < 0 ? 1 : 2] += 1;
  }
  double s4 = 0;
  for (double n : counts) s4 -= n / 320 * std::log(n / 320);
  EXPECT_NEAR(s4, std::log(4.0), 1e-12);
  EXPECT_NEAR(s4, 1.386, 5e-4);
  std::printf("[ measured ] triangular lattice: Z %.6f, S %.6f (ln 3), upper-half-plane count %.6f (ln 4)\n",
              vec(d, "f", kZ), vec(d, "f", kS), s4);
}

// Square lattice 8 x 8: Z = 4, directions 0 and -90 deg (bins 18 and 0 of 36;
// of 2 bins, both centres), S = ln 2; sigma_xx = sigma_yy = F / a.
TEST(ContactFabric, SquareLattice) {
  Deck d;
  d(lattice_deck("dimension 2", false, kA, 8, 8));
  d("compute f all contact/fabric\ncompute f2 all contact/fabric bins 2\nrun 0");
  EXPECT_NEAR(vec(d, "f", kZ), 4.0, 1e-12);
  EXPECT_NEAR(vec(d, "f", kS), std::log(2.0), 1e-12);
  EXPECT_NEAR(vec(d, "f", kP + 0), 0.5, 1e-15);
  EXPECT_NEAR(vec(d, "f", kP + 18), 0.5, 1e-15);
  EXPECT_NEAR(vec(d, "f2", kS), std::log(2.0), 1e-12);
  EXPECT_NEAR(vec(d, "f2", kP + 1), 0.5, 1e-15);
  for (int k : {1, 2}) EXPECT_NEAR(vec(d, "f", after(36, k)), kF / kA, 1e-9 * kF / kA);
}

// A random packing (60 grains, radii 0.8-1.2 mm, in a 12 mm square box with
// non-periodic boundaries), at rest: every overlapping pair carries the
// normal force kn delta only, so Love-Weber's sigma_ab = (1/A) sum kn delta
// n_a n_b |l| over the pairs found here by a double loop, with A given as
// `area 1e-4` and as v_name.
TEST(ContactFabric, LoveWeberOfARandomPacking) {
  Deck d;
  d(spring_scene_2d("dimension 2", "f f p", 0.012, 0.012));
  std::mt19937 rng(44);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  struct G {
    double x, y, r;
  };
  std::vector<G> g;
  for (int k = 0; k < 60; ++k) {
    g.push_back({0.001 + 0.01 * u(rng), 0.001 + 0.01 * u(rng), 0.0008 + 0.0004 * u(rng)});
    d(fmt("create_atoms 1 single %.17g %.17g 0 units box", g.back().x, g.back().y));
    d(fmt("set atom %.0f diameter %.17g density 2500", k + 1, 2 * g.back().r));
  }
  d("variable A equal 1e-4\ncompute f all contact/fabric area 1e-4\ncompute fv all contact/fabric area v_A\nrun 0");
  double s[2][2] = {{0, 0}, {0, 0}}, rel = 0, relmax = 0;
  int nc = 0;
  for (std::size_t i = 0; i < g.size(); ++i)
    for (std::size_t j = i + 1; j < g.size(); ++j) {
      const double l[2] = {g[i].x - g[j].x, g[i].y - g[j].y}, len = std::hypot(l[0], l[1]);
      const double delta = g[i].r + g[j].r - len;
      if (delta <= 0) continue;
      ++nc;
      rel += delta / (g[i].r + g[j].r);
      relmax = std::max(relmax, delta / (g[i].r + g[j].r));
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) s[a][b] += kKn * delta * l[a] * l[b] / len / 1e-4;
    }
  ASSERT_GT(nc, 20);
  EXPECT_EQ(vec(d, "f", after(36, 7)), nc);
  const double tr = s[0][0] + s[1][1];
  EXPECT_NEAR(vec(d, "f", after(36, 1)) + vec(d, "f", after(36, 2)), tr, 1e-12 * tr);
  EXPECT_NEAR(vec(d, "f", after(36, 1)), s[0][0], 1e-12 * tr);
  EXPECT_NEAR(vec(d, "f", after(36, 2)), s[1][1], 1e-12 * tr);
  EXPECT_NEAR(vec(d, "f", after(36, 3)), s[0][1], 1e-12 * tr);
  EXPECT_NEAR(vec(d, "f", after(36, 4)), s[1][0], 1e-12 * tr);
  EXPECT_NEAR(vec(d, "fv", after(36, 1)), s[0][0], 1e-12 * tr);
  EXPECT_NEAR(vec(d, "f", after(36, 5)), rel / nc, 1e-12);
  EXPECT_NEAR(vec(d, "f", after(36, 6)), relmax, 1e-12);
  std::printf("[ measured ] random packing: %d contacts, trace %.6g N/m, mean delta/(Ri+Rj) %.4f\n", nc, tr, rel / nc);
}

// Rattlers (M = 2): a triangle T1 T2 T3 of touching grains, a chain T1 - B - C
// and a lone grain D. C has one contact; once it goes B has one too; D has
// none: 3 rattlers of 6, and Z = 2 * 3 / 3 = 2 over the triangle. With
// `rattler 1` only D goes (Z = 2 * 5 / 5); with `rattler 0` none.
TEST(ContactFabric, RattlersRemovedRepeatedly) {
  Deck d;
  d(spring_scene_2d("dimension 2", "f f p", 0.02, 0.02));
  const double h = 0.0019 * std::sqrt(3.0) / 2;
  const double xy[6][2] = {{0.005, 0.005}, {0.0069, 0.005}, {0.00595, 0.005 + h},  // triangle, spacing 1.9 mm
                           {0.0031, 0.005}, {0.0012, 0.005},                       // B, C left of T1
                           {0.015, 0.015}};                                        // D
  for (const auto& p : xy) d(fmt("create_atoms 1 single %.17g %.17g 0 units box", p[0], p[1]));
  d("set group all diameter 0.002 density 2500");
  d("compute f all contact/fabric\ncompute f1 all contact/fabric rattler 1\ncompute f0 all contact/fabric rattler 0\n"
    "run 0");
  EXPECT_EQ(vec(d, "f", after(36, 7)), 5.0);
  EXPECT_NEAR(vec(d, "f", kRattlers), 0.5, 1e-15);
  EXPECT_NEAR(vec(d, "f", kZ), 2.0, 1e-15);
  EXPECT_EQ(vec(d, "f", after(36, 8)), 3.0);
  EXPECT_NEAR(vec(d, "f1", kRattlers), 1.0 / 6, 1e-15);
  EXPECT_NEAR(vec(d, "f1", kZ), 2.0, 1e-15);
  EXPECT_NEAR(vec(d, "f0", kRattlers), 0.0, 1e-15);
  EXPECT_NEAR(vec(d, "f0", kZ), 10.0 / 6, 1e-15);
  // The group without T3 (atom 3). `contacts both`: T1 - T2 is left as a pair of one
  // contact each, so every grain goes. `contacts any`: T3 counts as a wall, T1 and
  // T2 keep two contacts each: Z = 2, rattlers B, C, D (3 of 5), 5 contacts counted.
  d("group g id 1 2 4 5 6\ncompute gb g contact/fabric\ncompute ga g contact/fabric contacts any\nrun 0");
  EXPECT_EQ(vec(d, "gb", after(36, 7)), 3.0);
  EXPECT_EQ(vec(d, "gb", kRattlers), 1.0);
  EXPECT_EQ(vec(d, "gb", kZ), 0.0);
  EXPECT_EQ(vec(d, "ga", after(36, 7)), 5.0);
  EXPECT_NEAR(vec(d, "ga", kRattlers), 0.6, 1e-15);
  EXPECT_NEAR(vec(d, "ga", kZ), 2.0, 1e-15);
  EXPECT_EQ(vec(d, "ga", after(36, 8)), 2.0);
}

// force/midline: two grains (r = 1 mm) at (4.1, 5) and (5.9, 5.3) mm, line x = 5 mm.
// The contact carries kn delta along the branch; its x component, compression
// positive, over the height from the lower grain's bottom (4 mm) to the upper's
// top (6.3 mm); or over yhi - ylo, counting only crossings within. The line y
// = 5.15 mm gives the y component over the x span. A line beside the pair
// crosses nothing.
TEST(ForceMidline, TwoGrainContact) {
  Deck d;
  d(spring_scene_2d("dimension 2", "f f p", 0.01, 0.01));
  d("create_atoms 1 single 0.0041 0.005 0 units box\ncreate_atoms 1 single 0.0059 0.0053 0 units box");
  d("set group all diameter 0.002 density 2500");
  d("variable X equal 0.005\n"
    "compute m all force/midline x v_X\ncompute mb all force/midline x 0.005 ylo 0 yhi 0.01\n"
    "compute mc all force/midline x 0.005 ylo 0.0052 yhi 0.01\ncompute my all force/midline y 0.00515\n"
    "compute mo all force/midline x 0.0061\nrun 0");
  const double lx = 0.0018, ly = 0.0003, len = std::hypot(lx, ly), F = kKn * (kD - len);
  const double fx = F * lx / len, fy = F * ly / len;
  auto* m = d->find_compute("m");
  EXPECT_NEAR(m->vector(2), fx, 1e-12 * fx);
  EXPECT_NEAR(m->vector(3), 0.0023, 1e-15);
  EXPECT_NEAR(m->scalar(), fx / 0.0023, 1e-12 * fx / 0.0023);
  EXPECT_EQ(m->vector(4), 1.0);
  EXPECT_NEAR(m->vector(5), 0.004, 1e-15);
  EXPECT_NEAR(m->vector(6), 0.0063, 1e-15);
  EXPECT_NEAR(vec(d, "mb", 1), fx / 0.01, 1e-12 * fx / 0.01);
  EXPECT_EQ(vec(d, "mc", 4), 0.0);
  EXPECT_EQ(vec(d, "mc", 1), 0.0);
  EXPECT_NEAR(vec(d, "my", 2), fy, 1e-12 * fy);
  EXPECT_NEAR(vec(d, "my", 3), 0.0038, 1e-15);
  EXPECT_EQ(vec(d, "mo", 4), 0.0);
  EXPECT_EQ(vec(d, "mo", 1), 0.0);
}

// Across a periodic boundary: grains at x = 0.8 and 9.2 mm of a 10 mm periodic
// box touch through the image (gap 1.6 mm, delta 0.4 mm): the line x = 0 (its
// image x = 10 mm) is crossed, compression positive; x = 5 mm is not.
TEST(ForceMidline, PeriodicImage) {
  Deck d;
  d(spring_scene_2d("dimension 2", "p f p", 0.01, 0.01));
  d("create_atoms 1 single 0.0008 0.005 0 units box\ncreate_atoms 1 single 0.0092 0.005 0 units box");
  d("set group all diameter 0.002 density 2500");
  d("compute a all force/midline x 0\ncompute b all force/midline x 0.01\ncompute c all force/midline x 0.005\nrun 0");
  const double F = kKn * 0.0004;
  for (const char* id : {"a", "b"}) {
    EXPECT_EQ(vec(d, id, 4), 1.0) << id;
    EXPECT_NEAR(vec(d, id, 2), F, 1e-9 * F) << id;
    EXPECT_NEAR(vec(d, id, 1), F / 0.002, 1e-9 * F / 0.002) << id;
  }
  EXPECT_EQ(vec(d, "c", 4), 0.0);
}

// Errors: 3D, a missing pair style, bad keywords.
TEST(ContactFabric, Errors) {
  Deck d;
  d(lattice_deck("dimension 2", false, kA, 2, 2));
  EXPECT_NE(sable::test::error_of(d, "compute e all contact/fabric bins 0").find("1..100000"), std::string::npos);
  EXPECT_NE(sable::test::error_of(d, "compute e all contact/fabric colour 3").find("bins, area, rattler or contacts"),
            std::string::npos);
  EXPECT_NE(sable::test::error_of(d, "compute e all contact/fabric area v_nope").find("equal-style"),
            std::string::npos);
  EXPECT_NE(sable::test::error_of(d, "compute e all force/midline z 0").find("x or y"), std::string::npos);
  EXPECT_NE(sable::test::error_of(d, "compute e all force/midline x 0 xlo 0 xhi 1").find("ylo"), std::string::npos);
  Deck d3;
  d3(spring_scene_2d("dimension 3", "p p p", 0.01, 0.01));
  EXPECT_NE(sable::test::error_of(d3, "compute e all contact/fabric").find("dimension 2"), std::string::npos);
}

// A periodic triangular lattice (8 x 5 cells, rows horizontal): across the line
// x = 3.25 a over the box's height (ylo, yhi its bounds, y periodic: every contact
// once), each row adds one horizontal contact (F) and one diagonal (F/2) per
// sqrt(3)/2 a, so sigma_xx = sqrt(3) F / a, Love-Weber's value; 10 rows, 20 crossings.
TEST(ForceMidline, PeriodicLatticeMatchesLoveWeber) {
  Deck d;
  d(lattice_deck("dimension 2", true, kA, 8, 5));
  const double ly = 5 * kA * std::sqrt(3.0);
  d(fmt("compute m all force/midline x %.17g ylo 0 yhi %.17g\nrun 0", 3.25 * kA, ly));
  const double sig = std::sqrt(3.0) * kF / kA;
  EXPECT_EQ(vec(d, "m", 4), 20.0);
  EXPECT_NEAR(vec(d, "m", 3), ly, 1e-15);
  EXPECT_NEAR(vec(d, "m", 1), sig, 1e-9 * sig);
}

// Love-Weber's sigma_xx is the mean over x of the force across vertical lines: in a
// box periodic in x, each contact adds its f_x (on the grain right of the line) over
// the |l_x| its branch spans, so the integral over one period of force/midline's
// sum F(X0) is sum_c f_x l_x, equilibrium or not. F(X0) is constant between grain
// centres: lines at the midpoints of the gaps between sorted centres, weighted by
// the gaps, give the integral exactly. 40 random overlapping grains (rest, normal
// forces only), area 1 so that c_fab[1 + 3 + 36] is the sum itself.
TEST(ForceMidline, MeanOverXIsLoveWeber) {
  Deck d;
  const double lx = 0.012, ly = 0.012;
  d(spring_scene_2d("dimension 2", "p f p", lx, ly));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> xs;
  for (int k = 0; k < 40; ++k) {
    xs.push_back(lx * u(rng));
    d(fmt("create_atoms 1 single %.17g %.17g 0 units box", xs.back(), 0.0015 + 0.009 * u(rng)));
    d(fmt("set atom %.0f diameter %.17g density 2500", k + 1, 0.0016 + 0.0008 * u(rng)));
  }
  std::sort(xs.begin(), xs.end());
  std::vector<double> mid, w;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    const double a = xs[k], b = k + 1 < xs.size() ? xs[k + 1] : xs[0] + lx;
    mid.push_back(std::fmod(0.5 * (a + b), lx));
    w.push_back(b - a);
    d(fmt("compute m%.0f all force/midline x %.17g ylo 0 yhi %.17g", double(k), mid.back(), ly));
  }
  d("compute f all contact/fabric area 1\nrun 0");
  double integral = 0, fmin = 1e300, fmax = -1e300;
  for (std::size_t k = 0; k < mid.size(); ++k) {
    const double f = vec(d, fmt("m%.0f", double(k)).c_str(), 2);
    integral += f * w[k];
    fmin = std::min(fmin, f), fmax = std::max(fmax, f);
  }
  const double lw = vec(d, "f", after(36, 1));
  ASSERT_GT(std::fabs(lw), 0.0);
  EXPECT_NEAR(integral, lw, 1e-12 * std::fabs(lw));
  std::printf("[ measured ] sum f_x l_x %.6g N m, integral of F(X0) %.6g; F(X0) from %.4g to %.4g N\n", lw, integral,
              fmin, fmax);
}

// Without ylo, yhi the height is the group's: from its lowest grain bottom to its
// highest grain top, whichever grains the line crosses. The pair of TwoGrainContact
// (4.0 to 6.3 mm) and a lone grain at y = 9 mm (top 10 mm): 6 mm; for a group of the
// pair alone, 2.3 mm.
TEST(ForceMidline, DefaultHeightIsTheGroupsSpan) {
  Deck d;
  d(spring_scene_2d("dimension 2", "f f p", 0.01, 0.012));
  d("create_atoms 1 single 0.0041 0.005 0 units box\ncreate_atoms 1 single 0.0059 0.0053 0 units box\n"
    "create_atoms 1 single 0.002 0.009 0 units box\nset group all diameter 0.002 density 2500\ngroup pair id 1 2");
  d("compute a all force/midline x 0.005\ncompute p pair force/midline x 0.005\nrun 0");
  EXPECT_NEAR(vec(d, "a", 3), 0.006, 1e-15);
  EXPECT_NEAR(vec(d, "a", 5), 0.004, 1e-15);
  EXPECT_NEAR(vec(d, "a", 6), 0.010, 1e-15);
  EXPECT_NEAR(vec(d, "p", 3), 0.0023, 1e-15);
  EXPECT_EQ(vec(d, "a", 2), vec(d, "p", 2));
  EXPECT_NEAR(vec(d, "a", 1), vec(d, "a", 2) / 0.006, 1e-12 * vec(d, "a", 1));
}

}  // namespace test_contact_fabric
