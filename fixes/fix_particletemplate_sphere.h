#pragma once
// fix ID group particletemplate/sphere SEED [atom_type T] [density constant RHO]
//     [radius constant R] [volume_limit V] [relative no]
// One kind of grain for insertion (LIGGGHTS 3.8). As an extension (syntax of
// later LIGGGHTS-PUBLIC), `radius uniform number MIN MAX`, `radius gaussian
// number MU SIGMA` (truncated at +-3 sigma) and `density uniform|gaussian A B`.
//
// This header is also the home of the deck random numbers used by insertion
// and by set/delete_atoms: one portable generator, seeds checked like LIGGGHTS.
#include <cstdint>

#include "core/fix.h"

namespace sable {

// xoshiro256** seeded through splitmix64: fast, long period, and the same
// stream on every platform (std:: distributions are implementation-defined,
// so they would break "same seed -> same packing" across compilers).
class Rng {
 public:
  explicit Rng(std::uint64_t seed = 1) { reseed(seed); }
  void reseed(std::uint64_t seed);
  std::uint64_t next();
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  double gaussian();                                                          // standard normal (polar Box-Muller)

 private:
  std::uint64_t s_[4] = {0, 0, 0, 0};
  double spare_ = 0.0;
  bool has_spare_ = false;
};

// Uniform [0, 1) from (seed, key) alone: per-atom random choices (set
// type/fraction, delete_atoms porosity) that do not depend on atom order.
double hashed_uniform(long seed, long key);

// Word i as a LIGGGHTS fix seed: an integer > 10000, prime, <= INT_MAX.
long parse_prime_seed(const Args& a, std::size_t i);

// A scalar distribution (LIGGGHTS probability_distribution.h).
struct Pdf {
  enum Style { Constant, Uniform, Gaussian } style = Constant;
  double a = 1.0, b = 0.0;  // constant: a; uniform: [a, b]; gaussian: mu a, sigma b
  double min() const;
  double max() const;
  double mean() const;
  double moment(int k) const;  // E[X^k] for k = 2, 3
  double draw(Rng& rng) const;
};

class FixParticletemplateSphere : public Fix {
 public:
  FixParticletemplateSphere(Simulation& s, const Args& a);
  struct Grain {
    double radius, density, mass;
    int type;
  };
  long seed = 0;
  int atom_type = 1;
  double volume_limit = 1e-12;
  Pdf radius, density;
  // Expected volume (area 4/3 pi r^3; in 2D pi r^2, sable's disc extension) and mass.
  double volume_expect() const;
  double mass_expect() const;
  Grain draw();  // next grain from this template's own stream

 private:
  Rng rng_;
};

// Grain mass as LIGGGHTS computes it: sphere in 3D, disc (pi r^2 rho) in 2D.
double grain_mass(const Simulation& sim, double r, double rho);

}  // namespace sable
