// The rate-driven insertion styles' shared part; see FixInsertRated in fixes/fix_insert.h.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/engine/simulation.h"
#include "fixes/fix_insert.h"

namespace sable {

void FixInsertRated::init() {
  schedule();
  const double rate = particle_rate_ > 0 ? particle_rate_ : mass_rate_ / dist_->mass_expect;
  per_step_ = rate * static_cast<double>(insert_every_) * sim.dt;
  // LIGGGHTS adds 1e-14 to M so that a mass of exactly N grains gives N.
  if (mass_total_ > 0) ninsert_ = static_cast<long>((mass_total_ + 1e-14) / dist_->mass_expect);
  FixInsert::init();
}

bool FixInsertRated::rate_keyword(const Args& a, std::size_t& i) {
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

void FixInsertRated::check_rate(const Args& a) const {
  if (totals_ != 1) a.fail(a.size(), "exactly one of 'nparticles N|INF' and 'mass M|INF' (how many to insert)");
  if (rates_ != 1) a.fail(a.size(), "exactly one of 'particlerate R' and 'massrate MR'");
}

long FixInsertRated::wanted(double& filled) {
  filled = 0;
  const long n = static_cast<long>(per_step_ + rng_.uniform());
  return std::min(n, ninsert_ - ninserted_);
}

void FixInsertRated::announce() {
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

}  // namespace sable
