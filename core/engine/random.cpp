#include "core/engine/random.h"

#include <climits>
#include <cmath>
#include <numbers>

#include "core/engine/simulation.h"

namespace sable {

static std::uint64_t splitmix64(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

void Rng::reseed(std::uint64_t seed) {
  for (auto& s : s_) s = splitmix64(seed);
  has_spare_ = false;
}

std::uint64_t Rng::next() {
  auto rotl = [](std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); };
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9, t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double Rng::gaussian() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double g;
  polar_gaussians([this] { return uniform(); }, g, spare_);
  has_spare_ = true;
  return g;
}

double hashed_uniform(long seed, long key) {
  std::uint64_t x = static_cast<std::uint64_t>(seed) * 0x9e3779b97f4a7c15ULL ^ static_cast<std::uint64_t>(key);
  splitmix64(x);
  return static_cast<double>(splitmix64(x) >> 11) * 0x1.0p-53;
}

long parse_prime_seed(const Args& a, std::size_t i) {
  static const char* hint =
      "a random seed that is a prime number > 10000 (LIGGGHTS requires it; e.g. 15485863, 15485867, "
      "32452843, 32452867, 49979687, 49979693)";
  const long s = a.integer(i, hint);
  bool prime = s > 10000 && s <= INT_MAX;
  for (long d = 2; prime && d * d <= s; ++d)
    if (s % d == 0) prime = false;
  if (!prime) a.fail(i, hint);
  return s;
}

double Pdf::min() const { return style == Constant ? a : style == Uniform ? a : a - cut * b; }
double Pdf::max() const { return style == Constant ? a : style == Uniform ? b : a + cut * b; }

// Variance of a standard normal truncated at +-K, over its untruncated variance:
// 1 - 2 K phi(K) / (2 Phi(K) - 1) (symmetric truncation keeps the mean).
static double truncated_variance_factor(double K) {
  const double phi = std::exp(-0.5 * K * K) / std::sqrt(2 * std::numbers::pi);
  return 1 - 2 * K * phi / std::erf(K / std::numbers::sqrt2);
}
double Pdf::mean() const { return style == Uniform ? 0.5 * (a + b) : a; }

// Raw moments of the untruncated law, as LIGGGHTS uses for its expectancies
// (the +-3 sigma truncation changes E[r^3] by < 0.1 %); with an explicit `cut`
// those of the truncated law (a +-1 sigma cut keeps 29 % of the variance).
double Pdf::moment(int k) const {
  switch (style) {
    case Constant:
      return std::pow(a, k);
    case Uniform:
      return (std::pow(b, k + 1) - std::pow(a, k + 1)) / ((k + 1) * (b - a));
    case Gaussian: {
      const double var = b * b * (cut_given ? truncated_variance_factor(cut) : 1.0);
      return k == 2 ? a * a + var : a * (a * a + 3 * var);  // odd central moments vanish
    }
  }
  return 0.0;
}

double Pdf::draw(Rng& rng) const {
  switch (style) {
    case Constant:
      return a;
    case Uniform:
      return a + rng.uniform() * (b - a);
    case Gaussian: {
      double v;
      do v = a + b * rng.gaussian();
      while (v < min() || v > max());
      return v;
    }
  }
  return a;
}

double grain_mass(const Simulation& sim, double r, double rho) {
  return sim.atoms.mass_of(r, rho);
}

}  // namespace sable
