#include "contact_models/registry.h"

#include <algorithm>
#include <cstdlib>
#include <set>
#include <sstream>

#include "core/input/args.h"
#include "core/engine/simulation.h"

namespace sable {

static std::set<std::string> axis_names(ModelAxis axis) {
  const auto& p = GranModelRegistry::parts();
  std::set<std::string> s;
  auto keys = [&s](const auto& m) {
    for (auto& [k, f] : m) s.insert(k);
  };
  if (axis == kNormalAxis || axis == kDampingAxis)
    for (auto& [k, f] : p.normal) s.insert(k[axis == kNormalAxis ? 0 : 1]);
  if (axis == kTangentialAxis) keys(p.tangential);
  if (axis == kRollingAxis) keys(p.rolling);
  if (axis == kCohesionAxis) keys(p.cohesion);
  return s;
}

std::string GranModelRegistry::names(ModelAxis axis) {
  std::string out;
  for (auto& n : axis_names(axis)) out += (out.empty() ? "" : ", ") + n;
  return out;
}

bool GranModelRegistry::has_name(ModelAxis axis, const std::string& name) { return axis_names(axis).count(name) > 0; }

static const char* const kAxisKeyword[kAxes] = {"model", "damping", "tangential", "rolling_friction", "cohesion"};
static const char* const kAxisWhat[kAxes] = {"a normal model", "a damping model", "a tangential model",
                                             "a rolling friction model", "a cohesion model"};

static bool looks_numeric(const std::string& w) {
  char* end = nullptr;
  std::strtod(w.c_str(), &end);
  return !w.empty() && end == w.c_str() + w.size();
}

ModelSelection parse_model_selection(const Args& a, std::size_t i) {
  ModelSelection s;
  if (i < a.size() && looks_numeric(a[i]))  // LIGGGHTS 2.x: Kn Kt gamma_n gamma_t xmu dampflag
    a.fail(i, "'model' followed by a normal model (" + GranModelRegistry::names(kNormalAxis) +
                  "): the coefficients in the line are LIGGGHTS 2.x syntax, removed in LIGGGHTS 3 (3.8 rejects it "
                  "too); use fix property/global youngsModulus, poissonsRatio, coefficientRestitution, "
                  "coefficientFriction");
  if (i >= a.size() || a[i] != "model")
    a.fail(i, "'model' followed by a normal model (" + GranModelRegistry::names(kNormalAxis) + ")");
  // LIGGGHTS wants the order model, tangential, cohesion, rolling_friction, surface; any order is accepted here.
  while (i < a.size()) {
    const std::string& k = a[i];
    int axis = -1;
    for (int x = 0; x < kAxes; ++x)
      if (k == kAxisKeyword[x]) axis = x;
    if (axis >= 0) {
      const auto ax = static_cast<ModelAxis>(axis);
      s.names[ax] = a.word(i + 1, std::string(kAxisWhat[ax]) + " (" + GranModelRegistry::names(ax) + ")");
      s.at[ax] = i + 1;
    } else if (k == "surface") {
      if (a.word(i + 1, "a surface model (default)") != "default")
        a.fail(i + 1, "surface 'default' (only spheres are supported)");
    } else {
      break;
    }
    i += 2;
  }
  s.next = i;
  return s;
}

// The selection's parts, or an error: a normal model registered without this
// damping model (SABLE_GRAN_MODEL: damping liggghts only), or too much history.
static ComposedParts compose(const ModelSelection& s, const Args& a) {
  const auto& p = GranModelRegistry::parts();
  const auto nd = p.normal.find({s.names[kNormalAxis], s.names[kDampingAxis]});
  if (nd == p.normal.end())
    a.fail(s.at[kDampingAxis] ? s.at[kDampingAxis] : s.at[kNormalAxis],
           "a damping model registered with model " + s.names[kNormalAxis] + " (damping " + s.names[kDampingAxis] +
               " is not; SABLE_GRAN_NORMAL registers a normal model with every damping model)");
  ComposedParts c;
  std::copy(s.names.begin(), s.names.end(), c.names.begin());
  c.normal = nd->second();
  c.tangential = p.tangential.at(s.names[kTangentialAxis])();
  c.rolling = p.rolling.at(s.names[kRollingAxis])();
  c.cohesion = p.cohesion.at(s.names[kCohesionAxis])();
  if (c.history() > kMaxLoopHistory)
    a.fail(s.at[kNormalAxis], "models with at most " + std::to_string(kMaxLoopHistory) +
                                  " history values per contact together (core/engine/contact_loop.h), not " +
                                  std::to_string(c.history()));
  return c;
}

// Each selected name is registered on its axis, or an error naming those that are.
static void check_names(const ModelSelection& s, const Args& a) {
  for (int x = 0; x < kAxes; ++x) {
    const auto ax = static_cast<ModelAxis>(x);
    if (GranModelRegistry::has_name(ax, s.names[ax])) continue;
    const std::string known = GranModelRegistry::names(ax);
    if (axis_names(ax).size() == 1)  // one choice: name it
      a.fail(s.at[ax], std::string(kAxisKeyword[ax]) + " '" + known + "'");
    a.fail(s.at[ax], std::string(kAxisWhat[ax]) + ": " + known +
                         (ax == kNormalAxis ? " (or one a 'plugin load' registers)" : ""));
  }
}

std::unique_ptr<ContactKernel> make_kernel(const ModelSelection& s, const Args& a, Simulation& sim) {
  check_names(s, a);
  const char* env = std::getenv("SABLE_COMPOSED_LAWS");
  const bool all_composed = env && *env && std::string(env) != "0";
  if (const auto* f = GranModelRegistry::find(s.names); f && !all_composed) return (*f)();
  auto law = make_composed_kernel(compose(s, a));
  const std::string why =
      all_composed ? "SABLE_COMPOSED_LAWS is set" : "not among the compiled laws, contact_models/compiled_laws.txt";
  sim.print_once("NOTE: the contact law '" + law->name() + "' runs on the slower runtime-composed path (" + why + ")");
  return law;
}

void ModelSettings::parse(const Args& a, std::size_t i) const {
  while (i < a.size()) {
    if (!known(a[i])) a.fail(i, "a model keyword: " + names());
    std::size_t j = i;
    try_parse(a, j);
    i = j;
  }
}

bool ModelSettings::known(const std::string& w) const {
  for (auto& e : entries_)
    if (e.name == w) return true;
  return false;
}

bool ModelSettings::try_parse(const Args& a, std::size_t& i) const {
  if (i >= a.size() || !known(a[i])) return false;
  const bool on = a.yes_no(i + 1, "on or off after " + a[i]);
  for (auto& e : entries_) {
    if (e.name != a[i]) continue;
    if (!e.target && on) a.fail(i + 1, "'off' (" + a[i] + " is not supported by sable)");
    if (e.target) *e.target = on;
  }
  i += 2;
  return true;
}

std::string ModelSettings::names() const {
  std::set<std::string> s;
  for (auto& e : entries_) s.insert(e.name);
  std::string out;
  for (auto& n : s) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "(none for these models)" : out + " (each on/off)";
}

}  // namespace sable
