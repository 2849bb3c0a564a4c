// Energy conservation: an elastic (e = 1), frictionless gas of Hertz spheres
// (216 grains, 6 % solid fraction) in a periodic box. Between collisions the energy is purely kinetic, so the
// kinetic energy sampled when no contact is active must equal the initial one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "core/io/thermo.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_energy {

using sable::test::Deck;

namespace {

// True when any two grains overlap (minimum image in a periodic cube of side L).
bool any_contact(const sable::Atoms& a, double L) {
  for (std::size_t i = 0; i < a.n; ++i)
    for (std::size_t j = i + 1; j < a.n; ++j) {
      double r2 = 0;
      for (int k = 0; k < 3; ++k) {
        double d = a.x[3 * j + k] - a.x[3 * i + k];
        d -= L * std::round(d / L);
        r2 += d * d;
      }
      const double c = a.radius[i] + a.radius[j];
      if (r2 < c * c) return true;
    }
  return false;
}

}  // namespace

TEST(Energy, ElasticHertzGasConservesKineticEnergyBetweenCollisions) {
  const double r = 1e-3, rho = 2500, E = 1e8, nu = 0.3, L = 0.036;
  Deck d;
  d(R"D(units si
atom_style granular
boundary p p p
region box block 0 0.036 0 0.036 0 0.036 units box
create_box 1 box
lattice sc 0.006
create_atoms 1 box
set group all diameter 0.002 density 2500
neighbor 0.0004 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e8
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 1.0
fix m4 all property/global coefficientFriction peratomtypepair 1 0.0
pair_style gran model hertz tangential no_history
pair_coeff * *
fix i all nve/sphere)D");
  sable::Atoms& a = d->atoms;
  ASSERT_EQ(a.n, 216u);
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < 3 * a.n; ++i) a.v[i] = u(rng);

  // Hertz contact duration at the fastest approach speed (2 sqrt(3) m/s), equal spheres:
  // t_c = 2.87 (m*^2 / (R* Y*^2 v))^(1/5), m* = m/2, R* = r/2, Y* = E / (2 (1 - nu^2)).
  const double m = 4.0 / 3.0 * M_PI * r * r * r * rho;
  const double ys = E / (2 * (1 - nu * nu));
  const double tc = 2.87 * std::pow((m / 2) * (m / 2) / ((r / 2) * ys * ys * 2 * std::sqrt(3.0)), 0.2);
  d->dt = tc / 50;  // the issue's requirement: dt <= t_c / 50

  const double ke0 = d->thermo->kinetic_energy();
  int samples = 0;
  double worst = 0.0;
  for (int chunk = 0; chunk < 1000; ++chunk) {  // 1e5 steps in all
    d("run 100");
    if (any_contact(a, L)) continue;
    ++samples;
    worst = std::max(worst, std::fabs(d->thermo->kinetic_energy() - ke0) / ke0);
  }
  EXPECT_GT(samples, 100) << "too few contact-free samples to judge";
  EXPECT_GT(1000 - samples, 50) << "too few chunks ended in a collision: the gas barely collided";
  EXPECT_LT(worst, 1e-4) << "largest relative kinetic-energy change over " << samples << " samples";
  std::printf("energy test: %d contact-free samples of 1000, worst relative change %.3g\n", samples, worst);
}

}  // namespace test_energy
