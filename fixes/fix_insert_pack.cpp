// fix ID group insert/pack seed S distributiontemplate D insert_every N|once
//     [maxattempt M] [start STEP] [overlapcheck yes|no] [all_in yes|no]
//     [random_distribute exact|uncorrelated] [verbose yes|no]
//     [vel constant|uniform|gaussian ...] [omega constant wx wy wz]
//     region R  particles_in_region N | volumefraction_region F | mass_in_region M  [ntry_mc N]
//     [check_dist_from_subdomain_border yes|no]
// LIGGGHTS 3.8 semantics: at step (definition + 1) and then every N steps, count
// all grains whose centre is in the region and insert the missing ones (the
// placement rules are those of every region insertion: fixes/fix_insert.cpp).
// sable extension: in 2D fractions are area fractions.
#include "core/geometry/region.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "fixes/fix_insert.h"

namespace sable {
namespace {

class FixInsertPack : public FixInsert {
 public:
  FixInsertPack(Simulation& s, const Args& a) : FixInsert(s, a) { parse(a); }

 private:
  long n_target_ = 0;
  double vol_frac_ = 0, mass_target_ = 0;
  int targets_ = 0;

  bool own_keyword(const Args& a, std::size_t& i) override {
    const std::string& k = a[i];
    if (k == "volumefraction_region") {
      vol_frac_ = a.num(i + 1, "a volume fraction");
      if (!(vol_frac_ > 0 && vol_frac_ < 1)) a.fail(i + 1, "a volume fraction between 0 and 1");
    } else if (k == "particles_in_region") {
      n_target_ = a.integer(i + 1, "a number of particles");
      if (n_target_ <= 0) a.fail(i + 1, "a number of particles > 0");
    } else if (k == "mass_in_region") {
      mass_target_ = a.num(i + 1, "a mass");
      if (!(mass_target_ > 0)) a.fail(i + 1, "a mass > 0");
    } else {
      return false;
    }
    ++targets_, i += 2;
    return true;
  }
  void check_own(const Args& a) override {
    if (targets_ != 1) a.fail(a.size(), "exactly one of volumefraction_region, particles_in_region, mass_in_region");
  }
  std::string keyword_list() const override {
    return "distributiontemplate, insert_every, maxattempt, start, overlapcheck, all_in, random_distribute, verbose, "
           "vel, omega, orientation, region, volumefraction_region, particles_in_region, mass_in_region, ntry_mc";
  }

  // The grains missing from the target, counting every atom whose centre is in
  // the region, whatever its group (a clump once, by its centre of mass).
  long wanted(double& filled) override {
    long np = 0;
    double vol = 0, mass = 0;
    region_content(np, vol, mass);
    if (vol_frac_ > 0) {
      filled = vol / (vol_frac_ * region_volume_);
      return static_cast<long>((vol_frac_ * region_volume_ - vol) / dist_->volume_expect + rng_.uniform());
    }
    if (n_target_ > 0) {
      filled = static_cast<double>(np) / n_target_;
      return n_target_ - np;
    }
    filled = mass / mass_target_;
    return static_cast<long>((mass_target_ - mass) / dist_->mass_expect + rng_.uniform());
  }
};

}  // namespace

SABLE_FIX("insert/pack", FixInsertPack);

}  // namespace sable
