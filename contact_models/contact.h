#pragma once
// What every granular sub-model sees and returns. The kernel computes the
// contact kinematics once per contact (Contact), hands them by const
// reference to the normal, tangential and rolling sub-models, and each returns
// its part of the force. Conventions are LIGGGHTS 3.8's (surface_model_default.h):
//   en    unit normal pointing from j (or from the wall) to i
//   vn    (v_i - v_j) . en            (< 0 while approaching)
//   vtr   relative tangential velocity of the contact points
//         = (v_i - v_j)_t - (cri w_i + crj w_j) x en
//   cri   contact radius r_i - deltan/2 (lever arm of the tangential force)
//   force on i = Fn en + Ft, force on j = -(Fn en + Ft)
//   torque on i = -cri en x Ft - Mr, torque on j = -crj en x Ft + Mr
#include <cmath>
#include <string>
#include <vector>

#include "core/contact_columns.h"
#include "core/neighbor.h"  // HistorySlot

namespace sable {

class Args;

// Normal sub-model result. kt/gammat feed the tangential model, as LIGGGHTS'
// normal models set sidata.kt/gammat; Fn (damped, possibly limited) is the
// force the Coulomb cap uses.
struct NormalForce {
  double Fn = 0, kn = 0, kt = 0, gamman = 0, gammat = 0;
};

// Stability check inputs for one pair of grains touching at speed v.
struct ContactTimeInput {
  double meff, reff, v;
  int tp;
};

// Keywords a sub-model understands (LIGGGHTS "Settings": on/off switches after the model names).
class ModelSettings {
 public:
  void on_off(const std::string& name, bool& target) { entries_.push_back({name, &target}); }
  // A LIGGGHTS keyword sable knows but does not implement: 'off' is accepted, 'on' fails.
  void off_only(const std::string& name) { entries_.push_back({name, nullptr}); }
  // Parses "kw value" pairs of args from index `from`; unknown words fail naming the word.
  void parse(const Args& args, std::size_t from) const;
  std::string names() const;
  bool known(const std::string& w) const;
  // If word i is a known keyword, parse it and its value, advance i by 2 and return true.
  bool try_parse(const Args& args, std::size_t& i) const;

 private:
  struct Entry {
    std::string name;
    bool* target;
  };
  std::vector<Entry> entries_;
};

}  // namespace sable
