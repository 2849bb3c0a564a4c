#include "contact_models/gran_local.h"

#include "core/input/args.h"

namespace sable {

void GranLocalColumns::parse(const Args& a, std::size_t i) {
  if (i >= a.size()) return;  // LIGGGHTS' default set
  pos = vel = id = force = torque = history = area = false;
  for (; i < a.size(); ++i) {
    const std::string& k = a[i];
    if (k == "pos") pos = true;
    else if (k == "vel") vel = true;
    else if (k == "id") id = true;
    else if (k == "force") force = true;
    else if (k == "force_normal") fn = true;
    else if (k == "force_tangential") ft = true;
    else if (k == "torque") torque = true;
    else if (k == "history") history = history_explicit = true;
    else if (k == "contactArea") area = true;
    else if (k == "delta") delta = true;
    else
      a.fail(i, "a keyword: pos, vel, id, force, force_normal, force_tangential, torque, history, contactArea, delta");
  }
}

std::vector<std::string> GranLocalColumns::names(const std::vector<HistorySlot>& slots) const {
  std::vector<std::string> n;
  auto add3 = [&](const std::string& p, const std::string& s) {
    for (const char* c : {"x", "y", "z"}) n.push_back(p + c + s);
  };
  if (pos) add3("", "1"), add3("", "2");
  if (vel) add3("v", "1"), add3("v", "2");
  if (id) n.insert(n.end(), {"id1", "id2", "periodic"});
  if (force) add3("f", "");
  if (fn) add3("fn", "");
  if (ft) add3("ft", "");
  if (torque) add3("t", "");
  if (history)
    for (auto& s : slots) n.push_back(s.name);
  if (area) n.push_back("contactArea");
  if (delta) n.push_back("delta");
  return n;
}

void GranLocalColumns::row(std::vector<double>& out, const double* p1, const double* p2, const double* v1,
                           const double* v2, const double ids[3], const double* f, const double* t, const double* en,
                           const double* h, int nh, double a, double overlap) const {
  auto put = [&](const double* x) { out.insert(out.end(), x, x + 3); };
  if (pos) put(p1), put(p2);
  if (vel) put(v1), put(v2);
  if (id) put(ids);
  const double fnm = f[0] * en[0] + f[1] * en[1] + f[2] * en[2];
  const double fnv[3] = {fnm * en[0], fnm * en[1], fnm * en[2]};
  const double ftv[3] = {f[0] - fnv[0], f[1] - fnv[1], f[2] - fnv[2]};
  if (force) put(f);
  if (fn) put(fnv);
  if (ft) put(ftv);
  if (torque) put(t);
  if (history) out.insert(out.end(), h, h + nh);
  if (area) out.push_back(a);
  if (delta) out.push_back(overlap);
}

}  // namespace sable
