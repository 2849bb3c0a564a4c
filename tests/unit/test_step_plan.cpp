// The step plan (core/engine/step_plan.h): the plain plan runs every hook as LIGGGHTS
// does; each rewrite (fuse, fold gravity, pipeline, prescan) must give the bits
// of the plain plan, at 1 and 2 threads, and must change the plan it claims to
// change (else the comparison shows nothing).
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/engine/threads.h"
#include "tests/unit/deck_runner.h"

#ifdef _OPENMP
#include <omp.h>

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_step_plan {
#endif

using sable::test::Deck;

namespace {

// Grains falling on a floor in a periodic box, with gravity last: every rewrite applies.
const char* kFree = R"D(units si
atom_style granular
boundary p p f
newton off
communicate single vel yes
region box block 0 0.01 0 0.01 0 0.03 units box
create_box 1 box
neighbor 0.0004 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 4e-6
lattice sc 0.00105
region fill block 0 0.01 0 0.01 0.0006 0.01 units box
create_atoms 1 region fill
variable dd atom 0.0008+0.0002*(id*0.6180339887-floor(id*0.6180339887))
variable vvx atom 0.2*((id*0.7548776662-floor(id*0.7548776662))-0.5)
set group all diameter v_dd density 2500 vx v_vvx
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix integr all nve/sphere
fix grav all gravity 9.81 vector 0 0 -1
thermo 400
)D";

// The same grains glued into pairs along x (fix rigid/small: a two-phase integrator).
std::string clumps() {
  std::string deck = kFree;
  const std::string integ = "fix integr all nve/sphere";
  deck.replace(deck.find(integ), integ.size(),
               "variable body atom floor(x/0.0021)+100*floor(y/0.00105)+10000*floor(z/0.00105)+1\n"
               "fix rb all rigid/small custom v_body");
  return deck;
}

struct Result {
  std::vector<double> x, v, omega;
  long fused = 0, folded = 0, cleared = 0, prescans = 0;
  std::string plan;
  bool same_bits(const Result& o) const {
    auto same = [](const std::vector<double>& a, const std::vector<double>& b) {
      return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
    };
    return same(x, o.x) && same(v, o.v) && same(omega, o.omega);
  }
};

Result run(const std::string& deck, const std::string& steps, unsigned rewrites, int threads = 1) {
  sable::ThreadSettings& ts = sable::thread_settings();
  const sable::ThreadSettings saved = ts;
  ts.pair_atoms = ts.pair_entries = ts.loop_work = 0;  // every loop threaded
#ifdef _OPENMP
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
#endif
  Deck d;
  d->plan_rewrites = rewrites;
  const std::string out = sable::test::printed("info plan\n" + deck + steps, d);
  ts = saved;
#ifdef _OPENMP
  omp_set_num_threads(before);
#endif
  const sable::Atoms& a = d->atoms;
  Result r;
  r.x.assign(a.x.begin(), a.x.begin() + 3 * a.n);
  r.v.assign(a.v.begin(), a.v.begin() + 3 * a.n);
  r.omega.assign(a.omega.begin(), a.omega.begin() + 3 * a.n);
  r.fused = d->fused_steps, r.folded = d->folded_steps, r.cleared = d->cleared_steps;
  r.prescans = d->neighbor.prescans_used;
  const auto at = out.rfind("Step plan");
  r.plan = at == std::string::npos ? "" : out.substr(at, out.find("\nLoop time", at) - at);
  return r;
}

using sable::kFold, sable::kFuse, sable::kPipeline, sable::kPrescan, sable::kAllRewrites;

}  // namespace

TEST(StepPlan, PlainPlanRunsTheHooksInLiggghtsOrder) {
  const Result r = run(kFree, "run 10\n", 0);
  const auto at = [&](const char* s) { return r.plan.find(s); };
  ASSERT_NE(at("Step plan (plain)"), std::string::npos) << r.plan;
  EXPECT_LT(at("initial_integrate: fix integr"), at("neighbour list check"));
  EXPECT_LT(at("neighbour list check"), at("atom pass: clear forces"));
  EXPECT_LT(at("atom pass: clear forces"), at("force pass"));
  EXPECT_LT(at("post_force: fix floor"), at("post_force: fix grav"));
  EXPECT_LT(at("post_force: fix grav"), at("final_integrate: fix integr"));
  EXPECT_EQ(r.fused, 0);
  EXPECT_EQ(r.cleared, 0);
}

// Each rewrite added in turn: the same bits as the plain plan, and the plan changed.
TEST(StepPlan, EachRewriteGivesTheBitsOfThePlainPlan) {
  const std::string steps = "run 1200\n";
  const Result plain = run(kFree, steps, 0);
  const Result fused = run(kFree, steps, kFuse);
  EXPECT_NE(fused.plan.find("[after a quiet step] atom pass: fix integr (nve/sphere, integrator): second half kick, first half "
                            "kick and drift (one loop); clear forces"),
            std::string::npos)
      << fused.plan;
  EXPECT_EQ(fused.fused, 1197);  // all but the thermo steps 400, 800 and the last
  EXPECT_EQ(fused.cleared, 1200);
  EXPECT_TRUE(fused.same_bits(plain)) << "fuse";
  const Result folded = run(kFree, steps, kFuse | kFold);
  EXPECT_NE(folded.plan.find("[after a quiet step] atom pass: add m a of fix grav"), std::string::npos) << folded.plan;
  EXPECT_EQ(folded.folded, 1197);
  EXPECT_TRUE(folded.same_bits(plain)) << "fuse + fold";
  const Result piped = run(kFree, steps, kFuse | kPipeline);
  EXPECT_NE(piped.plan.find("[quiet steps] force pass, then on each range: fix floor (wall/gran, force contributor): "
                            "post_force; fix grav (gravity, force contributor): post_force; fix integr (nve/sphere, "
                            "integrator): second half kick, first"),
            std::string::npos)
      << piped.plan;
  EXPECT_TRUE(piped.same_bits(plain)) << "fuse + pipeline";
  const Result all = run(kFree, steps, kAllRewrites);
  EXPECT_NE(all.plan.find("scan displacements for the rebuild check"), std::string::npos) << all.plan;
  EXPECT_GT(all.prescans, 0);
  EXPECT_TRUE(all.same_bits(plain)) << "all rewrites";
#ifdef _OPENMP
  EXPECT_TRUE(run(kFree, steps, kAllRewrites, 2).same_bits(plain)) << "all rewrites, 2 threads";
  EXPECT_TRUE(run(kFree, steps, 0, 2).same_bits(plain)) << "plain plan, 2 threads";
#endif
  EXPECT_FALSE(run(kFree, "run 1201\n", 0).same_bits(plain)) << "one step more made no difference: the test shows nothing";
}

// A two-phase integrator (rigid bodies): fused with its phases, gravity not
// folded (its bodies sum members other threads hold), the scan in its placing phase.
TEST(StepPlan, RigidBodiesFusedInTwoPhasesWithTheBitsOfThePlainPlan) {
  const std::string steps = "run 1200\n";
  const Result plain = run(clumps(), steps, 0);
  const Result fused = run(clumps(), steps, kFuse);
  const Result all = run(clumps(), steps, kAllRewrites);
  EXPECT_NE(all.plan.find("second half kick; fix rb (rigid/small, rigid-body integrator): first half kick and drift; fix rb "
                          "(rigid/small, rigid-body integrator): first half kick and drift (phase 2); clear forces; scan "
                          "displacements"),
            std::string::npos)
      << all.plan;
  EXPECT_EQ(all.plan.find("add m a"), std::string::npos) << all.plan;
  EXPECT_EQ(all.fused, 1197);
  EXPECT_EQ(all.cleared, 1200);
  EXPECT_EQ(all.folded, 0);
  EXPECT_GT(all.prescans, 0);
  EXPECT_TRUE(fused.same_bits(plain)) << "fuse";
  EXPECT_TRUE(all.same_bits(plain)) << "all rewrites";
  EXPECT_NE(plain.omega, std::vector<double>(plain.omega.size(), 0.0)) << "no body turned: the test shows little";
#ifdef _OPENMP
  EXPECT_TRUE(run(clumps(), steps, kAllRewrites, 2).same_bits(plain)) << "all rewrites, 2 threads";
#endif
}

TEST(StepPlan, InfoTakesOnlyPlan) {
  Deck d;
  try {
    d("info fixes");
    FAIL() << "info fixes was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("'plan'"), std::string::npos) << e.what();
  }
}

}  // namespace test_step_plan
