// Rolling friction on a plane. A sphere rolling without slip under gravity on
// a zplane wall feels a constant rolling torque Mr = mu_r R* Fn opposing its
// spin (CDT: mu_r kn dn R* with kn dn = m g at rest on the plane, R* = r for a
// wall). With the friction force F at the contact and I = 2/5 m r^2:
//   m a = F,  I a / r = -F r - Mr   =>   a = -Mr r / (I + m r^2) = -(5/7) mu_r g.
// (Ai et al., Powder Technol. 206 (2011), model A.) EPSD2's spring saturates at
// the same torque mu_r R* |Fn| once rolling, so it decelerates at the same
// rate after a short transient. The deceleration is a straight-line fit of
// v(t) while the sphere still rolls; tolerance 1 %.
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
namespace test_contact_rolling {

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
SABLE_FIX("test/probe_rolling", FixProbe);

double slope(const std::vector<double>& t, const std::vector<double>& v) {
  double st = 0, sv = 0, stt = 0, stv = 0;
  const double n = static_cast<double>(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) {
    st += t[k];
    sv += v[k];
    stt += t[k] * t[k];
    stv += t[k] * v[k];
  }
  return (n * stv - st * sv) / (n * stt - st * st);
}

double rolling_deceleration(const std::string& model, double mu_r) {
  const double r = 0.001, rho = 2500, g = 9.81, ystar = 5e7 / (2 * (1 - 0.09));
  const double m = 4.0 / 3.0 * std::numbers::pi * r * r * r * rho;
  const double d0 = std::pow(3 * m * g / (4 * ystar * std::sqrt(r)), 2.0 / 3.0);
  const double v0 = 0.05;
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
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
timestep 1e-6
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere
fix p all test/probe_rolling)");
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", mu_r);
  d(std::string("fix m5 all property/global coefficientRollingFriction peratomtypepair 1 ") + buf);
  d("pair_style gran model hertz tangential history rolling_friction " + model);
  d("pair_coeff * *");
  d("fix w all wall/gran model hertz tangential history rolling_friction " + model + " primitive type 1 zplane 0.0");
  auto& at = d->atoms;
  at.set_radius_density(0, r, rho);
  at.x[2] = r - d0;
  at.v[0] = v0;
  at.omega[1] = v0 / r;  // rolling without slip along +x: v - w x (r e_z) = 0
  std::vector<double> ts, vs;
  g_probe = [&](sable::Simulation& s) {
    const double v = s.atoms.v[0];
    if (s.step % 10 == 0 && s.time > 0.005 && v > 0.2 * v0) {
      ts.push_back(s.time);
      vs.push_back(v);
    }
  };
  d("run 50000");
  g_probe = nullptr;
  return -slope(ts, vs);
}

}  // namespace

TEST(RollingFriction, CdtDeceleratesAtFiveSeventhsMuRG) {
  const double mu_r = 0.1, want = 5.0 / 7.0 * mu_r * 9.81;
  const double a = rolling_deceleration("cdt", mu_r);
  std::printf("rolling cdt mu_r 0.1: deceleration %.6f m/s^2, 5/7 mu_r g = %.6f\n", a, want);
  EXPECT_NEAR(a, want, 0.01 * want);
}

TEST(RollingFriction, Epsd2SaturatesAtTheSameTorque) {
  const double mu_r = 0.1, want = 5.0 / 7.0 * mu_r * 9.81;
  const double a = rolling_deceleration("epsd2", mu_r);
  std::printf("rolling epsd2 mu_r 0.1: deceleration %.6f m/s^2, 5/7 mu_r g = %.6f\n", a, want);
  EXPECT_NEAR(a, want, 0.01 * want);
}

TEST(RollingFriction, NoRollingFrictionKeepsRolling) {
  const double a = rolling_deceleration("off", 0.1);
  EXPECT_NEAR(a, 0.0, 1e-3);
}

}  // namespace test_contact_rolling
