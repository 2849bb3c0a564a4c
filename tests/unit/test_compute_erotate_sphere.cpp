// compute erotate/sphere against 1/2 I w^2, I = 2/5 m r^2, summed by hand (relative 1e-12).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_compute_erotate_sphere {

using sable::test::Deck;

namespace {
double mass(double r, double rho) { return 4.0 / 3.0 * std::numbers::pi * r * r * r * rho; }

void spinning_grains(Deck& d, const std::string& dim = "3") {
  d("units si\natom_style granular\ndimension " + dim + "\nregion box block 0 1 0 1 -0.5 0.5 units box\n"
    "create_box 1 box\n"
    "create_atoms 1 single 0.5 0.5 0 units box\ncreate_atoms 1 single 0.2 0.3 0 units box\n"
    "create_atoms 1 single 0.7 0.1 0 units box");
  sable::Atoms& a = d->atoms;
  const double w[3][3] = {{0, 0, 3}, {1, 2, 0}, {-4, 0.5, 1}};
  const double tq[3][3] = {{0, 0, 1e-3}, {0, 0, 0}, {2e-4, 0, 0}};
  const double r[3] = {0.05, 0.1, 0.025}, rho[3] = {2500, 1000, 3000};
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
      a.omega[3 * i + k] = w[i][k];
      a.torque[3 * i + k] = tq[i][k];
    }
    a.set_radius_density(i, r[i], rho[i]);
  }
}

double by_hand(const sable::Atoms& a, double half_dt = 0.0) {
  double e = 0;
  for (std::size_t i = 0; i < a.n; ++i) {
    const double I = 0.4 * a.rmass[i] * a.radius[i] * a.radius[i];
    for (int k = 0; k < 3; ++k) {
      const double w = a.omega[3 * i + k] + half_dt * a.torque[3 * i + k] / I;
      e += 0.5 * I * w * w;
    }
  }
  return e;
}
}  // namespace

TEST(ComputeErotateSphere, SumsHalfInertiaOmegaSquared) {
  Deck d;
  spinning_grains(d);
  d("compute r all erotate/sphere");
  // Written out for atom 1: I = 2/5 m r^2, w = 3 about z.
  const double m1 = mass(0.05, 2500), I1 = 0.4 * m1 * 0.05 * 0.05;
  const double m2 = mass(0.1, 1000), I2 = 0.4 * m2 * 0.01;
  const double m3 = mass(0.025, 3000), I3 = 0.4 * m3 * 0.025 * 0.025;
  const double want = 0.5 * I1 * 9 + 0.5 * I2 * 5 + 0.5 * I3 * (16 + 0.25 + 1);
  EXPECT_NEAR(d->find_compute("r")->scalar(), want, 1e-12 * want);
  EXPECT_NEAR(want, by_hand(d->atoms), 1e-12 * want);
}

TEST(ComputeErotateSphere, SphereInertiaAlsoIn2D) {
  // LIGGGHTS: in 2D the grains are still spheres (I = 2/5 m r^2), not disks.
  Deck d;
  spinning_grains(d, "2");
  d("compute r all erotate/sphere");
  const double want = by_hand(d->atoms);
  EXPECT_NEAR(d->find_compute("r")->scalar(), want, 1e-12 * want);
}

TEST(ComputeErotateSphere, HalfstepAndGroup) {
  Deck d;
  spinning_grains(d);
  d("timestep 1e-3\ncompute r all erotate/sphere halfstep");
  const double want = by_hand(d->atoms, 0.5e-3);
  EXPECT_NEAR(d->find_compute("r")->scalar(), want, 1e-12 * want);
  const int g = d->groups.find_or_create("first");
  d->atoms.mask[0] |= d->groups.bit(g);
  d("compute r1 first erotate/sphere");
  const double m1 = mass(0.05, 2500), want1 = 0.5 * 0.4 * m1 * 0.05 * 0.05 * 9;
  EXPECT_NEAR(d->find_compute("r1")->scalar(), want1, 1e-12 * want1);
}

}  // namespace test_compute_erotate_sphere
