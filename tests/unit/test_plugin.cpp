// `plugin load` of tests/plugin/example_contact_plugin.cpp, an out-of-tree
// normal model (hertz/petit: Fn = sqrt(R* dn) (4/3 Y* dn - gamma vn), the Mohr
// paper's Eq. 1), registered with one SABLE_GRAN_NORMAL line, then used by
// pair_style gran and fix wall/gran like a built-in model.
//
// Head-on collision of two equal spheres at relative speed v:
//  * gamma = 0: Hertz contact, duration 2 I dmax / v (I = (2/5) B(2/5, 1/2),
//    dmax = (15 m* v^2 / (16 Y* sqrt(R*)))^(2/5)) and restitution 1;
//  * gamma > 0: the viscoelastic Hertz model m* dn'' = -rho (dn^(3/2) + A dn^(1/2) dn'),
//    rho = 4/3 Y* sqrt(R*), A = gamma / (4/3 Y*), whose restitution is
//    e = 1 - C1 A alpha^(2/5) v^(1/5) + C2 A^2 alpha^(4/5) v^(2/5),
//    alpha = rho / m*, C1 = 1.15344, C2 = 0.79826 (Schwager & Poschel, PRE 57,
//    650 (1998); alpha = rho/m* confirmed by integrating the ODE with RK4 while
//    writing this test). Truncating the series costs O(A^3) ~ 1e-5 here and the
//    time step ~1e-6, so the tolerance is 1e-4 on e (0.5 % of the dissipation 1 - e).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <memory>
#include <numbers>
#include <string>

#include <unistd.h>

#include "core/engine/version.h"
#include "core/input/style_registry.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_plugin {

using sable::test::Deck;
using sable::test::error_of;

namespace {

constexpr double kPi = std::numbers::pi;
const double kR = 0.001, kM = 4.0 / 3.0 * kPi * kR * kR * kR * 2500, kYstar = 5e7 / (2 * (1 - 0.09));

std::function<void(sable::Simulation&)> g_probe;
class FixProbe : public sable::Fix {
 public:
  FixProbe(sable::Simulation& s, const sable::Args& a) : Fix(s, a) { hooks = sable::END_OF_STEP; }
  void end_of_step() override {
    if (g_probe) g_probe(sim);
  }
};
SABLE_FIX("test/probe_plugin", FixProbe);

std::string deck_head(double gamma) {
  char g[64];
  std::snprintf(g, sizeof g, "%.17g", gamma);
  return std::string("plugin load ") + SABLE_PLUGIN_EXAMPLE + R"(
units si
atom_style granular
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor 0.0005 bin
fix m1 all property/global youngsModulus peratomtype 5e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientFriction peratomtypepair 1 0.5
fix m4 all property/global dampingPetit peratomtypepair 1 )" + g + R"(
pair_style gran model hertz/petit tangential history
pair_coeff * *
timestep 1e-7
create_atoms 1 single -0.0011 0 0 units box
create_atoms 1 single 0.0011 0 0 units box
fix i all nve/sphere
fix p all test/probe_plugin
)";
}

struct Result {
  double duration, restitution;
};

Result collide(double gamma, double v) {
  Deck d;
  d(deck_head(gamma));
  auto& at = d->atoms;
  for (std::size_t i = 0; i < 2; ++i) {
    at.set_radius_density(i, kR, 2500);
    at.v[3 * i] = at.x[3 * i] < 0 ? v / 2 : -v / 2;
  }
  auto overlap = [](sable::Simulation& s) { return 2 * kR - std::fabs(s.atoms.x[3] - s.atoms.x[0]); };
  double prev = overlap(*d), t_in = -1, t_out = -1;
  const double dt = 1e-7;
  g_probe = [&](sable::Simulation& s) {
    const double o = overlap(s);
    if (prev <= 0 && o > 0 && t_in < 0) t_in = s.time - dt * o / (o - prev);
    if (prev > 0 && o <= 0 && t_in >= 0 && t_out < 0) t_out = s.time - dt * o / (o - prev);
    prev = o;
  };
  d("run " + std::to_string(static_cast<long>((0.0003 / v + 0.0003) / dt)));
  g_probe = nullptr;
  return {t_out - t_in, std::fabs(at.v[3] - at.v[0]) / v};
}

}  // namespace

TEST(Plugin, ElasticLimitIsHertz) {
  const double v = 2.0, meff = kM / 2, reff = kR / 2;
  const Result r = collide(0.0, v);
  const double dmax = std::pow(15.0 * meff * v * v / (16.0 * kYstar * std::sqrt(reff)), 0.4);
  const double tc = 2.0 * (0.4 * std::beta(0.4, 0.5)) * dmax / v;
  std::printf("hertz/petit gamma 0: duration %.6g s (Hertz %.6g s), restitution %.7f\n", r.duration, tc,
              r.restitution);
  EXPECT_NEAR(r.duration, tc, 0.01 * tc);
  EXPECT_NEAR(r.restitution, 1.0, 1e-4);
}

TEST(Plugin, ViscoelasticRestitutionMatchesSchwagerPoschel) {
  const double meff = kM / 2, reff = kR / 2, gamma = 20.0;
  const double rho = 4.0 / 3.0 * kYstar * std::sqrt(reff), A = gamma / (4.0 / 3.0 * kYstar), alpha = rho / meff;
  for (double v : {2.0, 0.5}) {
    const double x = A * std::pow(alpha, 0.4) * std::pow(v, 0.2);
    const double e = 1 - 1.15344 * x + 0.79826 * x * x;
    const Result r = collide(gamma, v);
    std::printf("hertz/petit gamma %g v %g: restitution %.7f, Schwager-Poschel %.7f\n", gamma, v, r.restitution, e);
    EXPECT_NEAR(r.restitution, e, 1e-4) << "v = " << v;
  }
}

// Every tangential x rolling model with the plugin's normal law, on a wall
// contact evaluated at set-up (run 0: history read, not advanced, so the
// spring and the rolling spring start from zero). Grain 1 (r = 1 mm) sinks
// dn = 0.5 mm into the plane z = -0.5 mm while moving down at 5 cm/s, sliding
// at 2 cm/s along x and spinning at 10 rad/s about y. By hand (contact.h's
// conventions; wall: R* = r, cri = r - dn/2, wroll = cri w / (r - dn)):
//   s = sqrt(R* dn), Fn = s (4/3 Y* dn - gamma vn) with vn = vz < 0,
//   vtr = vx - cri w_y;  Ft = 0 (off), -min(mu Fn, gamma s |vtr|) sgn (no_history),
//   -gamma s vtr (history: zero spring at set-up, below the Coulomb cap);
//   Mr = 0 (off), rmu (4/3 Y* s dn) R* along wroll (cdt), kt R*^2 wroll dt with
//   kt = 8 G* s (epsd2: zero spring plus one step), torque_y = -cri Ft - Mr_y.
// The dashpot is 5 % of Fn here, so a dropped or doubled damping term fails.
TEST(Plugin, ModelWorksWithEveryBuiltInTangentialAndRollingModelAndWalls) {
  const double gamma = 2e4, vz = -0.05, vx = 0.02, wy = 10.0, mu = 0.5, rmu = 0.1, dt = 1e-7;
  const double dn = kR - 0.0005, s = std::sqrt(kR * dn), cri = kR - dn / 2;
  const double Gstar = 5e7 / (4 * (2 - 0.3) * (1 + 0.3));
  const double fel = 4.0 / 3.0 * kYstar * s * dn, fn = fel - gamma * s * vz;
  const double vtr = vx - cri * wy, wroll = cri / (kR - dn) * wy;
  ASSERT_GT(gamma * s * -vz, 0.04 * fn);           // the dashpot is a visible part of Fn
  ASSERT_LT(gamma * s * std::fabs(vtr), mu * fn);  // viscous friction below the Coulomb cap
  for (const char* t : {"off", "no_history", "history"})
    for (const char* r : {"off", "cdt", "epsd2"}) {
      Deck d;
      d(deck_head(gamma));
      d("fix m5 all property/global coefficientRollingFriction peratomtypepair 1 0.1");
      d(std::string("pair_style gran model hertz/petit tangential ") + t + " rolling_friction " + r);
      d("pair_coeff * *");
      d(std::string("fix w all wall/gran model hertz/petit tangential ") + t + " rolling_friction " + r +
        " primitive type 1 zplane -0.0005");
      auto& a = d->atoms;
      for (std::size_t i = 0; i < 2; ++i) a.set_radius_density(i, kR, 2500);
      const std::size_t i1 = a.index_of(1);
      a.v[3 * i1] = vx;
      a.v[3 * i1 + 2] = vz;
      a.omega[3 * i1 + 1] = wy;
      d("run 0");
      const std::string tr = std::string(t), rr = std::string(r);
      const double ft = tr == "off" ? 0.0 : -gamma * s * vtr;  // no_history: min() picks the dashpot here
      const double mr = rr == "off" ? 0.0 : rr == "cdt" ? rmu * fel * kR : 8 * Gstar * s * kR * kR * wroll * dt;
      const std::string what = tr + " " + rr;
      EXPECT_NEAR(a.f[3 * i1 + 2], fn, 1e-10 * fn) << what;
      EXPECT_NEAR(a.f[3 * i1], ft, 1e-10 * fn) << what;
      EXPECT_NEAR(a.f[3 * i1 + 1], 0.0, 1e-10 * fn) << what;
      EXPECT_NEAR(a.torque[3 * i1 + 1], -cri * ft - mr, 1e-10 * (std::fabs(cri * ft) + std::fabs(mr)) + 1e-20)
          << what;
      EXPECT_NEAR(a.torque[3 * i1], 0.0, 1e-20) << what;
      EXPECT_NEAR(a.torque[3 * i1 + 2], 0.0, 1e-20) << what;
    }
}

// The sable executable exports its symbols, so the same library loads there.
TEST(Plugin, LoadsIntoTheSableExecutable) {
  const std::string deck = "plugin_test_deck_" + std::to_string(getpid()) + ".in";
  {
    std::ofstream out(deck);
    out << deck_head(0.0).substr(0, deck_head(0.0).find("fix p all")) << "run 100\n";
  }
  std::string cmd = std::string(SABLE_BINARY) + " -in " + deck + " -log none 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  ASSERT_TRUE(pipe);
  std::string output;
  std::array<char, 512> buf;
  while (fgets(buf.data(), buf.size(), pipe.get())) output += buf.data();
  const int rc = pclose(pipe.release());
  EXPECT_EQ(rc, 0) << output;
  EXPECT_NE(output.find("Loop time"), std::string::npos) << output;
  std::remove(deck.c_str());
}

// dlopen runs a library's registrars, so `plugin load` reads the tag its sources carry
// (core/input/plugin_abi.h) from the file first: a plugin built for another version
// is refused, naming the file, its version and ours, and none of its code runs.
TEST(Plugin, RefusesAPluginBuiltForAnotherVersion) {
  Deck d;
  const std::string e = error_of(d, std::string("plugin load ") + SABLE_PLUGIN_OTHER_VERSION);
  EXPECT_NE(e.find(std::string("'") + SABLE_PLUGIN_OTHER_VERSION + "' in 'plugin load"), std::string::npos) << e;
  EXPECT_NE(e.find(std::string("it was built for sable ") + SABLE_OTHER_VERSION + " ("), std::string::npos) << e;
  EXPECT_NE(e.find(std::string("this is sable ") + sable::version() + " ("), std::string::npos) << e;
  EXPECT_EQ(sable::CommandRegistry::find("test/other_version_probe"), nullptr) << "its registrar ran";
}

TEST(Plugin, RefusesALibraryNotBuiltAgainstSablesHeaders) {
  Deck d;
  const std::string e = error_of(d, std::string("plugin load ") + SABLE_NOT_A_PLUGIN);
  EXPECT_NE(e.find(std::string("'") + SABLE_NOT_A_PLUGIN + "' in 'plugin load"), std::string::npos) << e;
  EXPECT_NE(e.find("it was not built against sable's headers"), std::string::npos) << e;
  EXPECT_EQ(std::getenv("SABLE_TEST_FOREIGN_LIBRARY_RAN"), nullptr) << "its constructor ran";
}

// A file that is no shared library still gets dlopen's reason.
TEST(Plugin, RefusesAFileThatIsNoLibrary) {
  Deck d;
  const std::string e = error_of(d, std::string("plugin load ") + SABLE_SOURCE_DIR + "/tests/plugin/restitution.in");
  EXPECT_NE(e.find("expected a loadable shared library ("), std::string::npos) << e;
}

}  // namespace test_plugin
