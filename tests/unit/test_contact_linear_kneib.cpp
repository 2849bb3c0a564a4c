// model linear/kneib (contact_models/normal/linear_kneib.h): the cavity
// paper's linear spring-dashpot (kneib2017 Appendix B). Analytic answers of
// the damped linear oscillator m* x'' + gamman x' + kn x = 0 with
// gamman = 2 |beta| sqrt(m* kn), beta = ln e / sqrt(ln^2 e + pi^2):
//   restitution (velocity ratio at x = 0) exactly e,
//   contact time pi / (omega0 sqrt(1 - beta^2)), omega0 = sqrt(kn / m*),
// with kn = E 2 r1 r2 / (r1 + r2) between grains and kn = E r against a wall.
// The contact ends between two steps while the dashpot pulls: an error in e
// up to 2 |beta| omega0 dt (5e-4 here), hence the tolerance 3e-4 on e, as in
// test_contact_damping.cpp; the contact time is bracketed at +-1 %.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_contact_linear_kneib {

using sable::test::Deck;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kE = 1e7, kRho = 2500;

std::string num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

double mass(double r) { return 4.0 / 3.0 * kPi * r * r * r * kRho; }

std::string head(double e) {
  return R"(units si
atom_style granular
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor 0.0005 bin
fix m1 all property/global youngsModulus peratomtype )" + num(kE) + R"(
fix m2 all property/global poissonsRatio peratomtype 0.25
fix m3 all property/global coefficientRestitution peratomtypepair 1 )" + num(e) + R"(
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model linear/kneib tangential history
pair_coeff * *
timestep_check accept
)";
}

double beta(double e) { return std::log(e) / std::sqrt(std::log(e) * std::log(e) + kPi * kPi); }

struct Outcome {
  double e, gap_early, gap_late;  // restitution; surface gap at 0.99 and 1.01 contact times
};

// Two grains of radii r1, r2 a gap g0 apart closing at speed v (or, r2 = 0, one grain onto a zplane wall).
Outcome collide(double e, double r1, double r2, double v) {
  const double m1 = mass(r1), meff = r2 > 0 ? m1 * mass(r2) / (m1 + mass(r2)) : m1;
  const double kn = r2 > 0 ? kE * 2 * r1 * r2 / (r1 + r2) : kE * r1;
  const double w0 = std::sqrt(kn / meff), b = beta(e), tc = kPi / (w0 * std::sqrt(1 - b * b));
  const double dt = 5e-4 / w0, g0 = 1e-6;
  Deck d;
  std::string atoms = r2 > 0 ? "create_atoms 1 single 0 0 0 units box\ncreate_atoms 1 single " +
                                   num(r1 + r2 + g0) + " 0 0 units box\n"
                             : "create_atoms 1 single 0 0 " + num(r1 + g0) +
                                   " units box\nfix w all wall/gran model linear/kneib tangential history "
                                   "primitive type 1 zplane 0\n";
  d(head(e) + "timestep " + num(dt) + "\n" + atoms + "fix i all nve/sphere\n");
  auto& at = d->atoms;
  at.set_radius_density(0, r1, kRho);
  if (r2 > 0) {
    at.set_radius_density(1, r2, kRho);
    at.v[0] = v;
  } else {
    at.v[2] = -v;
  }
  auto gap = [&] {
    return r2 > 0 ? at.x[3] - at.x[0] - r1 - r2 : at.x[2] - r1;
  };
  const long to_touch = static_cast<long>(g0 / v / dt);
  Outcome o;
  d("run " + std::to_string(static_cast<long>(to_touch + 0.99 * tc / dt)));
  o.gap_early = gap();
  d("run " + std::to_string(static_cast<long>(0.02 * tc / dt) + 2));
  o.gap_late = gap();
  d("run " + std::to_string(static_cast<long>(0.2 * tc / dt)));
  EXPECT_GT(gap(), 0.0) << "still in contact";
  o.e = r2 > 0 ? (at.v[3] - at.v[0]) / v : at.v[2] / v;
  return o;
}

}  // namespace

TEST(LinearKneib, HeadOnRestitutionAndContactTimeBetweenUnequalGrains) {
  for (double e : {0.5, 0.9}) {
    const Outcome o = collide(e, 0.001, 0.0007, 0.1);
    std::printf("linear/kneib grains, e = %g: measured %.7f\n", e, o.e);
    EXPECT_NEAR(o.e, e, 3e-4);
    EXPECT_LT(o.gap_early, 0.0) << "separated before 0.99 of the contact time";
    EXPECT_GT(o.gap_late, 0.0) << "still touching after 1.01 of the contact time";
  }
}

TEST(LinearKneib, WallTakesTheGrainRadius) {
  const Outcome o = collide(0.5, 0.001, 0.0, 0.1);
  std::printf("linear/kneib wall, e = 0.5: measured %.7f\n", o.e);
  EXPECT_NEAR(o.e, 0.5, 3e-4);
  EXPECT_LT(o.gap_early, 0.0);
  EXPECT_GT(o.gap_late, 0.0);
}

}  // namespace test_contact_linear_kneib
