// Laws composed at run time (contact_models/composed.h) against the compiled
// ones (contact_models/kernel.h): the same scene run twice, the second time
// with SABLE_COMPOSED_LAWS=1, gives the same positions, velocities, spins,
// forces, torques, pair history and wall history, compared with == (to the
// last bit; -0 equals 0: in 2D and without rotation the compiled law leaves
// out terms that are exact zeros). The cases cover every model of every axis,
// one and two atom types (the compiled law's one-type-pair loop), 3D, 2D and
// no rotation, primitive walls, and a plugin's normal model; and a composed
// law says so once per run.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "contact_models/pair_gran.h"
#include "contact_models/registry.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_composed_law {

using sable::test::Deck;
using sable::test::entry_history;
using sable::test::printed;

namespace {

// hertz/stiffness is in no deck, so not in compiled_laws.txt: compiled here for the comparison.
const bool kHertzStiffness = sable::register_gran_model<sable::NormalHertzStiffness, sable::DampingLiggghts,
                                                        sable::TangentialNoHistory, sable::RollingCdt,
                                                        sable::CohesionSjkr2>();

struct Case {
  std::string law, keywords;
  int types = 2;
  bool plane = false, rotation = true;
};

std::string pairs(int types, const std::string& a, const std::string& b, const std::string& c) {
  return types == 1 ? "1 " + a : "2 " + a + " " + b + " " + b + " " + c;
}

// Grains of two sizes dropped into a box on a floor, against a sheared wall, with every coefficient any model reads.
std::string scene(const Case& k) {
  const int t = k.types;
  const bool hertz_stiffness = k.law.find("hertz/stiffness") != std::string::npos;
  const std::string kn = hertz_stiffness ? "2e6" : "2000", kt = hertz_stiffness ? "1.5e6" : "1500";
  const std::string gn = hertz_stiffness ? "3e4" : "300", gt = hertz_stiffness ? "2e4" : "200";
  const bool plugin = k.law.find("hertz/petit") != std::string::npos;  // tests/plugin/example_contact_plugin.cpp
  std::string s = plugin ? std::string("plugin load ") + SABLE_PLUGIN_EXAMPLE + "\n" : "";
  s += std::string("dimension ") + (k.plane ? "2 grains spheres" : "3") + R"(
units si
atom_style granular
atom_modify map array
boundary f f )" + (k.plane ? "p" : "f") + R"(
newton off
region box block -0.006 0.006 )" + (k.plane ? "0 0.02 -0.001 0.001" : "-0.006 0.006 0 0.02") + R"( units box
create_box )" + std::to_string(t) + R"( box
neighbor 0.0003 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype )" + (t == 1 ? "1e7" : "1e7 2e7") + R"(
fix m2 all property/global poissonsRatio peratomtype )" + (t == 1 ? "0.3" : "0.3 0.25") + R"(
fix m3 all property/global coefficientRestitution peratomtypepair )" + pairs(t, "0.6", "0.5", "0.4") + R"(
fix m4 all property/global coefficientFriction peratomtypepair )" + pairs(t, "0.5", "0.4", "0.3") + R"(
fix m5 all property/global coefficientRollingFriction peratomtypepair )" + pairs(t, "0.1", "0.05", "0.08") + R"(
fix m6 all property/global characteristicVelocity scalar 1.0
fix m7 all property/global kn peratomtypepair )" + pairs(t, kn, kn, kn) + R"(
fix m8 all property/global kt peratomtypepair )" + pairs(t, kt, kt, kt) + R"(
fix m9 all property/global gamman peratomtypepair )" + pairs(t, gn, gn, gn) + R"(
fix m10 all property/global gammat peratomtypepair )" + pairs(t, gt, gt, gt) + R"(
fix m11 all property/global gamman_abs peratomtypepair )" + pairs(t, "0.002", "0.003", "0.002") + R"(
fix m12 all property/global gammat_abs peratomtypepair )" + pairs(t, "0.001", "0.002", "0.001") + R"(
fix m13 all property/global cohesionEnergyDensity peratomtypepair )" + pairs(t, "5e4", "8e4", "1e5") + R"(
fix m14 all property/global dampingNormal peratomtypepair )" + pairs(t, "20", "30", "20") + R"(
fix m15 all property/global dampingTangential peratomtypepair )" + pairs(t, "20", "10", "20") + R"(
fix m16 all property/global coefficientMaxElasticStiffness peratomtypepair )" + pairs(t, "2", "2.5", "2") + R"(
fix m17 all property/global coefficientAdhesionStiffness peratomtypepair )" + pairs(t, "0.1", "0.2", "0.1") + R"(
fix m18 all property/global coefficientPlasticityDepth peratomtypepair )" + pairs(t, "0.05", "0.05", "0.05") + R"(
fix m19 all property/global dampingPetit peratomtypepair )" + pairs(t, "20", "30", "20") + R"(
pair_style gran )" + k.law + " " + k.keywords + R"(
pair_coeff * *
timestep 2e-6
lattice )" + (k.plane ? "sq" : "sc") + R"( 0.0021
region fill block -0.004 0.004 )" + (k.plane ? "0.001 0.015 -0.0005 0.0005" : "-0.004 0.004 0.001 0.012") + R"( units box
create_atoms 1 region fill
variable dd atom 0.0014+0.0006*(id*0.6180339887-floor(id*0.6180339887))
variable u atom 0.6*((id*0.7548776662-floor(id*0.7548776662))-0.5)
variable w atom -0.3-0.3*(id*0.5698402910-floor(id*0.5698402910))
variable o atom 200*((id*0.4142135624-floor(id*0.4142135624))-0.5)
set group all diameter v_dd density 2500
)";
  if (k.plane) {
    s += "set group all vx v_u vy v_w omegaz v_o\n";
  } else {
    s += "set group all vx v_u vy v_u vz v_w omegax v_o omegay v_u omegaz v_o\n";
  }
  if (t == 2) s += "set group all type/fraction 2 0.3 12345\n";
  const std::string wall = "wall/gran " + k.law + " primitive type " + std::to_string(t);
  if (k.plane) {
    s += "fix floor all " + wall + " yplane 0.0 " + k.keywords + "\n";
    s += "fix left all " + wall + " xplane -0.0055 " + k.keywords + "\n";
    s += "fix right all " + wall + " xplane 0.0055 shear y 0.05 " + k.keywords + "\n";
    s += "fix g all gravity 60 vector 0 -1 0\n";
  } else {
    s += "fix floor all " + wall + " zplane 0.0 " + k.keywords + "\n";
    s += "fix side all " + wall + " zcylinder 0.0058 0 0 shear z 0.05 " + k.keywords + "\n";
    s += "fix g all gravity 60 vector 0 0 -1\n";
  }
  s += std::string("fix i all ") + (k.rotation ? "nve/sphere" : "nve") + "\n";
  if (k.plane) s += "fix e2d all enforce2d\n";
  return s + "run 6000\n";
}

// SABLE_COMPOSED_LAWS set for the lifetime of this object.
struct AllComposed {
  AllComposed() { setenv("SABLE_COMPOSED_LAWS", "1", 1); }
  ~AllComposed() { unsetenv("SABLE_COMPOSED_LAWS"); }
};

// Values of a and b that differ (== false), with where the first one is.
long differences(const std::vector<double>& a, const std::vector<double>& b, const std::string& what,
                 std::string& first) {
  if (a.size() != b.size()) {
    if (first.empty()) first = what + ": sizes " + std::to_string(a.size()) + " and " + std::to_string(b.size());
    return 1;
  }
  long n = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i] == b[i])) {
      if (!n && first.empty()) {
        char v[80];
        std::snprintf(v, sizeof v, "]: %.17g vs %.17g", a[i], b[i]);
        first = what + "[" + std::to_string(i) + v;
      }
      ++n;
    }
  return n;
}

std::vector<double> pair_history(Deck& d) {
  auto* pair = dynamic_cast<sable::PairGran*>(d->pair.get());
  const sable::ContactStore* store = pair ? pair->history() : nullptr;
  return store ? entry_history(*store) : std::vector<double>{};
}

void expect_same_runs(const Case& k) {
  const std::string deck = scene(k);
  Deck compiled, composed;
  const std::string said = printed(deck, compiled);
  std::string said_composed;
  {
    AllComposed all;
    said_composed = printed(deck, composed);
  }
  const std::string what = k.law + " " + k.keywords;
  EXPECT_EQ(said.find("runtime-composed"), std::string::npos) << what << ": compiled, yet\n" << said;
  const std::string note = "runs on the slower runtime-composed path";
  const auto at = said_composed.find(note);
  EXPECT_NE(at, std::string::npos) << what;
  EXPECT_EQ(said_composed.find(note, at + 1), std::string::npos) << what << ": said twice";
  const auto& a = compiled->atoms;
  const auto& b = composed->atoms;
  ASSERT_EQ(a.n, b.n);
  std::string first;
  long n = differences(a.x, b.x, "x", first) + differences(a.v, b.v, "v", first) +
           differences(a.omega, b.omega, "omega", first) + differences(a.f, b.f, "f", first) +
           differences(a.torque, b.torque, "torque", first) +
           differences(pair_history(compiled), pair_history(composed), "pair history", first);
  ASSERT_EQ(a.ncolumns(), b.ncolumns());
  for (int c = 0; c < a.ncolumns(); ++c) n += differences(a.column(c), b.column(c), a.column_name(c), first);
  EXPECT_EQ(n, 0) << what << ": first " << first;
  // The scene exercised the law: grains pressed together and on the walls.
  double fmax = 0;
  for (double f : a.f) fmax = std::max(fmax, std::fabs(f));
  EXPECT_GT(fmax, 1e-6) << what;
}

}  // namespace

TEST(ComposedLaw, GivesTheCompiledLawsBitsForEveryModelOfEveryAxis) {
  ASSERT_TRUE(kHertzStiffness);
  const std::vector<Case> cases = {
      {"model hertz tangential history rolling_friction epsd2", ""},
      {"model hertz tangential history rolling_friction epsd2", "torsionTorque on", 2, true},
      {"model hertz tangential no_history rolling_friction cdt", "", 1},
      {"model hertz", "limitForce on", 2, false, false},
      {"model hertz tangential history cohesion sjkr", "tangential_reduce on"},
      {"model hertz tangential history cohesion sjkr2", "", 1, true},
      {"model hertz damping viscoelastic tangential history", ""},
      {"model hooke tangential history", "ktToKnUser on"},
      {"model hooke/hysteresis tangential history", ""},
      {"model hooke/stiffness tangential history rolling_friction epsd2", "absolute_damping on"},
      {"model hooke/stiffness damping restitution tangential history", ""},
      {"model linear/kneib tangential history", ""},
      {"model hertz/stiffness tangential no_history rolling_friction cdt cohesion sjkr2", ""},
      {"model hertz/petit tangential history", ""},  // a plugin's model (SABLE_GRAN_MODEL compiles this one)
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.law + " " + k.keywords);
    expect_same_runs(k);
  }
}

// A combination that is not compiled (cohesion with a sable damping model) runs composed and says so once.
TEST(ComposedLaw, AnyRegisteredCombinationRunsAndSaysSoOnce) {
  Deck d;
  const std::string out =
      printed(scene({"model hertz damping restitution tangential history rolling_friction cdt cohesion sjkr", ""}), d);
  const std::string note =
      "NOTE: the contact law 'model hertz damping restitution tangential history rolling_friction cdt cohesion sjkr' "
      "runs on the slower runtime-composed path (not among the compiled laws, contact_models/compiled_laws.txt)";
  const auto at = out.find(note);
  ASSERT_NE(at, std::string::npos) << out;
  EXPECT_EQ(out.find(note, at + 1), std::string::npos) << "said more than once:\n" << out;
  for (double x : d->atoms.x) ASSERT_TRUE(std::isfinite(x));
}

}  // namespace test_composed_law
