#pragma once
// Deck random numbers and grain size/density distributions, shared by
// insertion (fixes) and set / delete_atoms (core): one portable generator,
// seeds checked like LIGGGHTS; and the grain mass as LIGGGHTS computes it.
#include <cmath>
#include <cstdint>

#include "core/input/args.h"

namespace sable {

class Simulation;

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

// Marsaglia's polar method: two independent standard normal deviates from
// uniform() on [0, 1) (Rng and the LAMMPS generator of the deck's normal()).
template <class Uniform>
void polar_gaussians(Uniform&& uniform, double& first, double& second) {
  double u, v, s;
  do {
    u = 2.0 * uniform() - 1.0;
    v = 2.0 * uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double f = std::sqrt(-2.0 * std::log(s) / s);
  first = u * f;
  second = v * f;
}

// Uniform [0, 1) from (seed, key) alone: per-atom random choices (set
// type/fraction, delete_atoms porosity) that do not depend on atom order.
double hashed_uniform(long seed, long key);

// Word i as a LIGGGHTS fix seed: an integer > 10000, prime, <= INT_MAX.
long parse_prime_seed(const Args& a, std::size_t i);

// A scalar distribution (LIGGGHTS probability_distribution.h).
struct Pdf {
  enum Style { Constant, Uniform, Gaussian } style = Constant;
  double a = 1.0, b = 0.0;  // constant: a; uniform: [a, b]; gaussian: mu a, sigma b
  // gaussian: values outside mu +- cut sigma are drawn again. LIGGGHTS' fixed
  // +-3 sigma unless `cut K` was given (cut_given), when moments are the truncated law's.
  double cut = 3.0;
  bool cut_given = false;
  double min() const;
  double max() const;
  double mean() const;
  double moment(int k) const;  // E[X^k] for k = 2, 3
  double draw(Rng& rng) const;
};

// Grain mass from radius and density: Atoms::mass_of (sphere in 3D; in 2D a disc,
// pi r^2 rho, as LIGGGHTS, unless `dimension 2 grains spheres`).
double grain_mass(const Simulation& sim, double r, double rho);

}  // namespace sable
