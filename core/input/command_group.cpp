// group ID region R | type LIST | id LIST | variable V | subtract G1 G2 ... |
//          union G1 ... | intersect G1 G2 ... | delete | clear | initialize | empty
// LIGGGHTS 3.8 `group`: static assignment; an existing group gets atoms added.
// LIST = values or A:B[:C] sequences, or a logical: < <= > >= == != V, or <> V1 V2.
// `initialize` (LIGGGHTS) and `empty` (LAMMPS) create an empty group. Atoms
// inserted later join "all" and the groups of the inserting fixes.
#include <algorithm>

#include "core/engine/error.h"
#include "core/input/expression.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/input/variable.h"

namespace sable {
namespace {

// Selection by an integer attribute (type or id) from the list (or logical) at words 3...
std::vector<char> select_by(const Args& a, const std::vector<long>& attr, const std::string& what) {
  std::vector<char> sel(attr.size(), 0);
  const std::string list_expect = "a " + what + ", a sequence A:B or A:B:C, or a logical (< <= > >= == != <>)";
  a.need(4, list_expect);
  const std::string& op = a[3];
  if (op == "<" || op == "<=" || op == ">" || op == ">=" || op == "==" || op == "!=" || op == "<>") {
    const long v = a.integer(4, "a " + what);
    const long v2 = op == "<>" ? a.integer(5, "the upper " + what + " of '<>'") : 0;
    if (a.size() > (op == "<>" ? 6u : 5u)) a.fail(op == "<>" ? 6 : 5, "nothing more after the logical");
    for (std::size_t i = 0; i < attr.size(); ++i) {
      const long x = attr[i];
      sel[i] = op == "<"    ? x < v
               : op == "<=" ? x <= v
               : op == ">"  ? x > v
               : op == ">=" ? x >= v
               : op == "==" ? x == v
               : op == "!=" ? x != v
                            : (x >= v && x <= v2);
    }
    return sel;
  }
  for (std::size_t w = 3; w < a.size(); ++w) {
    const std::string& s = a[w];
    long lo, hi, step = 1;
    const auto c1 = s.find(':');
    if (c1 == std::string::npos) {
      if (!parse_long(s, lo)) a.fail(w, list_expect);
      hi = lo;
    } else {
      const auto c2 = s.find(':', c1 + 1);
      const std::string sb = s.substr(c1 + 1, c2 == std::string::npos ? std::string::npos : c2 - c1 - 1);
      if (!parse_long(s.substr(0, c1), lo) || !parse_long(sb, hi) ||
          (c2 != std::string::npos && !parse_long(s.substr(c2 + 1), step)) || step < 1 || hi < lo)
        a.fail(w, list_expect + "; A:B needs A <= B and a step C >= 1");
    }
    for (std::size_t i = 0; i < attr.size(); ++i)
      if (attr[i] >= lo && attr[i] <= hi && (attr[i] - lo) % step == 0) sel[i] = 1;
  }
  return sel;
}

// Groups has no erase: rebuild it with the slot renamed, so every other group
// keeps its bit (fixes and computes store bits) and the name can be reused.
void forget_group(Simulation& sim, int g) {
  Groups fresh;
  for (std::size_t k = 1; k < sim.groups.size(); ++k)
    fresh.find_or_create(static_cast<int>(k) == g ? "\x01"
                                                    "deleted-" +
                                                        std::to_string(k)
                                                  : sim.groups.name(k));
  sim.groups = fresh;
}

void cmd_group(Simulation& sim, const Args& a) {
  if (!sim.domain.box_exists) a.fail(0, "a box first (create_box before group)");
  const std::string& name = a.word(1, "a group ID");
  const std::string& style =
      a.word(2, "region, type, id, variable, subtract, union, intersect, delete, clear or initialize");
  Atoms& at = sim.atoms;

  if (style == "delete" || style == "clear") {
    const int g = sim.groups.existing(a, 1);
    if (g == 0) a.fail(1, "a group other than 'all' (it cannot be " + style + "ed)");
    if (style == "delete") {
      for (auto& f : sim.fixes)
        if (f->group == g) a.fail(1, "a group no fix uses (fix '" + f->id + "' acts on it; unfix it first)");
      for (auto& c : sim.computes)
        if (c->group == g) a.fail(1, "a group no compute uses (compute '" + c->id + "' acts on it)");
      for (auto& d : sim.dumps)
        if (d->group == g) a.fail(1, "a group no dump uses (dump '" + d->id + "' writes it)");
    }
    for (std::size_t i = 0; i < at.n; ++i) at.mask[i] &= ~sim.groups.bit(g);
    if (style == "delete") forget_group(sim, g);
    return;
  }

  std::vector<char> sel(at.n, 0);
  if (style == "region") {
    const Region* r = sim.find_region(a.word(3, "a region ID"));
    if (!r) a.fail(3, "an existing region ID (define it with 'region' first)");
    if (a.size() > 4) a.fail(4, "nothing after the region ID");
    for (std::size_t i = 0; i < at.n; ++i) sel[i] = r->match(&at.x[3 * i]);
  } else if (style == "type" || style == "id") {
    std::vector<long> attr(at.n);
    for (std::size_t i = 0; i < at.n; ++i) attr[i] = style == "type" ? at.type[i] : at.id[i];
    sel = select_by(a, attr, style == "type" ? "atom type" : "atom ID");
  } else if (style == "variable") {
    const std::string& v = a.word(3, "an atom-style variable name");
    if (!sim.variables->exists(v)) a.fail(3, "an existing variable");
    std::vector<double> vals;
    try {
      sim.variables->atom_values(v, vals);
    } catch (const ExpressionError& e) {
      a.fail(3, std::string("a variable that evaluates (") + e.what() + ")");
    }
    for (std::size_t i = 0; i < at.n; ++i) sel[i] = vals[i] != 0.0;
  } else if (style == "subtract" || style == "union" || style == "intersect") {
    const std::size_t need = style == "union" ? 4 : 5;
    if (a.size() < need) a.fail(a.size(), std::string(style == "union" ? "one or more" : "two or more") + " group IDs");
    std::vector<std::uint32_t> bits;
    for (std::size_t w = 3; w < a.size(); ++w) bits.push_back(sim.groups.bit(sim.groups.existing(a, w)));
    for (std::size_t i = 0; i < at.n; ++i) {
      const std::uint32_t m = at.mask[i];
      if (style == "union")
        sel[i] = std::any_of(bits.begin(), bits.end(), [&](auto b) { return m & b; });
      else if (style == "intersect")
        sel[i] = std::all_of(bits.begin(), bits.end(), [&](auto b) { return m & b; });
      else
        sel[i] = (m & bits[0]) && std::none_of(bits.begin() + 1, bits.end(), [&](auto b) { return m & b; });
    }
  } else if (style == "initialize" || style == "empty") {
    if (a.size() > 3) a.fail(3, "nothing after '" + style + "'");
  } else if (style == "molecule") {
    a.fail(2,
           "region, type, id, variable, subtract, union, intersect, delete, clear or initialize "
           "(atom_style granular has no molecule IDs)");
  } else {
    a.fail(2, "a group style: region, type, id, variable, subtract, union, intersect, delete, clear or initialize");
  }

  int g;
  try {
    g = sim.groups.find_or_create(name);
  } catch (const SableError& e) {
    a.fail(1, std::string("a new group within the limit: ") + e.what());
  }
  long count = 0;
  for (std::size_t i = 0; i < at.n; ++i) {
    if (sel[i]) at.mask[i] |= sim.groups.bit(g);
    count += (at.mask[i] & sim.groups.bit(g)) != 0;
  }
  sim.print(std::to_string(count) + " atoms in group " + name);
}

}  // namespace

SABLE_COMMAND("group", cmd_group);

}  // namespace sable
