#include "contact_models/materials.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/input/args.h"
#include "core/engine/simulation.h"
#include "core/engine/global_property.h"

namespace sable {

namespace {
std::string fmt(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", x);
  return b;
}
// One cache entry per live Simulation; weak so a finished simulation frees its tables.
std::map<const Simulation*, std::weak_ptr<Materials>>& cache() {
  static std::map<const Simulation*, std::weak_ptr<Materials>> c;
  return c;
}
}  // namespace

std::shared_ptr<Materials> Materials::of(Simulation& sim) {
  auto& c = cache();
  if (auto p = c[&sim].lock())
    if (p->generation_ == GlobalProperty::generation() && p->ntypes_ == sim.atoms.ntypes) return p;
  auto p = std::make_shared<Materials>(sim);
  c[&sim] = p;
  return p;
}

Materials::Materials(Simulation& sim)
    : sim_(sim), ntypes_(sim.atoms.ntypes), generation_(GlobalProperty::generation()) {}

bool Materials::has(const std::string& property) const { return GlobalProperty::find(sim_, property) != nullptr; }

std::string Materials::example_line(const std::string& name, const char* style) const {
  std::string s = "fix ID all property/global " + name + " " + style;
  const std::string st = style;
  if (st == "scalar") return s + " VALUE";
  if (st == "peratomtype") {
    for (int i = 1; i <= ntypes_; ++i) s.append(" v").append(std::to_string(i));
    return s + "' (one value per atom type, " + std::to_string(ntypes_) + " types)";
  }
  s.append(" ").append(std::to_string(ntypes_));
  for (int i = 1; i <= ntypes_; ++i)
    for (int j = 1; j <= ntypes_; ++j) s.append(" v").append(std::to_string(i)).append(std::to_string(j));
  return s + "' (N = " + std::to_string(ntypes_) + " atom types, then N*N symmetric values)";
}

const GlobalProperty& Materials::require(const std::string& name, const char* style, const std::string& who,
                                           const Args& line) const {
  const GlobalProperty* f = GlobalProperty::find(sim_, name);
  std::string ex = example_line(name, style);
  if (ex.back() != ')') ex += "'";
  if (!f) line.fail_line(who + " needs material property '" + name + "', which no fix defines: add '" + ex);
  using K = GlobalProperty::Kind;
  const std::string st = style;
  const K want = st == "scalar" ? K::Scalar : st == "peratomtype" ? K::Vector : K::Matrix;
  if (f->kind != want)
    f->line->fail_line("property " + name + " is given as '" + f->style_word + "' but " + who + " (" +
                      line.where().file + ":" + std::to_string(line.where().line) + ") needs " + style + ": '" + ex);
  if (want == K::Vector && static_cast<int>(f->values.size()) < ntypes_)
    f->line->fail_line(name + " has " + std::to_string(f->values.size()) + " value(s) but the box has " +
                      std::to_string(ntypes_) + " atom types: '" + ex);
  if (want == K::Matrix && f->ncols < ntypes_)
    f->line->fail_line(name + " is given for " + std::to_string(f->ncols) + " atom type(s) but the box has " +
                      std::to_string(ntypes_) + ": '" + ex);
  return *f;
}

std::vector<double> Materials::raw_pair(const std::string& name, const std::string& who, const Args& line) const {
  const GlobalProperty& f = require(name, "peratomtypepair", who, line);
  const int s = stride();
  std::vector<double> t(s * s, 0.0);
  for (int i = 1; i <= ntypes_; ++i)
    for (int j = 1; j <= ntypes_; ++j) t[i * s + j] = f.at(i - 1, j - 1);
  return t;
}

std::vector<double> Materials::raw_type(const std::string& name, const std::string& who, const Args& line) const {
  const GlobalProperty& f = require(name, "peratomtype", who, line);
  std::vector<double> t(stride(), 0.0);
  for (int i = 1; i <= ntypes_; ++i) t[i] = f.values[i - 1];
  return t;
}

const double* Materials::type_vector(const std::string& name, const std::string& who, const Args& line) {
  const std::string key = name + "/type";  // per-type vectors share the map with per-type-pair tables
  if (auto it = tables_.find(key); it != tables_.end()) return it->second.data();
  std::vector<double> t = raw_type(name, who, line);
  // LIGGGHTS' sanity checks (global_properties.cpp), so a deck LIGGGHTS refuses is refused here too.
  const GlobalProperty* f = GlobalProperty::find(sim_, name);
  for (int i = 1; i <= ntypes_; ++i) {
    if (name == "youngsModulus" && sim_.units == "si" && t[i] < 5e6 && !sim_.soft_particles)
      f->line->fail_line("youngsModulus >= 5e6 required for SI units (as in LIGGGHTS); 'soft_particles yes' "
                        "before it allows softer grains; type " + std::to_string(i) + " has " + fmt(t[i]));
    if (name == "youngsModulus" && !(t[i] > 0))
      f->line->fail_line("youngsModulus > 0 required; type " + std::to_string(i) + " has " + fmt(t[i]));
    if (name == "poissonsRatio" && (t[i] < 0.0 || t[i] > 0.5))
      f->line->fail_line("0 <= poissonsRatio <= 0.5 required (as in LIGGGHTS); type " + std::to_string(i) + " has " +
                        fmt(t[i]));
  }
  auto& stored = tables_[key];
  stored = std::move(t);
  return stored.data();
}

const double* Materials::pair_table(const std::string& name, const std::string& who, const Args& line) {
  if (auto it = tables_.find(name); it != tables_.end()) return it->second.data();
  const int s = stride();
  std::vector<double> t(s * s, 0.0);
  auto each = [&](auto fn) {
    for (int i = 1; i <= ntypes_; ++i)
      for (int j = 1; j <= ntypes_; ++j) t[i * s + j] = fn(i, j);
  };
  // Derived tables: formulas of LIGGGHTS 3.8 global_properties.cpp (createYeff, createGeff, createBetaEff, ...).
  if (name == "Yeff") {
    const double* Y = type_vector("youngsModulus", who, line);
    const double* nu = type_vector("poissonsRatio", who, line);
    each([&](int i, int j) { return 1.0 / ((1.0 - nu[i] * nu[i]) / Y[i] + (1.0 - nu[j] * nu[j]) / Y[j]); });
  } else if (name == "Geff") {
    const double* Y = type_vector("youngsModulus", who, line);
    const double* nu = type_vector("poissonsRatio", who, line);
    each([&](int i, int j) {
      return 1.0 / (2.0 * (2.0 - nu[i]) * (1.0 + nu[i]) / Y[i] + 2.0 * (2.0 - nu[j]) * (1.0 + nu[j]) / Y[j]);
    });
  } else if (name == "coeffRestLog") {
    const double* e = pair_table("coefficientRestitution", who, line);
    each([&](int i, int j) { return std::log(e[i * s + j]); });
  } else if (name == "betaeff") {
    const double* le = pair_table("coeffRestLog", who, line);
    each([&](int i, int j) {
      const double l = le[i * s + j];
      return l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
    });
  } else {
    t = raw_pair(name, who, line);
    check_range(name, t);
    if (name == "coefficientRestitution") {
      const GlobalProperty* f = GlobalProperty::find(sim_, name);
      each([&](int i, int j) {
        const double e = t[i * s + j];
        if (!(e > 0.05 && e <= 1.0))
          f->line->fail_line("0.05 < coefficientRestitution <= 1 required (as in LIGGGHTS); types " + std::to_string(i) +
                            "," + std::to_string(j) + " have " + fmt(e));
        return e;
      });
    }
  }
  auto& stored = tables_[name];
  stored = std::move(t);
  return stored.data();
}

// Ranges outside which a law's formula breaks down (LIGGGHTS does not check
// these; a zero denominator or a negative pull would pass silently there).
void Materials::check_range(const std::string& name, const std::vector<double>& t) const {
  struct Range {
    const char* name;
    double lo;
    bool open;  // lo itself is refused
    const char* why;
  };
  static const Range ranges[] = {
      {"coefficientMaxElasticStiffness", 1.0, true, "k2Max = ratio kn must exceed kn (model hooke/hysteresis)"},
      {"coefficientAdhesionStiffness", 0.0, false, "kc = ratio kn is an adhesive stiffness"},
      {"coefficientPlasticityDepth", 0.0, true, "the plastic overlap limit is proportional to it"},
      {"cohesionEnergyDensity", 0.0, false, "cohesion sjkr/sjkr2 pull with it"},
      // Below zero these make contacts push grains together or gain energy.
      {"coefficientFriction", 0.0, false, "a friction coefficient"},
      {"coefficientRollingFriction", 0.0, false, "a friction coefficient"},
      {"coefficientRollingViscousDamping", 0.0, false, "a damping coefficient"},
      {"kn", 0.0, true, "a stiffness"},
      {"kt", 0.0, true, "a stiffness"},
      {"gamman", 0.0, false, "a damping coefficient"},
      {"gammat", 0.0, false, "a damping coefficient"},
      {"gamman_abs", 0.0, false, "a damping coefficient"},
      {"gammat_abs", 0.0, false, "a damping coefficient"},
      {"dampingNormal", 0.0, false, "a damping coefficient"},
      {"dampingTangential", 0.0, false, "a damping coefficient"},
  };
  for (const Range& r : ranges) {
    if (name != r.name) continue;
    const int s = stride();
    for (int i = 1; i <= ntypes_; ++i)
      for (int j = 1; j <= ntypes_; ++j) {
        const double v = t[i * s + j];
        if (r.open ? v > r.lo : v >= r.lo) continue;  // NaN fails both
        GlobalProperty::find(sim_, name)->line->fail_line(
            name + (r.open ? " > " : " >= ") + fmt(r.lo) + " required (" + r.why + "); types " + std::to_string(i) +
            "," + std::to_string(j) + " have " + fmt(v));
      }
  }
}

double Materials::scalar(const std::string& name, const std::string& who, const Args& line) {
  if (auto it = scalars_.find(name); it != scalars_.end()) return it->second;
  const GlobalProperty& f = require(name, "scalar", who, line);
  const double v = f.values[0];
  if (name == "characteristicVelocity" && sim_.units == "si" && v < 1e-2)
    f.line->fail_line("characteristicVelocity >= 1e-2 required for SI units (as in LIGGGHTS)");
  return scalars_[name] = v;
}

}  // namespace sable
