// The damping axis (contact_models/damping/): each model against the
// analytic restitution of a head-on collision of two equal spheres.
//  * damping restitution on a linear spring (model hooke/stiffness): the
//    dashpot 2|beta| sqrt(m* kn), beta = ln e / sqrt(ln^2 e + pi^2), gives the
//    linear oscillator m* x'' + gamma x' + kn x = 0 damping ratio |beta|, whose
//    velocity ratio at x = 0 is exactly e. The contact ends between two steps
//    while the dashpot pulls (-gamma vn at zero overlap): an error up to
//    gamma dt / m* = 2 |beta| omega dt ~ 2e-4 here, hence the tolerance 3e-4.
//  * damping viscoelastic on model hertz: Fn = sqrt(R* dn) (4/3 Y* dn - gamma vn),
//    whose restitution is Schwager & Poschel's series (PRE 57, 650 (1998); see
//    test_plugin.cpp, which checks the same law as an out-of-tree model), to 1e-4.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "tests/unit/deck_runner.h"

using sable::test::Deck;

namespace {

constexpr double kPi = std::numbers::pi;
const double kR = 0.001, kM = 4.0 / 3.0 * kPi * kR * kR * kR * 2500;

std::string num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// Two grains approaching at relative speed v; returns the restitution after steps.
double restitution(const std::string& materials_and_pair, double v, double dt, long steps) {
  Deck d;
  d(R"(units si
atom_style granular
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor 0.0005 bin
)" + materials_and_pair + R"(
pair_coeff * *
timestep )" + num(dt) + R"(
timestep_check accept
create_atoms 1 single -0.0011 0 0 units box
create_atoms 1 single 0.0011 0 0 units box
fix i all nve/sphere
)");
  auto& at = d->atoms;
  for (std::size_t i = 0; i < 2; ++i) {
    at.set_radius_density(i, kR, 2500);
    at.v[3 * i] = at.x[3 * i] < 0 ? v / 2 : -v / 2;
  }
  d("run " + std::to_string(steps));
  EXPECT_GT(std::fabs(at.x[3] - at.x[0]), 2 * kR) << "still in contact";
  return std::fabs(at.v[3] - at.v[0]) / v;
}

}  // namespace

TEST(Damping, RestitutionModelGivesExactRestitutionOnALinearSpring) {
  const double kn = 2000.0, meff = kM / 2, omega = std::sqrt(kn / meff);
  const double dt = 5e-4 / omega;  // omega dt = 5e-4
  for (double e : {0.5, 0.9}) {
    // No gamman/gammat in the deck: only LIGGGHTS' own damping of hooke/stiffness needs them.
    const std::string deck = "fix m1 all property/global kn peratomtypepair 1 " + num(kn) +
                             "\nfix m2 all property/global kt peratomtypepair 1 " + num(kn) +
                             "\nfix m3 all property/global coefficientRestitution peratomtypepair 1 " + num(e) +
                             "\nfix m4 all property/global coefficientFriction peratomtypepair 1 0.5" +
                             "\npair_style gran model hooke/stiffness damping restitution tangential history";
    const double r = restitution(deck, 0.1, dt, static_cast<long>(0.0012 / 0.1 / dt));
    std::printf("damping restitution, e = %g: measured %.7f\n", e, r);
    EXPECT_NEAR(r, e, 3e-4) << "e = " << e;
  }
}

TEST(Damping, ViscoelasticModelMatchesSchwagerPoschel) {
  const double Ystar = 5e7 / (2 * (1 - 0.09)), meff = kM / 2, reff = kR / 2, gamma = 20.0;
  const double rho = 4.0 / 3.0 * Ystar * std::sqrt(reff), A = gamma / (4.0 / 3.0 * Ystar), alpha = rho / meff;
  const std::string deck = R"(fix m1 all property/global youngsModulus peratomtype 5e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientFriction peratomtypepair 1 0.5
fix m4 all property/global dampingNormal peratomtypepair 1 )" + num(gamma) + R"(
fix m5 all property/global dampingTangential peratomtypepair 1 )" + num(gamma) + R"(
pair_style gran model hertz damping viscoelastic tangential history)";
  for (double v : {2.0, 0.5}) {
    const double x = A * std::pow(alpha, 0.4) * std::pow(v, 0.2);
    const double e = 1 - 1.15344 * x + 0.79826 * x * x;
    const double r = restitution(deck, v, 1e-7, static_cast<long>((0.0003 / v + 0.0003) / 1e-7));
    std::printf("damping viscoelastic v %g: restitution %.7f, Schwager-Poschel %.7f\n", v, r, e);
    EXPECT_NEAR(r, e, 1e-4) << "v = " << v;
  }
}
