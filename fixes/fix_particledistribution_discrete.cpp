#include "fixes/fix_particledistribution_discrete.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

FixParticledistributionDiscrete::FixParticledistributionDiscrete(Simulation& s, const Args& a, bool number_based)
    : Fix(s, a) {
  const bool mass_based = !number_based;
  seed = parse_prime_seed(a, 4);
  const long nt = a.integer(5, "the number of templates");
  if (nt < 1) a.fail(5, "a number of templates >= 1");
  if (a.size() != 6 + 2 * static_cast<std::size_t>(nt))
    a.fail(std::min(a.size(), 6 + 2 * static_cast<std::size_t>(nt)),
           std::to_string(nt) + " pairs 'template-ID weight' (the count given after the seed)");
  std::vector<double> w;
  for (long t = 0; t < nt; ++t) {
    const std::size_t i = 6 + 2 * t;
    auto* tp = dynamic_cast<FixParticletemplateSphere*>(s.find_fix(a[i]));
    if (!tp) a.fail(i, "the ID of a fix particletemplate/sphere defined earlier (or of a particletemplate/multisphere)");
    if (std::find(templates.begin(), templates.end(), tp) != templates.end())
      a.fail(i, "a template not already listed (LIGGGHTS forbids using a template twice)");
    // LIGGGHTS aborts when the expected volume is below volume_limit (round-off risk).
    if (tp->volume_expect() < tp->volume_limit)
      a.fail(i, "a template whose expected particle volume exceeds its volume_limit (" +
                    std::to_string(tp->volume_limit) + "); raise the radius or lower volume_limit");
    templates.push_back(tp);
    template_ids.push_back(tp->id);
    const double wt = a.num(i + 1, "a weight >= 0");
    if (wt < 0) a.fail(i + 1, "a weight >= 0");
    w.push_back(wt);
  }
  double sum = 0;
  for (double x : w) sum += x;
  if (!(sum > 0)) a.fail(7, "weights that do not all vanish");
  if (std::fabs(sum - 1.0) > 1e-5)
    s.warn(a.where().file + ":" + std::to_string(a.where().line) +
           ": particledistribution/discrete: sum of distribution weights != 1, normalizing distribution");
  for (double& x : w) x /= sum;

  auto report = [&](const char* kind, const std::vector<double>& f) {
    s.print("Fix particledistribution/discrete (id " + id + "): distribution based on " + kind + "%:");
    for (std::size_t t = 0; t < templates.size(); ++t) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "    %s: d=%e (max. bounding sphere) %s%%=%f%%", templates[t]->id.c_str(),
                    2 * templates[t]->radius.max(), kind, 100 * f[t]);
      s.print(buf);
    }
  };
  if (mass_based) {
    report("mass", w);
    // mass% -> number%: n_t proportional to w_t / <m_t>
    double z = 0;
    for (std::size_t t = 0; t < w.size(); ++t) z += w[t] /= templates[t]->mass_expect();
    for (double& x : w) x /= z;
  }
  number_fraction = w;
  report("number", w);

  for (std::size_t t = 0; t < templates.size(); ++t) {
    volume_expect += number_fraction[t] * templates[t]->volume_expect();
    mass_expect += number_fraction[t] * templates[t]->mass_expect();
    max_radius = std::max(max_radius, templates[t]->radius.max());
    max_type = std::max(max_type, templates[t]->atom_type);
    order.push_back(static_cast<int>(t));
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](int p, int q) { return templates[p]->volume_expect() > templates[q]->volume_expect(); });
  rng_.reseed(static_cast<std::uint64_t>(seed));
}

std::vector<FixParticledistributionDiscrete::Grain> FixParticledistributionDiscrete::draw(long n, bool exact) {
  const std::size_t nt = templates.size();
  std::vector<long> count(nt);
  if (!exact) {
    for (std::size_t t = 0; t < nt; ++t) count[t] = static_cast<long>(n * number_fraction[t] + rng_.uniform());
  } else {
    // Truncate, then hand out the missing ones with probability proportional to the remainders.
    std::vector<double> rem(nt);
    long total = 0;
    for (std::size_t t = 0; t < nt; ++t) {
      count[t] = static_cast<long>(n * number_fraction[t]);
      rem[t] = n * number_fraction[t] - count[t];
      total += count[t];
    }
    for (long gap = n - total; gap > 0; --gap) {
      double rs = 0;
      for (double r : rem) rs += r;
      std::size_t t = 0;
      if (rs > 0) {
        const double r = rng_.uniform() * rs;
        double acc = rem[0];
        while (t + 1 < nt && acc <= r) acc += rem[++t];
      }
      ++count[t];
      rem[t] = 0;  // one extra grain per template at most: each count stays within 1 of n*fraction
    }
  }
  std::vector<Grain> out;
  for (int t : order) {
    const std::uint32_t bits = groupbit | templates[t]->groupbit;
    for (long k = 0; k < count[t]; ++k) out.push_back({templates[t]->draw(), bits});
  }
  return out;
}

SABLE_FIX("particledistribution/discrete", FixParticledistributionDiscrete);
SABLE_FIX("particledistribution/discrete/massbased", FixParticledistributionDiscrete);
// The number-based variant: the same class, told by its registration, not by its name.
struct FixParticledistributionDiscreteNumber : FixParticledistributionDiscrete {
  FixParticledistributionDiscreteNumber(Simulation& s, const Args& a) : FixParticledistributionDiscrete(s, a, true) {}
};
SABLE_FIX("particledistribution/discrete/numberbased", FixParticledistributionDiscreteNumber);

}  // namespace sable
