// model hooke/hysteresis (contact_models/normal/hooke_hysteresis.h) against the
// energy balance of its force-overlap loop, for undamped head-on collisions
// (coefficientRestitution 1: gamman = 0) of two equal grains and of a grain on
// a wall. With kn the hooke stiffness, k2Max = c2 kn, kc = cc kn and dLim =
// c2 / (c2 - 1) phiF 2 R*, the grain loads on kn up to dLim, beyond it on the
// line k2Max (d - dLim) + kn dLim; it unloads from the largest overlap dm with
// force f(dm) on a line of slope k2 (k2(dm) = kn + (k2Max - kn) dm / dLim below
// dLim, k2Max beyond), which reaches zero at d0 = dm - f(dm) / k2 and meets
// the adhesive branch -kc d at dc = k2 d0 / (k2 + kc). The energy returned is
//   W = k2/2 ((dm - d0)^2 - (dc - d0)^2) - kc/2 dc^2
// out of E = m* v^2 / 2 loaded, so e = sqrt(W / E) (kc = 0: e = sqrt(kn / k2)
// below dLim). Tolerance 1e-3 on e: the time step (contact time / ~1000) at
// the kinks of the loop.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_hooke_hysteresis {

using sable::test::Deck;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kR = 0.001, kRho = 2500, kY = 5e7, kNu = 0.3, kVchar = 1.0, kDt = 1e-7;
constexpr double kC2 = 2.0, kPhi = 0.05;
const double kMass = 4.0 / 3.0 * kPi * kR * kR * kR * kRho;

struct Law {
  double kn, k2max, kc, dlim;
};

Law law(double meff, double reff, double cc) {
  const double ys = kY / (2 * (1 - kNu * kNu));
  const double kn = 16.0 / 15.0 * std::sqrt(reff) * ys *
                    std::pow(15.0 * meff * kVchar * kVchar / (16.0 * std::sqrt(reff) * ys), 0.2);
  return {kn, kC2 * kn, cc * kn, kC2 / (kC2 - 1) * kPhi * 2 * reff};
}

// Restitution of the force-overlap loop (the header's formulas).
double loop_restitution(const Law& l, double meff, double v) {
  const double e_in = 0.5 * meff * v * v;
  double dm, fm, k2;
  if (e_in <= 0.5 * l.kn * l.dlim * l.dlim) {
    dm = std::sqrt(2 * e_in / l.kn);
    fm = l.kn * dm;
    k2 = l.kn + (l.k2max - l.kn) * dm / l.dlim;
  } else {  // 1/2 k2Max u^2 + kn dLim u + 1/2 kn dLim^2 = E, u = dm - dLim
    const double b = l.kn * l.dlim, c = 0.5 * l.kn * l.dlim * l.dlim - e_in;
    const double u = (-b + std::sqrt(b * b - 2 * l.k2max * c)) / l.k2max;
    dm = l.dlim + u;
    fm = l.k2max * u + l.kn * l.dlim;
    k2 = l.k2max;
  }
  const double d0 = dm - fm / k2, dc = k2 * d0 / (k2 + l.kc);
  const double w = 0.5 * k2 * ((dm - d0) * (dm - d0) - (dc - d0) * (dc - d0)) - 0.5 * l.kc * dc * dc;
  return w > 0 ? std::sqrt(w / e_in) : 0.0;
}

std::string head(double cc, double e = 1.0) {
  char b[1024];
  std::snprintf(b, sizeof b, R"(units si
atom_style granular
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor 0.0005 bin
timestep %.17g
fix m1 all property/global youngsModulus peratomtype %.17g
fix m2 all property/global poissonsRatio peratomtype %.17g
fix m3 all property/global coefficientRestitution peratomtypepair 1 %.17g
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix m5 all property/global characteristicVelocity scalar %.17g
fix m6 all property/global coefficientMaxElasticStiffness peratomtypepair 1 %.17g
fix m7 all property/global coefficientAdhesionStiffness peratomtypepair 1 %.17g
fix m8 all property/global coefficientPlasticityDepth peratomtypepair 1 %.17g
pair_style gran model hooke/hysteresis tangential history
pair_coeff * *
)",
                kDt, kY, kNu, e, kVchar, kC2, cc, kPhi);
  return b;
}

// Two equal grains head-on at relative speed v: the rebound speed over v.
double pair_restitution(double cc, double v) {
  Deck d;
  d(head(cc));
  d("create_atoms 1 single -0.00102 0 0 units box");
  d("create_atoms 1 single 0.00102 0 0 units box");
  for (long id : {1, 2}) {
    const std::size_t i = d->atoms.index_of(id);
    d->atoms.set_radius_density(i, kR, kRho);
    d->atoms.v[3 * i] = d->atoms.x[3 * i] < 0 ? v / 2 : -v / 2;
  }
  d("fix i all nve/sphere");
  d("run " + std::to_string(static_cast<long>((0.00004 / v + 0.0004) / kDt)));
  return (d->atoms.v[3 * d->atoms.index_of(2)] - d->atoms.v[3 * d->atoms.index_of(1)]) / v;
}

TEST(HookeHysteresis, PairRestitutionFromTheForceOverlapLoop) {
  const double meff = kMass / 2, reff = kR / 2;
  for (double cc : {0.0, 0.5})
    for (double v : {0.5, 2.0, 4.0}) {  // 4 m/s loads beyond dLim
      const Law l = law(meff, reff, cc);
      const double want = loop_restitution(l, meff, v), got = pair_restitution(cc, v);
      std::printf("hooke/hysteresis pair kc/kn %g v %g: e %.6f, loop %.6f (dmax/dLim %.3g)\n", cc, v, got, want,
                  v * std::sqrt(meff / l.kn) / l.dlim);
      EXPECT_NEAR(got, want, 1e-3) << "kc/kn " << cc << " v " << v;
    }
  // Without adhesion below dLim the closed form: e = sqrt(kn / k2(dm)).
  const Law l = law(meff, reff, 0.0);
  const double dm = 0.5 * std::sqrt(meff / l.kn);
  EXPECT_NEAR(loop_restitution(l, meff, 0.5), std::sqrt(l.kn / (l.kn + (l.k2max - l.kn) * dm / l.dlim)), 1e-12);
}

TEST(HookeHysteresis, WallRestitutionFromTheForceOverlapLoop) {
  for (double cc : {0.0, 0.5}) {
    const double v = 1.0;
    Deck d;
    d(head(cc));
    d("fix w all wall/gran model hooke/hysteresis tangential history primitive type 1 zplane -0.00102");
    d("create_atoms 1 single 0 0 0 units box");
    d->atoms.set_radius_density(0, kR, kRho);
    d->atoms.v[2] = -v;
    d("fix i all nve/sphere");
    d("run 6000");
    const Law l = law(kMass, kR, cc);  // wall: m* = m, R* = r
    const double want = loop_restitution(l, kMass, v), got = d->atoms.v[2] / v;
    std::printf("hooke/hysteresis wall kc/kn %g v %g: e %.6f, loop %.6f\n", cc, v, got, want);
    EXPECT_NEAR(got, want, 1e-3) << "kc/kn " << cc;
  }
}

TEST(HookeHysteresis, StrongAdhesionHoldsADampedPair) {
  Deck d;
  d(head(3.0, 0.3));
  d("create_atoms 1 single -0.00102 0 0 units box");
  d("create_atoms 1 single 0.00102 0 0 units box");
  for (long id : {1, 2}) {
    const std::size_t i = d->atoms.index_of(id);
    d->atoms.set_radius_density(i, kR, kRho);
    d->atoms.v[3 * i] = d->atoms.x[3 * i] < 0 ? 1.0 : -1.0;
  }
  d("fix i all nve/sphere");
  d("run 20000");
  const double gap = std::fabs(d->atoms.x[3] - d->atoms.x[0]) - 2 * kR;
  EXPECT_LT(gap, 0.0);  // still touching: the adhesive branch took the rebound
  EXPECT_LT(std::fabs(d->atoms.v[3] - d->atoms.v[0]), 0.01);
}

}  // namespace

}  // namespace test_hooke_hysteresis
