// fix ID group insert/rate/region seed S distributiontemplate D
//     nparticles N|INF | mass M|INF   particlerate R | massrate MR   insert_every K
//     region R  [start STEP] [maxattempt M] [overlapcheck yes|no] [all_in yes|no]
//     [vel constant|uniform|gaussian ...] [omega constant wx wy wz] [ntry_mc N]
//     [random_distribute exact|uncorrelated] [verbose yes|no] [check_dist_from_subdomain_border yes|no]
// LIGGGHTS 3.8 semantics: every K steps from the start step (default: the
// next step) int(n + u) grains, n = R K dt, in the region (the counts:
// FixInsertRated in fixes/fix_insert.h; placement: fixes/fix_insert.cpp).
#include "core/input/style_registry.h"
#include "fixes/fix_insert.h"

namespace sable {
namespace {

class FixInsertRateRegion : public FixInsertRated {
 public:
  FixInsertRateRegion(Simulation& s, const Args& a) : FixInsertRated(s, a) {
    once_allowed_ = false;
    parse(a);
  }

 private:
  bool own_keyword(const Args& a, std::size_t& i) override { return rate_keyword(a, i); }
  void check_own(const Args& a) override { check_rate(a); }
  std::string keyword_list() const override {
    return "distributiontemplate, nparticles, mass, particlerate, massrate, insert_every, start, maxattempt, "
           "overlapcheck, all_in, random_distribute, verbose, vel, omega, orientation, region, ntry_mc, "
           "check_dist_from_subdomain_border";
  }
};

}  // namespace

SABLE_FIX("insert/rate/region", FixInsertRateRegion);

}  // namespace sable
