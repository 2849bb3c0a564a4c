// sable --export-yade (tools/export_yade.h): the driver. It reads the deck
// through Input's intercept, keeps the deck-order bookkeeping of the script
// (core/io/yade_script.h), and at the first run asks each style, in deck order,
// for its own translation (export_yade); `run` and `print` become Python here.
#include "tools/export_yade.h"

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/input/args.h"
#include "core/io/dump.h"
#include "core/engine/error.h"
#include "core/input/input.h"
#include "core/engine/simulation.h"
#include "core/input/variable.h"
#include "core/io/yade_script.h"

namespace sable {
namespace {

std::string first_word(const std::string& line) {
  std::istringstream ss(line);
  std::string w;
  ss >> w;
  return w.empty() || w[0] == '#' ? "" : w;
}

class YadeDeck {
 public:
  YadeDeck(Simulation& sim, Input& in) : s_(sim), in_(in) {}
  bool intercept(const std::string& line, const DeckLocation& where);
  std::string script() const { return s_.script(); }

 private:
  YadeScript s_;
  Input& in_;
  bool scene_done_ = false;
  void record(const Args& a);
  void cmd_run(const Args& a);
  void cmd_print(const std::string& line, const DeckLocation& where);
  std::string substitute(const std::string& line, const Args& at, std::vector<std::string>& exprs);
  void scene(const Args& run);
  void dump_recorders();
};

// ------------------------------------------------------------------ deck flow
bool YadeDeck::intercept(const std::string& line, const DeckLocation& where) {
  const std::string c = first_word(line);
  if (c == "print") {
    cmd_print(line, where);
    return true;
  }
  if (c.empty() || c == "label" || c == "jump" || c == "next" || c == "if" || c == "include" || c == "log" ||
      c == "echo")
    return false;
  // $(cpu) is sable's wall clock now, not YADE's: `variable NAME equal $(cpu)` becomes
  // a snapshot of the script's clock at that point; any other use in a command is refused.
  static const std::regex snap(R"(^\s*variable\s+(\S+)\s+equal\s+\$\(\s*cpu\s*\)\s*(#.*)?$)");
  static const std::regex cpu(R"(\$\([^)]*\bcpu\b)");
  std::smatch m;
  const bool is_snap = std::regex_match(line, m, snap);
  if (!is_snap && std::regex_search(line, cpu))
    Args({line}, where).fail_line("export-yade: $(cpu) here is sable's clock at export time, not YADE's; only "
                                  "`variable NAME equal $(cpu)` (a snapshot of the script's clock) is translated");
  Args a(in_.parse(line, where), where);
  if (a.size() == 0) return false;
  if (c == "run") {
    cmd_run(a);
    return true;
  }
  record(a);
  if (is_snap) {
    s_.formulas.erase(m[1]);
    s_.snaps.insert(m[1]);
    s_.py << "_snap[" << yade_quoted(m[1]) << "] = _cpu()  # " << where.file << ":" << where.line << "\n";
  }
  return false;
}

// Remembers what run and print need later; after the scene is written, only
// output and flow commands may follow (the scene is translated once).
void YadeDeck::record(const Args& a) {
  const std::string& c = a.command();
  if (c == "neigh_modify")  // YADE's collider has no per-type or per-group exclusion
    for (std::size_t i = 1; i + 1 < a.size(); ++i)
      if (a[i] == "exclude" && a[i + 1] != "none")
        a.fail(i, "a neigh_modify keyword other than exclude (export-yade: excluded pairs are not translated to YADE)");
  if (c == "variable" && a.size() >= 2) s_.snaps.erase(a[1]);
  if (c == "variable" && a.size() >= 4 && a[2] == "equal") s_.formulas[a[1]] = a.joined(3);
  if (c == "variable" && a.size() >= 3 && a[2] != "equal") s_.formulas.erase(a[1]);
  if (c == "thermo_style") {
    if (a.size() < 3 || a[1] != "custom") a.fail(1, "thermo_style custom (export-yade translates custom columns only)");
    s_.thermo_cols.assign(a.words().begin() + 2, a.words().end());
  }
  if (c == "thermo") s_.thermo_every = a.integer(1, "a thermo interval");
  if (c == "boundary") s_.boundary = a.joined(1);
  if (c == "dump_modify" && a.size() >= 2 && s_.dumps_done.count(a[1]))
    a.fail_line("export-yade: dump " + a[1] + " is already a recorder (translated at the run before); "
                "dump_modify it before its first run");
  if (c == "dump_modify" && a.size() >= 2) s_.dump_mods[a[1]].push_back(a);
  if (c == "undump" && a.size() >= 2) s_.dump_mods.erase(a[1]);  // a dump of that ID defined again starts afresh
  if (c == "undump" && a.size() >= 2 && s_.dumps_done.erase(a[1]))
    s_.py << "_recorders = [r for r in _recorders if getattr(r, 'name', None) != " << yade_quoted(a[1]) << "]  # "
        << a.where().file << ":" << a.where().line << ": undump\n";
  static const std::set<std::string> after_ok{"variable", "thermo_style", "thermo", "thermo_modify", "dump",
                                              "dump_modify", "undump"};
  if (scene_done_ && !after_ok.count(c))
    a.fail_line("export-yade: '" + c + "' after the first run changes the scene, which is translated once; not translated to YADE");
}

void YadeDeck::cmd_run(const Args& a) {
  const long n = a.integer(1, "a number of steps");
  for (std::size_t i = 2; i < a.size(); i += 2)
    if (a[i] != "pre" && a[i] != "post") a.fail(i, "pre or post (export-yade translates `run N` only)");
  if (!scene_done_) scene(a);
  scene_done_ = true;
  dump_recorders();  // dumps defined since the last run
  std::vector<std::string> cols;
  for (const auto& c : s_.thermo_cols) cols.push_back("lambda: " + s_.translate(c, a));
  s_.py << "\n# " << a.where().file << ":" << a.where().line << ": run " << n << "\n";
  s_.py << "_thermo_cols = [" ;
  for (const auto& c : cols) s_.py << c << ", ";
  s_.py << "]\n_run(" << n << ", " << s_.thermo_every << ", " << yade_quoted(a.where().file) << ")\n";
}

// print "TEXT": equal-style variables become Python evaluated after YADE's run.
void YadeDeck::cmd_print(const std::string& line, const DeckLocation& where) {
  const Args at({line}, where);
  std::vector<std::string> exprs;
  const std::string subst = substitute(line, at, exprs);
  const Args a(in_.parse(subst, where), where);
  for (std::size_t i = 2; i < a.size(); i += 2)
    if (a[i] != "screen" || a.word(i + 1, "yes") != "yes") a.fail(i, "no file/append/screen no (export-yade prints to the screen only)");
  const std::string& text = a.word(1, "the text to print");
  s_.py << "print(''";
  std::size_t from = 0;
  for (std::size_t k; (k = text.find('\x01', from)) != std::string::npos;) {
    const std::size_t e = text.find('\x01', k + 1);
    s_.py << " + " << yade_quoted(text.substr(from, k - from)) << " + " << exprs[std::stoi(text.substr(k + 1, e - k - 1))];
    from = e + 1;
  }
  s_.py << " + " << yade_quoted(text.substr(from)) << ")\n";
}

// ${name} and $x: equal-style variables become placeholders \x01k\x01 for
// exprs[k], other variables their value now; $(expr) is translated.
std::string YadeDeck::substitute(const std::string& line, const Args& at, std::vector<std::string>& exprs) {
  std::string out;
  auto hold = [&](const std::string& py) {
    out += "\x01" + std::to_string(exprs.size()) + "\x01";
    exprs.push_back(py);
  };
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] != '$' || i + 1 >= line.size()) {
      out += line[i];
      continue;
    }
    std::string name;
    if (line[i + 1] == '{' || line[i + 1] == '(') {
      const char close = line[i + 1] == '{' ? '}' : ')';
      std::size_t e = line.find(close, i + 2);
      if (close == ')') {  // $(expr) with parentheses inside: the balancing ')'
        int depth = 1;
        for (e = i + 2; e < line.size() && (depth += line[e] == '(' ? 1 : line[e] == ')' ? -1 : 0) > 0;) ++e;
        if (e >= line.size()) e = std::string::npos;
      }
      if (e == std::string::npos) at.fail(0, std::string("a closing '") + close + "'");
      name = line.substr(i + 2, e - i - 2);
      if (close == ')') {
        const std::size_t f = name.find(":%");  // $(expr:%fmt)
        if (f != std::string::npos)
          hold("(" + yade_quoted(yade_python_format(name.substr(f + 1))) + " % (" + s_.translate(name.substr(0, f), at) + "))");
        else
          hold("_fmt(" + s_.translate(name, at) + ")");
        i = e;
        continue;
      }
      i = e;
    } else {
      name = line.substr(i + 1, 1);
      ++i;
    }
    if (s_.formulas.count(name)) hold("_fmt(" + s_.translate("v_" + name, at) + ")");
    else out += s_.sim.variables->string_value(name, at);
  }
  return out;
}

// The scene, once: the contact law, the cell, each fix's translation in deck
// order, then what the script writes from them.
void YadeDeck::scene(const Args& run) {
  Simulation& sim = s_.sim;
  if (!sim.pair) run.fail_line("export-yade needs a pair_style before the first run");
  s_.first_run = &run;
  // sable's step and time where YADE's O.iter is 0 (a restart's step, reset_timestep):
  // the recorders' schedules and step/time values count from there.
  s_.py << "_step0[0], _step[0], _time0[0] = " << sim.step << ", " << sim.step << ", " << yade_num(sim.time) << "\n";
  sim.pair->export_yade(s_);
  s_.periodic_cell();
  s_.begin_fixes();
  for (const auto& f : sim.fixes) f->export_yade(s_);
  s_.check_integrated();
  s_.materials();
  s_.walls();
  s_.mesh_facets();
  s_.bodies();
  s_.engines();
  s_.recorders();
}

void YadeDeck::dump_recorders() {
  for (const auto& d : s_.sim.dumps)
    if (!s_.dumps_done.count(d->id)) {
      d->export_yade(s_);
      s_.dumps_done.insert(d->id);
    }
}

}  // namespace

void export_yade(Simulation& sim, Input& input, const std::string& deck, const std::string& out) {
  YadeDeck ex(sim, input);
  input.intercept = [&](const std::string& line, const DeckLocation& where) { return ex.intercept(line, where); };
  input.file(deck);
  input.intercept = nullptr;
  std::ofstream os(out);
  if (!os) fail("export-yade: cannot write " + out);
  os << ex.script();
  if (!os) fail("export-yade: writing " + out + " failed");
}

}  // namespace sable
