// read_data (LAMMPS/LIGGGHTS data files, atom_style granular/sphere): box, atoms,
// masses from diameter and density, image flags, velocities; soft_particles; errors.
#include <gtest/gtest.h>

#include <fstream>
#include <numbers>
#include <string>

#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_read_data {

using sable::test::Deck;
using sable::test::error_of;

namespace {

std::string write(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

const char* kData = R"(LIGGGHTS data file

 3  atoms
 2  atom types
 0 bonds

 -0.1  0.2 xlo xhi
 -0.1  0.2 ylo yhi
  0.0  0.4 zlo zhi

Atoms # sphere

1 1 0.02 2500 0.0 0.0 0.1
3 2 0.04 1000 0.1 0.05 0.2 1 0 -2
2 1 0.02 2500 0.05 0.0 0.1

Velocities

3 1.5 0 -2 0 0 10
1 0 0 0 0 0 0
2 0 0.25 0 1 0 0
)";

}  // namespace

TEST(ReadData, BoxAtomsMassesImagesAndVelocities) {
  Deck d;
  d("units si\natom_style sphere\nsoft_particles yes\nread_data " + write("three.data", kData) + "\n");
  const sable::Atoms& at = d->atoms;
  ASSERT_EQ(at.n, 3u);
  EXPECT_EQ(at.ntypes, 2);
  EXPECT_DOUBLE_EQ(d->domain.lo[0], -0.1);
  EXPECT_DOUBLE_EQ(d->domain.hi[2], 0.4);
  const std::size_t i = at.index_of(3);
  EXPECT_EQ(at.type[i], 2);
  EXPECT_DOUBLE_EQ(at.radius[i], 0.02);
  // mass 4/3 pi r^3 rho, round-off only
  EXPECT_NEAR(at.rmass[i], 4.0 / 3.0 * std::numbers::pi * 0.02 * 0.02 * 0.02 * 1000, 1e-15);
  EXPECT_DOUBLE_EQ(at.x[3 * i + 1], 0.05);
  EXPECT_EQ(at.image[3 * i], 1);
  EXPECT_EQ(at.image[3 * i + 2], -2);
  EXPECT_DOUBLE_EQ(at.v[3 * i], 1.5);
  EXPECT_DOUBLE_EQ(at.v[3 * i + 2], -2.0);
  EXPECT_DOUBLE_EQ(at.omega[3 * i + 2], 10.0);
  const std::size_t j = at.index_of(2);
  EXPECT_DOUBLE_EQ(at.v[3 * j + 1], 0.25);
  EXPECT_DOUBLE_EQ(at.omega[3 * j], 1.0);
}

TEST(ReadData, Errors) {
  auto err = [](const std::string& name, const std::string& text) {
    Deck d;
    return error_of(d, "units si\natom_style sphere\nread_data " + write(name, text) + "\n");
  };
  std::string s = kData;
  EXPECT_NE(err("bonds.data", std::string(s).replace(s.find(" 0 bonds"), 8, " 2 bonds")).find("no bonds"), std::string::npos);
  EXPECT_NE(err("type.data", std::string(s).replace(s.find("3 2 0.04"), 8, "3 5 0.04")).find("an atom type from 1 to 2"),
            std::string::npos);
  EXPECT_NE(err("short.data", s.substr(0, s.find("2 1 0.02 2500"))).find("2 of 3 lines read"), std::string::npos);
  EXPECT_NE(err("dup.data", std::string(s).replace(s.find("2 1 0.02 2500"), 1, "1")).find("appears twice"), std::string::npos);
  EXPECT_NE(err("masses.data", std::string(s).replace(s.find("Velocities"), 10, "Masses")).find("Atoms and Velocities"),
            std::string::npos);
  Deck d;
  EXPECT_NE(error_of(d, "units si\nread_data nofile.data\n").find("cannot open 'nofile.data'"), std::string::npos);
  Deck e;
  EXPECT_NE(error_of(e, "soft_particles maybe\n").find("yes or no"), std::string::npos);
}

// soft_particles yes lifts LIGGGHTS' youngsModulus >= 5e6 check (the hydrogel tutorial's
// E = 23.3 kPa); a modulus <= 0 stays refused.
TEST(SoftParticles, LiftsTheYoungsModulusBound) {
  const std::string deck = R"(units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 1 box
fix m1 all property/global youngsModulus peratomtype E_
fix m2 all property/global poissonsRatio peratomtype 0.5
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.9
fix m4 all property/global coefficientFriction peratomtypepair 1 0.1
pair_style gran model hertz tangential history
pair_coeff * *
create_atoms 1 single 0.5 0.5 0.5 units box
set group all diameter 0.01 density 1000
run 0
)";
  auto with = [&](const std::string& pre, const std::string& E) {
    std::string d = pre + deck;
    d.replace(d.find("E_"), 2, E);
    Deck k;
    return error_of(k, d);
  };
  EXPECT_NE(with("", "23.3e3").find("youngsModulus >= 5e6 required"), std::string::npos);
  EXPECT_EQ(with("soft_particles yes\n", "23.3e3"), "(no error)");
  EXPECT_NE(with("soft_particles yes\n", "0").find("youngsModulus > 0 required"), std::string::npos);
}

// compute_modify (the hydrogel tutorial's `compute_modify thermo_temp dynamic yes`):
// checked, and changes nothing (sable has no temperature compute).
TEST(ComputeModify, AcceptsTemperatureKeywordsAndChecksThem) {
  Deck d;
  d("units si\natom_style granular\nregion box block 0 1 0 1 0 1 units box\ncreate_box 1 box\ncompute k all ke\n");
  EXPECT_EQ(error_of(d, "compute_modify thermo_temp dynamic yes\ncompute_modify k extra/dof 0\n"), "(no error)");
  EXPECT_NE(error_of(d, "compute_modify nothere dynamic yes\n").find("an existing compute ID"), std::string::npos);
  EXPECT_NE(error_of(d, "compute_modify thermo_temp dynamic maybe\n").find("yes or no"), std::string::npos);
  EXPECT_NE(error_of(d, "compute_modify thermo_temp colour red\n").find("dynamic, dynamic/dof, extra"), std::string::npos);
}

}  // namespace test_read_data
