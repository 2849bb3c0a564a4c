#pragma once
// fix ID group particletemplate/multisphere SEED [atom_type T] density constant RHO
//     nspheres N ntry M spheres (file F scale S | x1 y1 z1 r1 ... xN yN zN rN) type MT
//     [mass M inertia_tensor Ixx Ixy Ixz Iyy Iyz Izz use_volume|use_density]
//     [fflag on|off x3] [tflag on|off x3]
// A clump of N spheres for insertion, moved as one rigid body by fix
// multisphere (LIGGGHTS 3.8). Mass, centre of mass and inertia tensor by
// LIGGGHTS' Monte Carlo: M points uniform in the spheres' bounding box, a
// point inside any sphere counted once; volume = hits / M * box volume, centre
// = mean of the hits (the spheres are then shifted so that it is the origin);
// a second set of M points gives the inertia tensor about it, times RHO * box
// volume / M. With `mass` and `inertia_tensor` no Monte Carlo fixes them:
// use_density keeps the spheres where given (the centre of mass at the origin)
// and the volume is M / RHO; use_volume takes volume and centre from the Monte
// Carlo and the density as M / volume.
#include <array>
#include <vector>

#include "fixes/fix_particletemplate_sphere.h"

namespace sable {

// A clump as inserted: spheres in the body frame (principal axes, centre of
// mass at the origin), mass, principal moments, the template's orientation.
struct ClumpShape {
  std::vector<std::array<double, 3>> displace;
  std::vector<double> radius;
  double mass = 0, volume = 0, density = 0;
  double r_bound = 0;  // largest |displace| + r: the clump fits in this sphere about its centre
  std::array<double, 3> moments{};
  std::array<double, 4> q{1, 0, 0, 0};  // body axes in the world frame, as a quaternion (w x y z)
  std::array<bool, 3> fflag{true, true, true}, tflag{true, true, true};
  int ms_type = 0;
};

// The template's own keywords, parsed while the sphere template's constructor
// reads the shared ones (a base constructed first, so it exists by then).
struct MultisphereSpec {
  std::vector<std::array<double, 3>> x;  // sphere centres, input frame
  std::vector<double> r;
  long nspheres = 0, ntry = 0;
  int ms_type = 0;
  double mass = -1;
  int use_density = -1;  // -1: not given, 0: use_volume, 1: use_density
  bool tensor_given = false;
  std::array<double, 9> tensor{};
  std::array<bool, 3> fflag{true, true, true}, tflag{true, true, true};
  bool keyword(const Args& a, std::size_t& i);
  void read_file(const Args& a, std::size_t at, double scale);
};

class FixParticletemplateMultisphere : private MultisphereSpec, public FixParticletemplateSphere {
 public:
  FixParticletemplateMultisphere(Simulation& s, const Args& a);
  double volume_expect() const override { return shape_.volume; }
  double mass_expect() const override { return shape_.mass; }
  Grain draw() override { return {shape_.r_bound, shape_.density, shape_.mass, atom_type, &shape_}; }
  const ClumpShape& shape() const { return shape_; }
  // The inertia tensor about the centre of mass in the input frame (row-major),
  // and that centre in the input frame, for tests and the log.
  const std::array<double, 9>& inertia_tensor() const { return tensor; }
  const std::array<double, 3>& centre_of_mass() const { return xcm_; }

 private:
  ClumpShape shape_;
  std::array<double, 3> xcm_{};
  void monte_carlo(bool centre, bool inertia);
  void finish(const Args& a);
};

}  // namespace sable
