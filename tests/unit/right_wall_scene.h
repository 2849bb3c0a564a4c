#pragma once
// The scene of the wall-contact recorder tests (compute wall/gran/slices, dump local):
// one Hertz material, a plane wall at x = 0.01 (fix right), no gravity, and the
// analytic force of a grain at rest pressed into it.
#include <cmath>

namespace sable::test::right_wall {

constexpr double kR = 0.0008, kRho = 2500, kE = 5e7, kNu = 0.3;
constexpr double kWall = 0.01;

inline const char* kScene = R"(units si
atom_style granular
boundary f f f
region box block -0.01 0.011 -0.005 0.02 -0.01 0.01 units box
create_box 1 box
neighbor 0.0002 bin
fix m1 all property/global youngsModulus peratomtype 5e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-6
fix right all wall/gran model hertz tangential history primitive type 1 xplane 0.01)";

// LIGGGHTS' Hertz against a wall (R* = r, Y* = E / (2 (1 - nu^2))): F = 4/3 Y* sqrt(r) delta^1.5.
inline double hertz(double delta) {
  const double ystar = kE / (2 * (1 - kNu * kNu));
  return 4.0 / 3.0 * ystar * std::sqrt(kR) * std::pow(delta, 1.5);
}

}  // namespace sable::test::right_wall
