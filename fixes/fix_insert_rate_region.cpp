// fix ID group insert/rate/region seed S distributiontemplate D
//     nparticles N|INF | mass M|INF   particlerate R | massrate MR   insert_every K
//     region R  [start STEP] [maxattempt M] [overlapcheck yes|no] [all_in yes|no]
//     [vel constant|uniform|gaussian ...] [omega constant wx wy wz] [ntry_mc N]
//     [random_distribute exact|uncorrelated] [verbose yes|no] [check_dist_from_subdomain_border yes|no]
// LIGGGHTS 3.8 semantics: every K steps from the start step (default: the
// next step) it asks for int(n + u) grains, u uniform in [0, 1) and
// n = R K dt (massrate: R = MR / expected grain mass), but never for more
// than what remains of N (mass M: N = int(M / expected grain mass)), and it
// stops once N are in. Grains that found no place (overlapcheck) are not
// carried over: later steps still ask for n each until N are in. Placement:
// fixes/fix_insert.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/simulation.h"
#include "core/style_registry.h"
#include "fixes/fix_insert.h"

namespace sable {
namespace {

class FixInsertRateRegion : public FixInsert {
 public:
  FixInsertRateRegion(Simulation& s, const Args& a) : FixInsert(s, a) {
    once_allowed_ = false;
    parse(a);
  }

  // The grains per insertion follow dt, which the deck may change between runs.
  void init() override {
    const double rate = particle_rate_ > 0 ? particle_rate_ : mass_rate_ / dist_->mass_expect;
    per_step_ = rate * static_cast<double>(insert_every_) * sim.dt;
    if (mass_total_ > 0) ninsert_ = static_cast<long>(mass_total_ / dist_->mass_expect);
    FixInsert::init();
  }

 private:
  static constexpr long kUnlimited = std::numeric_limits<long>::max();
  long ninsert_ = 0;  // grains to insert in all (kUnlimited for INF)
  double mass_total_ = 0, particle_rate_ = 0, mass_rate_ = 0, per_step_ = 0;
  int totals_ = 0, rates_ = 0;

  bool own_keyword(const Args& a, std::size_t& i) override {
    const std::string& k = a[i];
    const bool inf = i + 1 < a.size() && a[i + 1] == "INF";
    if (k == "nparticles") {
      ninsert_ = inf ? kUnlimited : a.integer(i + 1, "a number of particles or INF");
      if (ninsert_ < 1) a.fail(i + 1, "a number of particles >= 1 or INF");
      ++totals_;
    } else if (k == "mass") {
      if (inf) {
        ninsert_ = kUnlimited;
      } else {
        mass_total_ = a.num(i + 1, "a mass or INF");
        if (!(mass_total_ > 0)) a.fail(i + 1, "a mass > 0 or INF");
      }
      ++totals_;
    } else if (k == "particlerate" || k == "massrate") {
      double& r = k == "particlerate" ? particle_rate_ : mass_rate_;
      r = a.num(i + 1, k == "particlerate" ? "a particle rate (per time unit)" : "a mass rate (mass per time unit)");
      if (!(r > 0)) a.fail(i + 1, "a rate > 0");
      ++rates_;
    } else {
      return false;
    }
    i += 2;
    return true;
  }
  void check_own(const Args& a) override {
    if (totals_ != 1) a.fail(a.size(), "exactly one of 'nparticles N|INF' and 'mass M|INF' (how many to insert)");
    if (rates_ != 1) a.fail(a.size(), "exactly one of 'particlerate R' and 'massrate MR'");
  }
  std::string keyword_list() const override {
    return "distributiontemplate, nparticles, mass, particlerate, massrate, insert_every, start, maxattempt, "
           "overlapcheck, all_in, random_distribute, verbose, vel, omega, orientation, region, ntry_mc, "
           "check_dist_from_subdomain_border";
  }

  long wanted(double& filled) override {
    filled = 0;
    const long n = static_cast<long>(per_step_ + rng_.uniform());
    return std::min(n, ninsert_ - ninserted_);
  }
  long following_step() const override { return ninserted_ >= ninsert_ ? -1 : next_step_ + insert_every_; }

  void announce() override {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "INFO: Particle insertion %s: %f particles every %ld steps - particle rate %f  (mass rate %e)",
                  id.c_str(), per_step_, insert_every_, per_step_ / (insert_every_ * sim.dt),
                  per_step_ / (insert_every_ * sim.dt) * dist_->mass_expect);
    sim.print(buf);
    if (ninsert_ != kUnlimited) {
      std::snprintf(buf, sizeof buf, " - %ld particles (mass %e) in all, the last of them at about step %ld", ninsert_,
                    ninsert_ * dist_->mass_expect,
                    next_step_ + static_cast<long>(std::max(0.0, std::ceil(ninsert_ / per_step_) - 1)) * insert_every_);
      sim.print(buf);
    }
  }
};

}  // namespace

SABLE_FIX("insert/rate/region", FixInsertRateRegion);

}  // namespace sable
