#pragma once
// fix ID group particledistribution/discrete[/massbased|/numberbased] SEED N  T1 W1 ... TN WN
// A discrete mix of particle templates (LIGGGHTS 3.8). Weights are mass
// fractions (plain and /massbased) or number fractions (/numberbased); they
// are normalised with a warning when they do not sum to 1.
#include <vector>

#include "fixes/fix_particletemplate_sphere.h"

namespace sable {

class FixParticledistributionDiscrete : public Fix {
 public:
  // number_based: /numberbased (weights are number fractions), else mass fractions.
  FixParticledistributionDiscrete(Simulation& s, const Args& a, bool number_based = false);
  void export_yade(YadeScript&) const override {}  // --export-yade: a definition only, as its templates
  struct Grain {
    FixParticletemplateSphere::Grain g;
    std::uint32_t groupbits;  // the template's and this fix's groups
  };
  long seed = 0;
  std::vector<FixParticletemplateSphere*> templates;
  std::vector<std::string> template_ids;  // to check at each run that the templates still exist
  std::vector<double> number_fraction;    // per template, sums to 1
  std::vector<int> order;                 // templates by expected volume, largest first
  double volume_expect = 0, mass_expect = 0, max_radius = 0;
  int max_type = 1;

  // The grains for one insertion of n bodies, largest templates first (LIGGGHTS
  // inserts big grains first to reach denser packings). exact: the per-template
  // counts sum to n (LIGGGHTS `random_distribute exact`), each within 1 of n*fraction;
  // otherwise each count is int(n*fraction + uniform) (`uncorrelated`).
  std::vector<Grain> draw(long n, bool exact);

 private:
  Rng rng_;
};

}  // namespace sable
