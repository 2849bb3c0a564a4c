// One contact, frozen in place (no integrator): the kernel's force and torques
// against the LIGGGHTS 3.8 formulas written out by hand below (doc pages
// gran_model_*.txt, gran_tangential_history.txt, gran_rolling_friction_*.txt;
// formulas as in the LIGGGHTS sources normal_model_*.h, tangential_model_history.h,
// rolling_model_cdt.h / epsd2.h). Tolerance: 1e-12 relative to the vector's norm
// (round-off only; the kernel and this file evaluate the same expressions in a
// different order).
//
// `run 1` without an integrator: the setup pass does not advance the history
// (LIGGGHTS' shearupdate = 0 at setup), step 1 does once, so the tangential
// spring is shear = (vtr dt) projected on the tangent plane.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_contact_formulas {

using sable::test::Deck;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDt = 1e-6;

struct V {
  double x = 0, y = 0, z = 0;
};
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
double dotp(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V cross(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double norm(V a) { return std::sqrt(dotp(a, a)); }

// Material of the two types (and the wall, type 2).
const double Y[3] = {0, 5e6, 1e7}, NU[3] = {0, 0.3, 0.4};
const double E[3][3] = {{0, 0, 0}, {0, 0.8, 0.7}, {0, 0.7, 0.6}};
const double MU[3][3] = {{0, 0, 0}, {0, 0.5, 0.4}, {0, 0.4, 0.3}};
const double RMU[3][3] = {{0, 0, 0}, {0, 0.2, 0.15}, {0, 0.15, 0.1}};
const double KN[3][3] = {{0, 0, 0}, {0, 3e3, 2e3}, {0, 2e3, 4e3}}, KT[3][3] = {{0, 0, 0}, {0, 2e3, 1e3}, {0, 1e3, 3e3}};
const double GN[3][3] = {{0, 0, 0}, {0, 400, 300}, {0, 300, 500}}, GT[3][3] = {{0, 0, 0}, {0, 200, 100}, {0, 100, 300}};
const double GNA[3][3] = {{0, 0, 0}, {0, 0.02, 0.01}, {0, 0.01, 0.03}}, GTA[3][3] = {{0, 0, 0}, {0, 0.01, 0.005}, {0, 0.005, 0.02}};
const double KNH[3][3] = {{0, 0, 0}, {0, 4e6, 3e6}, {0, 3e6, 5e6}}, KTH[3][3] = {{0, 0, 0}, {0, 3e6, 2e6}, {0, 2e6, 4e6}};
const double VCHAR = 1.5;

const char* kMaterials = R"(fix m1 all property/global youngsModulus peratomtype 5e6 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3 0.4
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.8 0.7 0.7 0.6
fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.4 0.4 0.3
fix m5 all property/global coefficientRollingFriction peratomtypepair 2 0.2 0.15 0.15 0.1
fix m6 all property/global characteristicVelocity scalar 1.5)";
const char* kStiffness = R"(fix s1 all property/global kn peratomtypepair 2 3e3 2e3 2e3 4e3
fix s2 all property/global kt peratomtypepair 2 2e3 1e3 1e3 3e3
fix s3 all property/global gamman peratomtypepair 2 400 300 300 500
fix s4 all property/global gammat peratomtypepair 2 200 100 100 300
fix s5 all property/global gamman_abs peratomtypepair 2 0.02 0.01 0.01 0.03
fix s6 all property/global gammat_abs peratomtypepair 2 0.01 0.005 0.005 0.02)";
const char* kHertzStiffness = R"(fix s1 all property/global kn peratomtypepair 2 4e6 3e6 3e6 5e6
fix s2 all property/global kt peratomtypepair 2 3e6 2e6 2e6 4e6
fix s3 all property/global gamman peratomtypepair 2 400 300 300 500
fix s4 all property/global gammat peratomtypepair 2 200 100 100 300)";

struct Grain {
  V x, v, w;
  double r, rho;
  int type;
  double m() const { return 4.0 / 3.0 * kPi * r * r * r * rho; }
};

// What the normal model gives (LIGGGHTS' sidata.Fn, kn, kt, gamman, gammat).
struct Normal {
  double Fn, kn, kt, gn, gt;
};

Normal normal_law(const std::string& model, const std::string& kw, int a, int b, double R, double m, double dn,
                  double vn) {
  const double Ys = 1.0 / ((1 - NU[a] * NU[a]) / Y[a] + (1 - NU[b] * NU[b]) / Y[b]);
  const double Gs = 1.0 / (2 * (2 - NU[a]) * (1 + NU[a]) / Y[a] + 2 * (2 - NU[b]) * (1 + NU[b]) / Y[b]);
  const double lne = std::log(E[a][b]);
  const bool td = kw.find("tangential_damping off") == std::string::npos;
  Normal n{};
  if (model == "hertz") {
    const double beta = lne / std::sqrt(lne * lne + kPi * kPi), s = std::sqrt(R * dn);
    const double Sn = 2 * Ys * s, St = 8 * Gs * s;
    n.kn = 4.0 / 3.0 * Ys * s;
    n.kt = St;
    n.gn = -2 * std::sqrt(5.0 / 6.0) * beta * std::sqrt(Sn * m);
    n.gt = -2 * std::sqrt(5.0 / 6.0) * beta * std::sqrt(St * m);
  } else if (model == "hooke") {
    n.kn = 16.0 / 15.0 * std::sqrt(R) * Ys * std::pow(15.0 * m * VCHAR * VCHAR / (16.0 * std::sqrt(R) * Ys), 0.2);
    n.kt = kw.find("ktToKnUser on") != std::string::npos ? n.kn * 0.285714286 : n.kn;
    n.gn = std::sqrt(4 * m * n.kn / (1 + (kPi / lne) * (kPi / lne)));
    n.gt = n.gn;
  } else if (model == "hooke/stiffness") {
    n.kn = KN[a][b];
    n.kt = KT[a][b];
    const bool abs = kw.find("absolute_damping on") != std::string::npos;
    n.gn = abs ? GNA[a][b] : m * GN[a][b];
    n.gt = abs ? GTA[a][b] : m * GT[a][b];
  } else {  // hertz/stiffness
    const double s = std::sqrt(R * dn);
    n.kn = s * KNH[a][b];
    n.kt = s * KTH[a][b];
    n.gn = s * m * GN[a][b];
    n.gt = s * m * GT[a][b];
  }
  if (!td) n.gt = 0;
  n.Fn = n.kn * dn - n.gn * vn;
  if (kw.find("limitForce on") != std::string::npos && n.Fn < 0) n.Fn = 0;
  return n;
}

struct Expect {
  V f1, t1, t2;  // force on grain 1, torques on 1 and 2
};

// Hand evaluation of one contact after one history update. For a wall, g2 is
// ignored and the wall has normal en_wall, velocity vwall and type 2.
Expect by_hand(const std::string& model, const std::string& tang, const std::string& roll, const std::string& kw,
               const Grain& g1, const Grain* g2, V en_wall, double wall_gap, V vwall) {
  V en, vr;
  double dn, R, m, r, cr1, cr2 = 0;
  V wr, wroll;
  int tb;
  if (g2) {
    const V d = g1.x - g2->x;
    r = norm(d);
    en = (1.0 / r) * d;
    dn = g1.r + g2->r - r;
    R = g1.r * g2->r / (g1.r + g2->r);
    m = g1.m() * g2->m() / (g1.m() + g2->m());
    vr = g1.v - g2->v;
    cr1 = g1.r - dn / 2;
    cr2 = g2->r - dn / 2;
    wr = (cr1 * g1.w + cr2 * g2->w);  // contact-point spin, times r
    wroll = g1.w - g2->w;
    tb = g2->type;
  } else {
    en = en_wall;
    r = wall_gap;
    dn = g1.r - r;
    R = g1.r;
    m = g1.m();
    vr = g1.v - vwall;
    cr1 = g1.r - dn / 2;
    wr = cr1 * g1.w;
    wroll = (cr1 / r) * g1.w;
    tb = 2;
  }
  const int ta = g1.type;
  const double vn = dotp(vr, en);
  const V vtr = vr - vn * en - cross(wr, en);  // relative velocity of the contact points
  const Normal n = normal_law(model, kw, ta, tb, R, m, dn, vn);
  V ft;
  if (tang == "history") {
    V s = kDt * vtr;
    s = s - dotp(s, en) * en;
    ft = -n.kt * s;
    const double cap = MU[ta][tb] * std::fabs(n.Fn);
    if (n.kt * norm(s) > cap) ft = (cap / (n.kt * norm(s))) * ft;
    else ft = ft - n.gt * vtr;
  } else if (tang == "no_history") {
    const double vt = norm(vtr);
    ft = -(std::min(MU[ta][tb] * std::fabs(n.Fn), n.gt * vt) / vt) * vtr;
  }
  V mr;
  if (roll == "cdt") {
    mr = (RMU[ta][tb] * n.kn * dn * R / norm(wroll)) * wroll;
    mr = mr - dotp(mr, en) * en;
  } else if (roll == "epsd2") {
    V wt = wroll - dotp(wroll, en) * en;
    mr = (n.kt * R * R * kDt) * wt;
    const double cap = std::fabs(n.Fn) * R * RMU[ta][tb];
    if (norm(mr) > cap) mr = (cap / norm(mr)) * mr;
  }
  Expect e;
  e.f1 = n.Fn * en + ft;
  const V tor = cross(en, ft);
  e.t1 = -cr1 * tor - mr;
  e.t2 = -cr2 * tor + mr;
  return e;
}

std::string props_for(const std::string& model) {
  if (model == "hooke/stiffness") return kStiffness;
  if (model == "hertz/stiffness") return kHertzStiffness;
  return "";
}

void place(Deck& d, long id, const Grain& g) {
  auto& at = d->atoms;
  const std::size_t i = at.index_of(id);
  at.type[i] = g.type;
  at.set_radius_density(i, g.r, g.rho);
  const double x[3] = {g.x.x, g.x.y, g.x.z}, v[3] = {g.v.x, g.v.y, g.v.z}, w[3] = {g.w.x, g.w.y, g.w.z};
  for (int k = 0; k < 3; ++k) {
    at.x[3 * i + k] = x[k];
    at.v[3 * i + k] = v[k];
    at.omega[3 * i + k] = w[k];
  }
}

V vec(const std::vector<double>& a, std::size_t i) { return {a[3 * i], a[3 * i + 1], a[3 * i + 2]}; }

void expect_close(V got, V want, double tol, const std::string& what) {
  const double scale = std::max(norm(want), 1e-300);
  EXPECT_LE(norm(got - want) / scale, tol) << what << ": got (" << got.x << ", " << got.y << ", " << got.z
                                           << "), want (" << want.x << ", " << want.y << ", " << want.z << ")";
}

const Grain kG1{{0, 0, 0}, {0.1, 0.02, -0.03}, {1, 2, 3}, 0.001, 2500, 1};
const Grain kG2{{0.0024, 0.0003, 0.0001}, {-0.05, 0.01, 0.04}, {-2, 0.5, 1}, 0.0015, 3000, 2};

void check_pair(const std::string& model, const std::string& tang, const std::string& roll, const std::string& kw = "") {
  Deck d;
  d(R"(units si
atom_style granular
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 2 box
create_atoms 1 single -0.005 0 0 units box
create_atoms 2 single 0.005 0 0 units box
neighbor 0.001 bin
timestep 1e-6)");
  d(kMaterials);
  d(props_for(model));
  d("pair_style gran model " + model + " tangential " + tang + " rolling_friction " + roll + " " + kw);
  d("pair_coeff * *");
  place(d, 1, kG1);
  place(d, 2, kG2);
  d("run 1");
  const Expect e = by_hand(model, tang, roll, kw, kG1, &kG2, {}, 0, {});
  const auto& at = d->atoms;
  const std::size_t i1 = at.index_of(1), i2 = at.index_of(2);
  const std::string what = model + " " + tang + " " + roll + " " + kw;
  expect_close(vec(at.f, i1), e.f1, 1e-12, what + " force on 1");
  expect_close(vec(at.f, i2), -1.0 * e.f1, 1e-12, what + " force on 2");
  expect_close(vec(at.torque, i1), e.t1, 1e-12, what + " torque on 1");
  expect_close(vec(at.torque, i2), e.t2, 1e-12, what + " torque on 2");
}

void check_wall(const std::string& model, const std::string& tang, const std::string& roll, const std::string& kw = "") {
  Deck d;
  d(R"(units si
atom_style granular
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 2 box
create_atoms 1 single 0 0 0 units box
neighbor 0.001 bin
timestep 1e-6)");
  d(kMaterials);
  d(props_for(model));
  d("pair_style gran model " + model + " tangential " + tang + " rolling_friction " + roll + " " + kw);
  d("pair_coeff * *");
  // Plane below the grain, overlap 6e-5, sliding at 0.05 m/s along x.
  d("fix w all wall/gran model " + model + " tangential " + tang + " rolling_friction " + roll +
    " primitive type 2 zplane -0.00094 shear x 0.05 " + kw);
  place(d, 1, kG1);
  d("run 1");
  const Expect e = by_hand(model, tang, roll, kw, kG1, nullptr, {0, 0, 1}, 0.00094, {0.05, 0, 0});
  const auto& at = d->atoms;
  const std::string what = "wall " + model + " " + tang + " " + roll + " " + kw;
  expect_close(vec(at.f, 0), e.f1, 1e-12, what + " force");
  expect_close(vec(at.torque, 0), e.t1, 1e-12, what + " torque");
  // f_w[1..3] is the force the grain exerts on the wall.
  sable::Fix* w = d->find_fix("w");
  expect_close({w->compute_vector(1), w->compute_vector(2), w->compute_vector(3)}, -1.0 * e.f1, 1e-12,
               what + " wall force");
}

const char* kNormals[] = {"hertz", "hooke", "hooke/stiffness", "hertz/stiffness"};
const char* kTangentials[] = {"off", "no_history", "history"};
const char* kRollings[] = {"off", "cdt", "epsd2"};

}  // namespace

TEST(ContactFormulas, EveryPairCombinationMatchesLiggghtsFormulas) {
  for (const char* n : kNormals)
    for (const char* t : kTangentials)
      for (const char* r : kRollings) check_pair(n, t, r);
}

TEST(ContactFormulas, EveryWallCombinationMatchesLiggghtsFormulas) {
  for (const char* n : kNormals)
    for (const char* t : kTangentials)
      for (const char* r : kRollings) check_wall(n, t, r);
}

TEST(ContactFormulas, ModelKeywords) {
  check_pair("hertz", "history", "off", "tangential_damping off");
  check_pair("hooke", "history", "cdt", "ktToKnUser on");
  check_pair("hooke/stiffness", "history", "epsd2", "absolute_damping on");
  check_pair("hertz/stiffness", "no_history", "off", "tangential_damping off");
  check_wall("hooke/stiffness", "history", "off", "absolute_damping on tangential_damping off");
}

// limitForce: a fast separating contact whose damping exceeds the spring gives Fn = 0.
TEST(ContactFormulas, LimitForceClipsAttraction) {
  Deck d;
  d(R"(units si
atom_style granular
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 2 box
create_atoms 1 single 0 0 0 units box
create_atoms 1 single 0.00199999 0 0 units box
neighbor 0.001 bin
timestep 1e-6)");
  d(kMaterials);
  d("pair_style gran model hertz tangential off limitForce on");
  d("pair_coeff * *");
  d->atoms.v[3] = 5.0;  // grain 2 leaves at 5 m/s: damping would pull the grains together
  for (std::size_t i = 0; i < 2; ++i) d->atoms.set_radius_density(i, 0.001, 2500);
  d("run 0");
  EXPECT_EQ(d->atoms.f[0], 0.0);
  EXPECT_EQ(d->atoms.f[3], 0.0);
}

}  // namespace test_contact_formulas
