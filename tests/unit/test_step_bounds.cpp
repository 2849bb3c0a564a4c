// Simulation::step_bounds, the numbers behind the setup time-step check: the Rayleigh
// time of 2D grains (whose `density` is per area) and the free-fall speed scale.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_step_bounds {

using sable::test::Deck;

namespace {
const std::string kMaterials = R"D(fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
)D";
}  // namespace

TEST(StepBounds, RayleighTimeIn2DUsesTheSphereVolumeDensity) {
  // LIGGGHTS 2D: `set density` is per area, m = pi r^2 rho_A. The Rayleigh time
  // T_R = pi r sqrt(rho/G) / (0.1631 nu + 0.8766), G = E / (2 (1 + nu)) (LIGGGHTS'
  // fix check/timestep/gran, as in PairGran::rayleigh_time) needs the volume density
  // of the sphere with that mass, rho = m / (4/3 pi r^3) = 3 rho_A / (4 r): here
  // rho_A = 3 kg/m^2 and r = 1 mm give rho = 2250 kg/m^3, T_R = 8.210e-5 s
  // (taking rho_A as a volume density gives 3.00e-6 s). Tolerance 1e-12 relative.
  const double r = 0.001, rhoA = 3.0, E = 1e7, nu = 0.3;
  Deck d;
  d("units si\natom_style granular\ndimension 2\nboundary f f p\n"
    "region box block -0.01 0.01 -0.01 0.01 -0.001 0.001 units box\ncreate_box 1 box\n"
    "neighbor 0.0005 bin\n" +
    kMaterials +
    "create_atoms 1 single 0 0 0 units box\n"
    "set atom 1 diameter 0.002 density 3\n"
    "timestep 1e-7\nfix i all nve/sphere\nfix e2d all enforce2d\nrun 0\n");
  const double m = std::numbers::pi * r * r * rhoA;
  ASSERT_NEAR(d->atoms.rmass[0], m, 1e-12 * m) << "2D mass is per area";
  const double rho = m / (4.0 / 3.0 * std::numbers::pi * r * r * r), G = E / (2.0 * (1.0 + nu));
  EXPECT_NEAR(rho, 2250.0, 1e-9);
  const double expected = std::numbers::pi * r * std::sqrt(rho / G) / (0.1631 * nu + 0.8766);
  EXPECT_NEAR(expected, 8.20989e-5, 1e-10);  // hand value
  const auto b = d->step_bounds();
  ASSERT_TRUE(b.valid);
  EXPECT_NEAR(b.rayleigh, expected, 1e-12 * expected);
}

namespace {
// A 0.1 x 0.1 x 0.02 m box, periodic in x and y, walls (f) in z, gravity 9.81 along -z,
// one grain in the middle moving at vx.
sable::Simulation::StepBounds bounds_with_gravity(const std::string& boundary, double vx) {
  Deck d;
  d("units si\natom_style granular\nboundary " + boundary +
    "\nregion box block 0 0.1 0 0.1 0 0.02 units box\ncreate_box 1 box\nneighbor 0.0005 bin\n" + kMaterials +
    "create_atoms 1 single 0.05 0.05 0.01 units box\n"
    "set atom 1 diameter 0.002 density 2500 vx " +
    std::to_string(vx) + "\ntimestep 1e-7\nfix i all nve/sphere\nfix g all gravity 9.81 vector 0 0 -1\nrun 0\n");
  return d->step_bounds();
}
}  // namespace

TEST(StepBounds, FreeFallSpeedOnlyAlongNonPeriodicAxes) {
  // Speed scale = max(fastest grain, free fall sqrt(2 g h)), h the largest non-periodic box
  // length: grains cannot fall across a periodic axis. Here h = Lz = 0.02 m, not Lx = Ly = 0.1 m:
  // sqrt(2 * 9.81 * 0.02) = 0.626 m/s (0.1 m would give 1.40 m/s). Tolerance 1e-12 relative.
  const double fall = std::sqrt(2.0 * 9.81 * 0.02);
  const auto rest = bounds_with_gravity("p p f", 0.0);
  ASSERT_TRUE(rest.valid);
  EXPECT_NEAR(rest.speed, fall, 1e-12 * fall);
  // A grain faster than the fall (1 m/s) but slower than sqrt(2 g Lx) sets the scale itself.
  const auto fast = bounds_with_gravity("p p f", 1.0);
  EXPECT_NEAR(fast.speed, 1.0, 1e-12);
}

TEST(StepBounds, NoFreeFallInAFullyPeriodicBox) {
  // No wall to fall onto: the speed scale is the fastest grain alone (0.3 m/s here).
  const auto b = bounds_with_gravity("p p p", 0.3);
  ASSERT_TRUE(b.valid);
  EXPECT_NEAR(b.speed, 0.3, 1e-12);
}

// Before the first run the pair style has no law yet: step_bounds() answers (no contact
// time, so no bound from it) instead of reading a law that does not exist (it crashed).
TEST(StepBounds, BeforeTheFirstRunThereIsNoContactTime) {
  Deck d;
  d("units si\natom_style granular\nregion box block 0 0.1 0 0.1 0 0.02 units box\ncreate_box 1 box\n" + kMaterials +
    "create_atoms 1 single 0.05 0.05 0.01 units box\nset atom 1 diameter 0.002 density 2500\n");
  const auto b = d->step_bounds();
  ASSERT_TRUE(b.valid);
  EXPECT_TRUE(std::isinf(b.hertz));
  d("timestep 1e-7\nfix i all nve/sphere\nrun 0");
  EXPECT_TRUE(std::isfinite(d->step_bounds().hertz));
}

}  // namespace test_step_bounds
