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
#include <algorithm>
#include <cmath>
#include <concepts>
#include <numbers>
#include <string>
#include <vector>

#include "core/engine/contact_columns.h"
#include "core/engine/neighbor.h"  // HistorySlot

namespace sable {

class Args;
class PropertyRequest;

// The normal force of one contact, built along the axes: the normal model
// sets kn, kt, the elastic force Fel (and s, what the Hertz dashpots scale
// with), the damping model gamman and gammat from them; then Fn = Fel - gamman vn,
// limited by the normal model (limitForce), plus the cohesion force. kt and
// gammat feed the tangential model, as LIGGGHTS' normal models set
// sidata.kt/gammat; Fn (damped, possibly limited) is the force the Coulomb cap uses.
struct NormalForce {
  double Fn = 0, kn = 0, kt = 0, gamman = 0, gammat = 0;
  double Fel = 0;  // elastic part
  double s = 0;    // sqrt(R* dn) for Hertz-type models (0 for linear springs)
};

// Which of LIGGGHTS' dashpots a normal model has in LIGGGHTS 3.8, applied by
// `damping liggghts` (damping/liggghts.h, which lists the formulas); `own`: the
// model brings its dashpot as damping()/connect_damping() (a plugin's model).
enum class LiggghtsDamping { hertz, hooke, stiffness, hertz_stiffness, restitution, own };

// Stability check inputs for one pair of grains touching at speed v.
struct ContactTimeInput {
  double meff, reff, v;
  int tp;
};

// Half period of a linear spring kn with dashpot gamman: pi / sqrt(kn/m* - (gamman / 2m*)^2).
inline double linear_contact_time(double kn, double meff, double gamman = 0.0) {
  const double w2 = kn / meff - gamman * gamman / (4.0 * meff * meff);
  return std::numbers::pi / std::sqrt(std::max(w2, 1e-300));
}

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

// A sub-model that keeps nothing per contact (most of them).
struct NoHistory {
  static constexpr int kHistory = 0;
  static void history_slots(std::vector<HistorySlot>&) {}
};

// What LIGGGHTS 3.8's normal models share: the switches tangential_damping
// (gammat, read by damping liggghts) and limitForce (Fn clipped at 0: no
// attraction), and three keywords they accept that sable does not implement.
struct LiggghtsNormal : NoHistory {
  bool tangential_damping = true, limit_force = false;

  void switches(ModelSettings& s) {
    s.on_off("tangential_damping", tangential_damping);
    s.on_off("limitForce", limit_force);
  }
  static void unimplemented(ModelSettings& s) {
    s.off_only("disableNormalWhenBonded");
    s.off_only("computeDissipatedEnergy");
    s.off_only("computeElasticPotential");
  }
  void limit(NormalForce& n) const {
    if (limit_force && n.Fn < 0.0) n.Fn = 0.0;
  }
};

// What each axis asks of a sub-model (contact_models/README.md). A header
// under contact_models/<axis>/ ends with SABLE_<AXIS>_MODEL(Type); the build
// finds that line and the type runs with every model of the other axes
// (composed at run time; compiled when contact_models/compiled_laws.txt lists
// the combination: no list to edit otherwise); the macro checks the interface.
template <class M>
concept SubModel = requires(M m, ModelSettings& s, std::vector<HistorySlot>& h) {
  { M::kName } -> std::convertible_to<const char*>;
  { M::kHistory } -> std::convertible_to<int>;
  M::history_slots(h);
  m.settings(s);
};
// A normal model whose LIGGGHTS dashpot is its own (LiggghtsDamping::own).
template <class M>
concept OwnDashpot = requires(const M& m, M& mm, const Contact& c, NormalForce& n, PropertyRequest& p) {
  m.damping(c, n);
  mm.connect_damping(p);
};
template <class M>
concept NormalSubModel = SubModel<M> && requires(const M& m, const Contact& c, NormalForce& n, double* h,
                                                 const StepContext& x, const ContactTimeInput& t) {
  { m.force(c, h, x) } -> std::same_as<NormalForce>;
  m.limit(n);
  { m.contact_time(t) } -> std::convertible_to<double>;  // undamped
  { M::kLiggghtsDamping } -> std::convertible_to<LiggghtsDamping>;
} && (M::kLiggghtsDamping != LiggghtsDamping::own || OwnDashpot<M>);
template <class M>
concept TangentialSubModel = SubModel<M> && requires(const M& m, const Contact& c, const NormalForce& n, double* h,
                                                     const StepContext& x) {
  { m.force(c, n, h, x) } -> std::same_as<Vec3>;
};
template <class M>
concept RollingSubModel = SubModel<M> && requires(const M& m, const Contact& c, const NormalForce& n, double* h,
                                                  const StepContext& x) {
  { m.torque(c, n, h, x) } -> std::same_as<Vec3>;
};
template <class M>
concept CohesionSubModel = SubModel<M> && requires(const M& m, const Contact& c, const NormalForce& n, double* h,
                                                   const StepContext& x) {
  { M::kActive } -> std::convertible_to<bool>;
  { m.force(c, n, h, x) } -> std::convertible_to<double>;
  { m.reduces_tangential() } -> std::convertible_to<bool>;
};

}  // namespace sable

#define SABLE_NORMAL_MODEL(T) static_assert(::sable::NormalSubModel<T>, #T ": not a normal model")
#define SABLE_DAMPING_MODEL(T) static_assert(::sable::SubModel<T>, #T ": not a damping model")
#define SABLE_TANGENTIAL_MODEL(T) static_assert(::sable::TangentialSubModel<T>, #T ": not a tangential model")
#define SABLE_ROLLING_MODEL(T) static_assert(::sable::RollingSubModel<T>, #T ": not a rolling model")
#define SABLE_COHESION_MODEL(T) static_assert(::sable::CohesionSubModel<T>, #T ": not a cohesion model")

