// A sphere on an inclined plane (gravity tilted by theta against a zplane
// wall, hertz + tangential history): rigid-body mechanics with Coulomb
// friction. Below the friction angle (tan theta < 7/2 mu) the sphere rolls
// without slipping, a = 5/7 g sin theta (I = 2/5 m r^2); above it slides with
// a = g (sin theta - mu cos theta). Source: any rigid-body text (e.g. Goldstein,
// or Meriam & Kraige, rolling vs slipping on an incline). The acceleration is
// a least-squares quadratic fit of x(t) after the tangential spring's start-up
// transient has died out (10 ms, ~10 damped periods); tolerance 1 %.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "core/input/style_registry.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_contact_coulomb {

using sable::test::Deck;

namespace {

std::function<void(sable::Simulation&)> g_probe;
class FixProbe : public sable::Fix {
 public:
  FixProbe(sable::Simulation& s, const sable::Args& a) : Fix(s, a) { hooks = sable::END_OF_STEP; }
  void end_of_step() override {
    if (g_probe) g_probe(sim);
  }
};
SABLE_FIX("test/probe_coulomb", FixProbe);

std::string num(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}

// Least-squares fit x = c0 + c1 t + c2 t^2; returns 2 c2.
double fitted_acceleration(const std::vector<double>& t, const std::vector<double>& x) {
  double S[5] = {0, 0, 0, 0, 0}, B[3] = {0, 0, 0};
  for (std::size_t k = 0; k < t.size(); ++k) {
    double p = 1;
    for (int m = 0; m < 5; ++m, p *= t[k]) S[m] += p;
    B[0] += x[k];
    B[1] += x[k] * t[k];
    B[2] += x[k] * t[k] * t[k];
  }
  // Normal equations [S0 S1 S2; S1 S2 S3; S2 S3 S4] c = B, by Cramer's rule on the 3x3.
  auto det = [](double a, double b, double c, double d, double e, double f, double g, double h, double i) {
    return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
  };
  const double D = det(S[0], S[1], S[2], S[1], S[2], S[3], S[2], S[3], S[4]);
  const double D2 = det(S[0], S[1], B[0], S[1], S[2], B[1], S[2], S[3], B[2]);
  return 2 * D2 / D;
}

double incline_acceleration(double theta_deg, double mu) {
  const double th = theta_deg * std::numbers::pi / 180, g = 9.81, r = 0.001, rho = 2500, Y = 5e7, nu = 0.3;
  const double m = 4.0 / 3.0 * std::numbers::pi * r * r * r * rho;
  const double ystar = Y / (2 * (1 - nu * nu));
  // Start at the static Hertz overlap so the grain sits still on the plane.
  const double d0 = std::pow(3 * m * g * std::cos(th) / (4 * ystar * std::sqrt(r)), 2.0 / 3.0);
  Deck d;
  d(R"(units si
atom_style granular
boundary f f f
region box block -0.01 0.02 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
create_atoms 1 single 0 0 0.001 units box
neighbor 0.0005 bin
fix m1 all property/global youngsModulus peratomtype 5e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-6
fix w all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix i all nve/sphere
fix p all test/probe_coulomb)");
  d("fix m4 all property/global coefficientFriction peratomtypepair 1 " + num(mu));
  d("fix g all gravity 9.81 vector " + num(std::sin(th)) + " 0 " + num(-std::cos(th)));
  d->atoms.set_radius_density(0, r, rho);
  d->atoms.x[2] = r - d0;
  std::vector<double> ts, xs;
  g_probe = [&](sable::Simulation& s) {
    if (s.step % 10 == 0 && s.time > 0.01) {
      ts.push_back(s.time);
      xs.push_back(s.atoms.x[0]);
    }
  };
  d("run 30000");
  g_probe = nullptr;
  return fitted_acceleration(ts, xs);
}

}  // namespace

TEST(CoulombIncline, RollsWithoutSlipBelowTheFrictionAngle) {
  const double th = 20 * std::numbers::pi / 180, mu = 0.5;
  ASSERT_LT(std::tan(th), 3.5 * mu);
  const double a = incline_acceleration(20, mu), want = 5.0 / 7.0 * 9.81 * std::sin(th);
  std::printf("incline 20 deg, mu 0.5 (rolling): a = %.6f m/s^2, 5/7 g sin = %.6f\n", a, want);
  EXPECT_NEAR(a, want, 0.01 * want);
}

TEST(CoulombIncline, SlidesAboveTheFrictionAngle) {
  const double th = 30 * std::numbers::pi / 180, mu = 0.1;
  ASSERT_GT(std::tan(th), 3.5 * mu);
  const double a = incline_acceleration(30, mu), want = 9.81 * (std::sin(th) - mu * std::cos(th));
  std::printf("incline 30 deg, mu 0.1 (sliding): a = %.6f m/s^2, g (sin - mu cos) = %.6f\n", a, want);
  EXPECT_NEAR(a, want, 0.01 * want);
}

}  // namespace test_contact_coulomb
