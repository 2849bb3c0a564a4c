#pragma once
// Deck text of 2D scenes of grains with linear springs (hooke/stiffness, kn =
// 2000 N/m, kt = 1000 N/m, absolute damping): a grain pair at rest overlapping
// by delta carries F = kn delta, normal. Used by the compute stress/cg and
// contact/fabric tests.
#include <cmath>
#include <cstdio>
#include <string>

namespace sable::test {

// The box [0, lx] x [0, ly] (z: +-1 mm), boundary e.g. "p p p", no grains yet.
inline std::string spring_scene_2d(const std::string& dimension, const std::string& boundary, double lx, double ly) {
  char box[160];
  std::snprintf(box, sizeof box, "region box block 0 %.17g 0 %.17g -0.001 0.001 units box\n", lx, ly);
  return dimension + "\nunits si\natom_style granular\nboundary " + boundary + "\n" + box + R"(create_box 1 box
neighbor 0.0004 bin
fix k1 all property/global kn peratomtypepair 1 2000
fix k2 all property/global kt peratomtypepair 1 1000
fix k3 all property/global gamman_abs peratomtypepair 1 0.02
fix k4 all property/global gammat_abs peratomtypepair 1 0.01
fix k5 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hooke/stiffness tangential history absolute_damping on
pair_coeff * *
timestep 1e-6
)";
}

// A periodic lattice of grains of diameter d = 2 mm at spacing a < d (every
// contact overlaps by d - a: F = kn (d - a)): `lattice sq` (x = i a, y = j a) or
// `lattice hex` (horizontal rows sqrt(3)/2 a apart, every other one shifted by
// a/2), nx by ny cells (hex: two grains a cell, the box sqrt(3) a ny high).
inline std::string lattice_deck(const std::string& dimension, bool hex, double a, int nx, int ny) {
  const double lx = nx * a, ly = ny * a * (hex ? std::sqrt(3.0) : 1.0);
  char lat[80];
  std::snprintf(lat, sizeof lat, "lattice %s %.17g\n", hex ? "hex" : "sq", a);
  return spring_scene_2d(dimension, "p p p", lx, ly) + lat + "create_atoms 1 box\nset group all diameter 0.002 density 2500\n";
}

}  // namespace sable::test
