#pragma once
// fix ID group particletemplate/sphere SEED [atom_type T] [density constant RHO]
//     [radius constant R] [volume_limit V] [relative no]
// One kind of grain for insertion (LIGGGHTS 3.8). As an extension (syntax of
// later LIGGGHTS-PUBLIC), `radius uniform number MIN MAX`, `radius gaussian
// number MU SIGMA [cut K]` (truncated at +-3 sigma, or at +-K sigma with sable's
// `cut`) and `density uniform|gaussian A B [cut K]`.
// Random numbers and distributions: core/engine/random.h.
#include <cstdint>
#include <functional>

#include "core/engine/fix.h"
#include "core/engine/random.h"

namespace sable {

struct ClumpShape;  // fixes/fix_particletemplate_multisphere.h

class FixParticletemplateSphere : public Fix {
 public:
  FixParticletemplateSphere(Simulation& s, const Args& a);
  // --export-yade: a definition only; the grains it made are in the atoms.
  void export_yade(YadeScript&) const override {}
  struct Grain {
    double radius, density, mass;  // a clump: its bounding radius, density and mass
    int type;
    const ClumpShape* clump = nullptr;  // set for a particletemplate/multisphere grain
  };
  long seed = 0;
  int atom_type = 1;
  double volume_limit = 1e-12;
  Pdf radius, density;
  // Expected volume (area 4/3 pi r^3; in 2D pi r^2, sable's disc extension) and mass.
  virtual double volume_expect() const;
  virtual double mass_expect() const;
  virtual Grain draw();  // next grain from this template's own stream

 protected:
  // For particletemplate/multisphere: `extra` consumes its own keywords at a[i]
  // (advancing i; false if a[i] is none); `radius` is then refused.
  using Keywords = std::function<bool(const Args&, std::size_t&)>;
  FixParticletemplateSphere(Simulation& s, const Args& a, const Keywords& extra);
  Rng rng_;
};

}  // namespace sable
