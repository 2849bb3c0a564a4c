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

#include "core/neighbor.h"  // HistorySlot

namespace sable {

class Args;

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

inline double dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

struct Contact {
  double en[3];      // unit normal, j (or wall) -> i
  double deltan;     // overlap (> 0)
  double r;          // centre distance (wall: centre to wall = radi - deltan)
  double radi, radj;  // radj = 0 for a wall (infinite radius)
  double reff, meff;  // R* (wall: radi) and m* (wall: m_i)
  double cri, crj;    // contact radii r - deltan/2 (crj = 0 for a wall)
  double vn;          // normal relative velocity
  double vtr[3];      // tangential relative velocity at the contact point
  double wroll[3];    // relative spin for rolling friction (pair: w_i - w_j; wall: cri w_i / r as LIGGGHTS)
  int itype, jtype;   // jtype = wall material type for walls
  int tp;             // itype * (ntypes + 1) + jtype: index into per-type-pair tables
  bool is_wall;
};

// Normal sub-model result. kt/gammat feed the tangential model, as LIGGGHTS'
// normal models set sidata.kt/gammat; Fn (damped, possibly limited) is the
// force the Coulomb cap uses.
struct NormalForce {
  double Fn = 0, kn = 0, kt = 0, gamman = 0, gammat = 0;
};

// Per-step context shared by all contacts of one loop.
struct StepContext {
  double dt = 0;
  bool update = true;  // false during setup and for per-contact output: history is read, never written
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
