#include "contact_models/registry.h"

#include <set>
#include <sstream>

#include "core/args.h"

namespace sable {

static std::set<std::string> axis_names(int axis) {
  std::set<std::string> s;
  for (auto& [k, f] : GranModelRegistry::table()) {
    std::istringstream in(k);
    std::string w[3];
    in >> w[0] >> w[1] >> w[2];
    s.insert(w[axis]);
  }
  return s;
}

std::string GranModelRegistry::names(int axis) {
  std::string out;
  for (auto& n : axis_names(axis)) out += (out.empty() ? "" : ", ") + n;
  return out;
}

bool GranModelRegistry::has_name(int axis, const std::string& name) { return axis_names(axis).count(name) > 0; }

ModelSelection parse_model_selection(const Args& a, std::size_t i) {
  ModelSelection s;
  if (i >= a.size() || a[i] != "model") a.fail(i, "'model' followed by a normal model (" + GranModelRegistry::names(0) + ")");
  // LIGGGHTS wants the order model, tangential, cohesion, rolling_friction, surface; any order is accepted here.
  while (i < a.size()) {
    const std::string& k = a[i];
    if (k == "model") {
      s.normal = a.word(i + 1, "a normal model (" + GranModelRegistry::names(0) + ")");
      s.normal_at = i + 1;
    } else if (k == "tangential") {
      s.tangential = a.word(i + 1, "a tangential model (" + GranModelRegistry::names(1) + ")");
      s.tangential_at = i + 1;
    } else if (k == "rolling_friction") {
      s.rolling = a.word(i + 1, "a rolling friction model (" + GranModelRegistry::names(2) + ")");
      s.rolling_at = i + 1;
    } else if (k == "cohesion") {
      if (a.word(i + 1, "a cohesion model (off)") != "off")
        a.fail(i + 1, "cohesion 'off' (cohesion models are not supported yet)");
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

std::unique_ptr<ContactKernel> make_kernel(const ModelSelection& s, const Args& a) {
  if (!GranModelRegistry::has_name(0, s.normal))
    a.fail(s.normal_at, "a normal model: " + GranModelRegistry::names(0) + " (or one a 'plugin load' registers)");
  if (!GranModelRegistry::has_name(1, s.tangential))
    a.fail(s.tangential_at, "a tangential model: " + GranModelRegistry::names(1));
  if (!GranModelRegistry::has_name(2, s.rolling))
    a.fail(s.rolling_at, "a rolling friction model: " + GranModelRegistry::names(2));
  const auto* f = GranModelRegistry::find(s.normal, s.tangential, s.rolling);
  if (!f)
    a.fail(s.normal_at, "a registered combination: model " + s.normal + " tangential " + s.tangential +
                            " rolling_friction " + s.rolling +
                            " was not compiled (register it with SABLE_GRAN_MODEL or SABLE_GRAN_NORMAL)");
  return (*f)();
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
