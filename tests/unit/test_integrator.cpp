// Free flight under gravity: velocity Verlet is exact for constant force.
#include <gtest/gtest.h>

#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_integrator {

using sable::test::Deck;

TEST(Integrator, FreeFallIsExactForConstantGravity) {
  Deck d;
  d(R"(units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0.9 units box
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere
timestep 1e-4
run 1000)");
  // z(t) = z0 - g t^2 / 2, t = 0.1 s; tolerance: round-off only (1e-12 m).
  EXPECT_NEAR(d->atoms.x[2], 0.9 - 0.5 * 9.81 * 0.01, 1e-12);
  EXPECT_NEAR(d->atoms.v[2], -0.981, 1e-12);
  EXPECT_NEAR(d->time, 0.1, 1e-12);
}

}  // namespace test_integrator
