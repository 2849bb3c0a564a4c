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
#include <vector>

#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_contact_damping {

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

namespace {

// The pair's contact time (what the stability check uses) for two grains of radius kR.
double pair_contact_time(const std::string& materials_and_pair) {
  Deck d;
  d(R"(units si
atom_style granular
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
create_atoms 1 single 0 0 0 units box
)" + materials_and_pair + R"(
pair_coeff * *
timestep 1e-7
timestep_check accept)");
  d->atoms.set_radius_density(0, kR, 2500);
  d("run 0");
  return d->pair->contact_time(0, 0, 2.0);
}

double beta_of(double e) { return std::log(e) / std::sqrt(std::log(e) * std::log(e) + kPi * kPi); }
double damped_time(double kn, double meff, double gamman) {
  return kPi / std::sqrt(kn / meff - gamman * gamman / (4 * meff * meff));
}

const std::string kElastic = R"(fix m1 all property/global youngsModulus peratomtype 5e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix m5 all property/global characteristicVelocity scalar 2
)";
const std::string kStiffness = R"(fix m1 all property/global kn peratomtypepair 1 2000
fix m2 all property/global kt peratomtypepair 1 1500
fix m3 all property/global gamman peratomtypepair 1 20000
fix m4 all property/global gammat peratomtypepair 1 10000
fix m5 all property/global coefficientFriction peratomtypepair 1 0.5
fix m6 all property/global coefficientRestitution peratomtypepair 1 0.5
)";

}  // namespace

// Linear springs: the damped oscillator's half period pi / sqrt(kn/m* - (gamman/2m*)^2)
// with LIGGGHTS' own dashpot (damping liggghts), the undamped pi / sqrt(kn/m*) with
// another damping model; hooke/hysteresis: the stiffest branch k2Max, undamped.
TEST(Damping, ContactTimeOfLinearSpringsWithTheirDashpot) {
  const double meff = kM / 2, reff = kR / 2, e = 0.5, Ystar = 5e7 / (2 * (1 - 0.09));
  const double kn_hooke = 16.0 / 15.0 * std::sqrt(reff) * Ystar *
                          std::pow(15.0 * meff * 4.0 / (16.0 * std::sqrt(reff) * Ystar), 0.2);
  const double gn_hooke = std::sqrt(4 * meff * kn_hooke / (1 + std::pow(kPi / std::log(e), 2)));
  struct Case {
    std::string name, deck;
    double expected;
  };
  const std::vector<Case> cases = {
      {"hooke", kElastic + "pair_style gran model hooke tangential history", damped_time(kn_hooke, meff, gn_hooke)},
      {"hooke/stiffness", kStiffness + "pair_style gran model hooke/stiffness tangential history",
       damped_time(2000, meff, 20000 * meff)},
      {"hooke/stiffness, damping restitution",
       kStiffness + "pair_style gran model hooke/stiffness damping restitution tangential history",
       damped_time(2000, meff, 0)},
      {"linear/kneib", kElastic + "pair_style gran model linear/kneib tangential history",
       kPi / std::sqrt(5e7 * kR / meff * (1 - beta_of(e) * beta_of(e)))},
      {"hooke/hysteresis", kElastic + R"(fix m6 all property/global coefficientMaxElasticStiffness peratomtypepair 1 1.5
fix m7 all property/global coefficientAdhesionStiffness peratomtypepair 1 0.1
fix m8 all property/global coefficientPlasticityDepth peratomtypepair 1 0.5
pair_style gran model hooke/hysteresis tangential history)",
       kPi / std::sqrt(1.5 * kn_hooke / meff)},
  };
  for (const Case& c : cases) {
    const double t = pair_contact_time(c.deck);
    std::printf("%s: contact time %.9g s (expected %.9g s)\n", c.name.c_str(), t, c.expected);
    EXPECT_NEAR(t, c.expected, 1e-12 * c.expected) << c.name;
  }
}

}  // namespace test_contact_damping
