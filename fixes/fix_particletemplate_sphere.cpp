#include "fixes/fix_particletemplate_sphere.h"

#include <climits>
#include <cmath>
#include <numbers>

#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {


// Optional `cut K` after a gaussian's MU SIGMA (sable extension, petit2017's
// +-1 sigma radii): values outside mu +- K sigma are drawn again, and any
// sigma is allowed while mu - K sigma > 0. Without it LIGGGHTS' +-3 sigma and
// its refusal of mu - 3 sigma < 0 (delta > 33 %) stand, so its decks mean the same.
static void parse_cut(const Args& a, std::size_t& i, Pdf& p) {
  if (i < a.size() && a[i] == "cut") {
    p.cut = a.num(i + 1, "the cut K (values outside mu +- K sigma are drawn again)");
    if (!(p.cut >= 0.1 && p.cut <= 10)) a.fail(i + 1, "a cut K between 0.1 and 10 (in sigmas)");
    if (!(p.a - p.cut * p.b > 0)) a.fail(i + 1, "a cut K with mu - K sigma > 0 (radii stay positive)");
    p.cut_given = true;
    i += 2;
  } else if (p.a - 3 * p.b < 0) {
    a.fail(i - 1, "mu - 3 sigma >= 0 (values are drawn within +-3 sigma; 'cut K' after sigma narrows it)");
  }
}

// Parses `constant V | uniform [number] MIN MAX | gaussian [number] MU SIGMA` at word i
// (the `number` word is required for radius, as in LIGGGHTS-PUBLIC, and absent for density).
static Pdf parse_pdf(const Args& a, std::size_t& i, const char* what, bool number_word) {
  Pdf p;
  const std::string expect =
      std::string("a ") + what + " style: constant" +
      (number_word ? ", uniform number MIN MAX or gaussian number MU SIGMA" : ", uniform MIN MAX or gaussian MU SIGMA");
  const std::string& s = a.word(i, expect);
  if (s == "constant") {
    p.a = a.num(i + 1, std::string("the ") + what);
    if (!(p.a > 0)) a.fail(i + 1, std::string("a ") + what + " > 0");
    i += 2;
    return p;
  }
  if (s != "uniform" && s != "gaussian") a.fail(i, expect);
  p.style = s == "uniform" ? Pdf::Uniform : Pdf::Gaussian;
  ++i;
  if (number_word) {
    const std::string& nm = a.word(i, "'number' (number-based distribution)");
    if (nm == "mass") a.fail(i, "'number' (mass-based radius distributions are not implemented in LIGGGHTS)");
    if (nm != "number") a.fail(i, "'number' or 'mass'");
    ++i;
  }
  p.a = a.num(i, p.style == Pdf::Uniform ? "the minimum" : "the mean mu");
  p.b = a.num(i + 1, p.style == Pdf::Uniform ? "the maximum" : "the standard deviation sigma");
  if (p.style == Pdf::Uniform && !(p.a > 0 && p.b > p.a)) a.fail(i + 1, "0 < min < max");
  if (p.style == Pdf::Gaussian) {
    if (!(p.a > 0)) a.fail(i, "mu > 0");
    if (!(p.b > 0)) a.fail(i + 1, "sigma > 0");
  }
  i += 2;
  if (p.style == Pdf::Gaussian) parse_cut(a, i, p);
  return p;
}

FixParticletemplateSphere::FixParticletemplateSphere(Simulation& s, const Args& a)
    : FixParticletemplateSphere(s, a, nullptr) {}

FixParticletemplateSphere::FixParticletemplateSphere(Simulation& s, const Args& a, const Keywords& extra)
    : Fix(s, a) {
  seed = parse_prime_seed(a, 4);
  bool have_radius = false, have_density = false;
  for (std::size_t i = 5; i < a.size();) {
    const std::string& k = a[i];
    if (k == "atom_type") {
      const long t = a.integer(i + 1, "an atom type");
      if (t < 1 || (s.domain.box_exists && t > s.atoms.ntypes))
        a.fail(i + 1, "an atom type between 1 and " + std::to_string(s.atoms.ntypes));
      atom_type = static_cast<int>(t);
      i += 2;
    } else if (extra && extra(a, i)) {
    } else if (k == "radius" && extra) {
      a.fail(i, "no 'radius' (a multisphere template takes its spheres from 'spheres', as LIGGGHTS)");
    } else if (k == "radius") {
      ++i;
      radius = parse_pdf(a, i, "radius", true);
      have_radius = true;
    } else if (k == "density") {
      ++i;
      density = parse_pdf(a, i, "density", false);
      have_density = true;
    } else if (k == "volume_limit") {
      volume_limit = a.num(i + 1, "the smallest allowed particle volume");
      if (!(volume_limit > 0)) a.fail(i + 1, "volume_limit > 0");
      i += 2;
    } else if (k == "relative") {
      if (a.yes_no(i + 1, "yes or no")) a.fail(i + 1, "'no' (relative radii are not supported)");
      i += 2;
    } else {
      a.fail(i, extra ? "a particletemplate/multisphere keyword: atom_type, density, volume_limit, nspheres, ntry, "
                        "spheres, type, mass, inertia_tensor, use_volume, use_density, fflag, tflag"
                      : "a particletemplate/sphere keyword: atom_type, density, radius, volume_limit, relative");
    }
  }
  // LIGGGHTS defaults are radius 1 and density 1, but it requires both to be given.
  if (!have_density) a.fail(a.size(), "'density constant RHO' (LIGGGHTS requires a density)");
  if (!have_radius && !extra) a.fail(a.size(), "'radius constant R' (LIGGGHTS requires a radius)");
  rng_.reseed(static_cast<std::uint64_t>(seed));
}

double FixParticletemplateSphere::volume_expect() const {
  return sim.domain.dimension == 2 ? std::numbers::pi * radius.moment(2)
                                   : 4.0 / 3.0 * std::numbers::pi * radius.moment(3);
}

// The mass convention of Atoms::mass_of: spheres in a 2D plane weigh their volume.
double FixParticletemplateSphere::mass_expect() const {
  if (!sim.atoms.area_density) return density.mean() * 4.0 / 3.0 * std::numbers::pi * radius.moment(3);
  return density.mean() * volume_expect();
}

FixParticletemplateSphere::Grain FixParticletemplateSphere::draw() {
  const double r = radius.draw(rng_), rho = density.draw(rng_);
  return {r, rho, grain_mass(sim, r, rho), atom_type};
}

SABLE_FIX("particletemplate/sphere", FixParticletemplateSphere);

}  // namespace sable
