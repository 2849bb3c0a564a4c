// Fix roles (core/engine/fix.h): the traits a fix fills in once, the role it
// plays at each hook (named by `info plan`), the rigid-body role reached through
// rigid_bodies(), and the sums core hands out to per-atom tasks (AtomSum): fix
// aveforce and fix move give the same bits at 1 and 2 threads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/engine/rigid_bodies.h"
#include "core/engine/threads.h"
#include "tests/unit/deck_runner.h"

#ifdef _OPENMP
#include <omp.h>

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_fix_roles {
#endif

using sable::FixRole;
using sable::test::Deck;

namespace {

// Grains on a floor in a periodic box: about 3000, so that 2 threads split a
// block of the sums (blocks of 1024 atoms).
const char* kBed = R"D(units si
atom_style granular
boundary p p f
newton off
communicate single vel yes
region box block 0 0.02 0 0.02 0 0.03 units box
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
region fill block 0 0.02 0 0.02 0.0006 0.01 units box
create_atoms 1 region fill
variable dd atom 0.0008+0.0002*(id*0.6180339887-floor(id*0.6180339887))
variable vvx atom 0.2*((id*0.7548776662-floor(id*0.7548776662))-0.5)
set group all diameter v_dd density 2500 vx v_vvx
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix grav all gravity 9.81 vector 0 0 -1
thermo 100
)D";

struct Bits {
  std::vector<double> x, v, out;
  bool operator==(const Bits& o) const {
    auto same = [](const std::vector<double>& a, const std::vector<double>& b) {
      return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
    };
    return same(x, o.x) && same(v, o.v) && same(out, o.out);
  }
};

// Runs kBed + `fixes` at `threads` threads (every loop threaded); f_ID[1..3] of `fix_id`.
Bits run(const std::string& fixes, int threads, const char* fix_id) {
  sable::ThreadSettings& ts = sable::thread_settings();
  const sable::ThreadSettings saved = ts;
  ts.pair_atoms = ts.pair_entries = ts.loop_work = 0;
#ifdef _OPENMP
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
#endif
  Deck d;
  d(std::string(kBed) + fixes + "run 300\n");
  ts = saved;
#ifdef _OPENMP
  omp_set_num_threads(before);
#endif
  const sable::Atoms& a = d->atoms;
  Bits b;
  b.x.assign(a.x.begin(), a.x.begin() + 3 * a.n);
  b.v.assign(a.v.begin(), a.v.begin() + 3 * a.n);
  for (int k = 1; k <= 3; ++k) b.out.push_back(d->find_fix(fix_id)->compute_vector(k));
  return b;
}

}  // namespace

TEST(FixRoles, TraitsAreDeclaredOnceAndNameTheRoles) {
  Deck d;
  d(std::string(kBed) + R"(group low id <= 100
group rest id > 100
fix fr low freeze
fix mv rest move linear 0.1 NULL 0
fix integr low nve/sphere
fix flat all nve
)");
  const sable::Fix* fr = d->find_fix("fr");
  EXPECT_TRUE(fr->traits.freezes_group);
  EXPECT_TRUE(fr->traits.constraint);
  EXPECT_TRUE(fr->traits.keeps_plane);
  EXPECT_EQ(fr->role(sable::POST_FORCE), FixRole::Constraint);
  EXPECT_EQ(fr->role(sable::INITIAL_INTEGRATE), FixRole::None);  // a hook it does not hold

  const sable::Fix* g = d->find_fix("grav");
  EXPECT_TRUE(g->traits.accelerates);
  EXPECT_FALSE(g->traits.freezes_group);
  EXPECT_EQ(g->traits.acceleration[2], -9.81);
  EXPECT_EQ(g->traits.acceleration_norm(), 9.81);
  EXPECT_EQ(g->role(sable::POST_FORCE), FixRole::ForceContributor);
  EXPECT_EQ(d->find_fix("floor")->role(sable::POST_FORCE), FixRole::ForceContributor);

  const sable::Fix* mv = d->find_fix("mv");
  EXPECT_TRUE(mv->traits.prescribes_motion);
  EXPECT_FALSE(mv->traits.turns_grains.value_or(true));  // linear: no spin set
  EXPECT_EQ(mv->role(sable::INITIAL_INTEGRATE), FixRole::PrescribedMotion);
  EXPECT_EQ(d->find_fix("integr")->role(sable::FINAL_INTEGRATE), FixRole::Integrator);
  EXPECT_TRUE(d->find_fix("integr")->traits.turns_grains.value_or(false));
  EXPECT_FALSE(d->find_fix("flat")->traits.turns_grains.value_or(true));  // fix nve: translation only
  EXPECT_EQ(d->find_fix("integr")->rigid_bodies(), nullptr);
}

// `info plan` says what each fix is at each stage.
TEST(FixRoles, InfoPlanNamesTheRoles) {
  Deck d;
  const std::string out = sable::test::printed(std::string(kBed) + R"(group low id <= 100
fix fr low freeze
fix integr all nve/sphere
info plan
run 2
)",
                                               d);
  for (const char* s : {"fix floor (wall/gran, force contributor)", "fix grav (gravity, force contributor)",
                        "fix fr (freeze, constraint)", "fix integr (nve/sphere, integrator)"})
    EXPECT_NE(out.find(s), std::string::npos) << s << "\n" << out;
}

// fix rigid/small reached through its rigid-body role: each grain's body by the
// deck's numbers, shared by the grains of one body, and the body's force.
TEST(FixRoles, RigidBodiesThroughTheirRole) {
  Deck d;
  d(std::string(kBed) + R"(variable body atom floor((id+1)/2)
fix rb all rigid/small custom v_body
run 20
)");
  const sable::Fix* rb = d->find_fix("rb");
  const sable::RigidBodies* bodies = rb->rigid_bodies();
  ASSERT_NE(bodies, nullptr);
  EXPECT_EQ(rb->role(sable::INITIAL_INTEGRATE), FixRole::RigidBodies);
  EXPECT_EQ(d->find_fix("grav")->rigid_bodies(), nullptr);
  const sable::Atoms& a = d->atoms;
  double fz = 0;
  int members_of_0 = 0, first = -1;
  for (std::size_t i = 0; i < a.n; ++i) {
    const int b = bodies->body_of(i);
    ASSERT_GE(b, 0);
    EXPECT_EQ(d->body_of(i), std::make_pair(bodies, b));  // the simulation's lookup over all fixes
    if (first < 0) first = b;
    if (b == first) ++members_of_0, fz += a.f[3 * i + 2];
  }
  EXPECT_EQ(members_of_0, 2);  // grains glued in pairs by ID
  ASSERT_NE(bodies->body_force(first), nullptr);
  EXPECT_NEAR(bodies->body_force(first)[2], fz, 1e-12 * std::abs(fz) + 1e-30);
  double ke;
  EXPECT_FALSE(bodies->body_kinetic_energy(ke));  // members carry their own mass (not multisphere)
}

// fix aveforce as a two-phase atom task: core's sum over the group, then every
// member set from it; f_ID and the motion have the same bits at 1 and 2 threads.
TEST(FixRoles, AveforceSumsWithTheSameBitsAtAnyThreadCount) {
  const std::string fixes = R"(region top block INF INF INF INF 0.005 INF units box
group top region top
fix integr all nve/sphere
fix ave top aveforce 0.001 NULL NULL
)";
  const Bits one = run(fixes, 1, "ave");
  EXPECT_NE(one.out[2], 0.0);  // the group has a force to average (its weight)
#ifdef _OPENMP
  EXPECT_TRUE(run(fixes, 2, "ave") == one);
#endif
}

// fix move as per-atom tasks beside an integrator: the same bits at 1 and 2 threads.
TEST(FixRoles, MoveTasksGiveTheSameBitsAtAnyThreadCount) {
  const std::string fixes = R"(region low block INF INF INF INF INF 0.003 units box
group low region low
group free subtract all low
fix integr free nve/sphere
fix mv low move wiggle 0.0002 NULL 0 0.01
fix fr low freeze
)";
  const Bits one = run(fixes, 1, "fr");
#ifdef _OPENMP
  EXPECT_TRUE(run(fixes, 2, "fr") == one);
#endif
  Deck d;
  const std::string out = sable::test::printed(std::string(kBed) + fixes + "info plan\nrun 1\n", d);
  EXPECT_NE(out.find("initial_integrate: fix mv (move, prescribed motion)"), std::string::npos) << out;
}

}  // namespace test_fix_roles
