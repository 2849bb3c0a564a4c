#include "core/input/input.h"

#include <cctype>
#include <cmath>
#include <new>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/engine/error.h"
#include "core/input/number_format.h"
#include "core/input/expression.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/input/variable.h"

namespace sable {

Input::Input(Simulation& sim) : sim_(sim) { sim.input = this; }

static std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail("cannot open deck file '" + path + "' (does it exist and is it readable?)");
  std::vector<std::string> lines;
  std::string s;
  while (std::getline(in, s)) lines.push_back(s);
  return lines;
}

void Input::file(const std::string& path) {
  stack_.push_back({path, read_lines(path), 0});
  run_frame();
  stack_.pop_back();
}

void Input::text(const std::string& name, const std::string& deck) {
  std::vector<std::string> lines;
  std::istringstream ss(deck);
  for (std::string l; std::getline(ss, l);) lines.push_back(l);
  stack_.push_back({name, std::move(lines), 0});
  run_frame();
  stack_.pop_back();
}

void Input::run_frame() {
  const std::size_t depth = stack_.size();
  while (stack_.size() == depth && stack_.back().next < stack_.back().lines.size()) {
    Frame& f = stack_.back();
    DeckLocation where{f.path, static_cast<int>(f.next) + 1};
    std::string line = f.lines[f.next++];
    // '&' at the end joins the next physical line.
    while (true) {
      std::size_t e = line.find_last_not_of(" \t\r");
      if (e == std::string::npos || line[e] != '&' || f.next >= f.lines.size()) break;
      line = line.substr(0, e) + " " + f.lines[f.next++];
    }
    one(line, where);
  }
}

// Drop a '#' comment that is not inside quotes.
static std::string strip_comment(const std::string& s) {
  char q = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (q) {
      if (s[i] == q) q = 0;
    } else if (s[i] == '"' || s[i] == '\'') {
      q = s[i];
    } else if (s[i] == '#') {
      return s.substr(0, i);
    }
  }
  return s;
}

// Immediate $(expr) prints like LAMMPS/LIGGGHTS: %.20g unless a format is given.
static std::string format_number(double v, const std::string& fmt) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt.empty() ? "%.20g" : fmt.c_str(), v);
  return buf;
}

std::string Input::substitute(const std::string& line, const DeckLocation& where) {
  std::string out;
  // LAMMPS rule: no substitution inside single or triple quotes; double quotes do not protect.
  bool in_single = false, in_double = false, in_triple = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (!in_single && line.compare(i, 3, "\"\"\"") == 0) {
      in_triple = !in_triple;
      out += "\"\"\"";
      i += 2;
      continue;
    }
    if (!in_triple && !in_double && c == '\'') in_single = !in_single;
    if (!in_triple && !in_single && c == '"') in_double = !in_double;
    if (in_single || in_triple) {
      out += c;
      continue;
    }
    if (c != '$' || i + 1 >= line.size()) {
      out += c;
      continue;
    }
    const char d = line[i + 1];
    Args here({line}, where);
    if (d == '{') {
      const std::size_t close = line.find('}', i + 2);
      if (close == std::string::npos) here.fail(0, "a closing '}' after '${'");
      const std::string name = line.substr(i + 2, close - i - 2);
      out += sim_.variables->string_value(name, here);
      i = close;
    } else if (d == '(') {
      int depth = 0;
      std::size_t k = i + 1;
      for (; k < line.size(); ++k) {
        if (line[k] == '(') ++depth;
        if (line[k] == ')' && --depth == 0) break;
      }
      if (k >= line.size()) here.fail(0, "a closing ')' after '$('");
      std::string expr = line.substr(i + 2, k - i - 2), fmt;
      const std::size_t colon = expr.rfind(':');
      if (colon != std::string::npos && colon + 1 < expr.size() && expr[colon + 1] == '%') {
        fmt = expr.substr(colon + 1);
        expr = expr.substr(0, colon);
        const std::string bad = number_format_problem(fmt, false);
        if (!bad.empty()) here.fail_line("the format '" + fmt + "' in '$(" + expr + ":" + fmt + ")' needs " + bad);
      }
      out += format_number(sim_.variables->evaluate(expr, here), fmt);
      i = k;
    } else if (std::isalpha(static_cast<unsigned char>(d))) {
      out += sim_.variables->string_value(std::string(1, d), here);
      ++i;
    } else {
      out += c;
    }
  }
  return out;
}

std::vector<std::string> Input::parse(const std::string& raw, const DeckLocation& where) {
  const std::string line = substitute(strip_comment(raw), where);
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i >= line.size()) break;
    std::string w;
    if (line.compare(i, 3, "\"\"\"") == 0) {
      const std::size_t e = line.find("\"\"\"", i + 3);
      if (e == std::string::npos) Args({line}, where).fail(0, "closing \"\"\"");
      w = line.substr(i + 3, e - i - 3);
      i = e + 3;
    } else if (line[i] == '"' || line[i] == '\'') {
      const char q = line[i];
      const std::size_t e = line.find(q, i + 1);
      if (e == std::string::npos) Args({line}, where).fail(0, std::string("a closing ") + q + " quote");
      w = line.substr(i + 1, e - i - 1);
      i = e + 1;
    } else {
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) w += line[i++];
    }
    words.push_back(w);
  }
  return words;
}

void Input::one(const std::string& line, const DeckLocation& where) {
  where_ = where;
  // While jumping to a label, only the label line matters (and it needs no substitution).
  if (!jump_label_.empty()) {
    std::istringstream ss(strip_comment(line));
    std::string a, b;
    ss >> a >> b;
    if (a == "label" && b == jump_label_) jump_label_.clear();
    return;
  }
  try {
    if (intercept && intercept(line, where)) return;
    std::vector<std::string> words = parse(line, where);
    if (words.empty()) return;
    if (echo_screen || echo_log) sim_.print_to(line, echo_screen, echo_log);
    execute(Args(std::move(words), where));
  } catch (const std::exception& e) {
    rethrow_located(e, line, where);
  }
}

// Every error leaves here naming the deck file and line: messages that already name a
// place (Args::fail, a run's "during ... at FILE:LINE", an included file) pass unchanged;
// others get this line's location, and no raw std::bad_alloc reaches the user.
void Input::rethrow_located(const std::exception& e, const std::string& line, const DeckLocation& where) {
  const std::string msg = e.what();
  auto located = [&] {
    if (msg.find(where.file + ":" + std::to_string(where.line)) != std::string::npos) return true;
    const std::size_t c = msg.find(':');  // "FILE:LINE: ..." from a nested (included) deck
    std::size_t d = c + 1;
    while (c != std::string::npos && d < msg.size() && std::isdigit(static_cast<unsigned char>(msg[d]))) ++d;
    return c != std::string::npos && c > 0 && d > c + 1 && d < msg.size() && msg[d] == ':' &&
           msg.find_first_of(" \n") > c;
  };
  const std::string here = where.file + ":" + std::to_string(where.line) + ": '" + line.substr(0, 200) + "': ";
  if (dynamic_cast<const std::bad_alloc*>(&e))
    throw SableError(here + "out of memory (the command asks for more memory than this machine has: "
                            "check counts, box size and loop lengths)");
  if (dynamic_cast<const SableError*>(&e) || dynamic_cast<const ExpressionError*>(&e)) {
    if (located()) throw;
    throw SableError(here + msg);
  }
  throw SableError(here + "internal error (" + msg + "); please report it with this deck");
}

void Input::execute(const Args& a) {
  const std::string& c = a.command();
  if (c == "label") return;
  if (c == "include") return cmd_include(a);
  if (c == "jump") return cmd_jump(a);
  if (c == "if") return cmd_if(a);
  if (c == "print") return cmd_print(a);
  // sable's addition (LAMMPS has only `quit`): a deck's own check stops with its line and message.
  if (c == "error") a.fail_line("stopped by the deck: " + a.word(1, "the message to stop with"));
  if (c == "variable") return sim_.variables->define(a);
  if (c == "next") {
    a.need(2, "the name of a loop or index variable");
    // When a variable is exhausted, LAMMPS deletes it and skips the next jump.
    for (std::size_t i = 1; i < a.size(); ++i)
      if (!sim_.variables->next(a[i], a)) skip_jump_ = true;
    return;
  }
  if (c == "log") {
    sim_.open_log(a.word(1, "a log file name or none"));
    return;
  }
  if (c == "echo") {
    if (!set_echo(a.word(1, "none, screen, log or both"))) a.fail(1, "none, screen, log or both");
    return;
  }
  check_several_ranks(sim_, a);
  const auto* cmd = CommandRegistry::find(c);
  if (!cmd) a.fail(0, "a known command (see the README's command list; e.g. " + CommandRegistry::names().substr(0, 200) + " ...)");
  (*cmd)(sim_, a);
}

bool Input::set_echo(const std::string& mode) {
  if (mode != "none" && mode != "screen" && mode != "log" && mode != "both") return false;
  echo_screen = mode == "screen" || mode == "both";
  echo_log = mode == "log" || mode == "both";
  return true;
}

void Input::cmd_include(const Args& a) {
  const std::string& path = a.word(1, "a file name to include");
  if (stack_.size() >= kMaxIncludeDepth)
    a.fail(1, "at most " + std::to_string(kMaxIncludeDepth) + " nested includes (does '" + path + "' include itself?)");
  std::ifstream test(path);
  if (!test) a.fail(1, "a readable file to include");
  stack_.push_back({path, read_lines(path), 0});
  run_frame();
  stack_.pop_back();
}

void Input::cmd_jump(const Args& a) {
  if (skip_jump_) {
    skip_jump_ = false;
    return;
  }
  const std::string& target = a.word(1, "SELF or a deck file name");
  if (stack_.empty()) a.fail_line("jump works only inside a deck file");
  // A jump loop in which no variable, step or atom count changes between two passes
  // of the same jump line can never end; one in which only the atom count changes
  // (a 'next' moved after the jump) makes atoms until memory runs out: stopped
  // after kMaxAtomOnlyJumps. Per line: an inner loop's jumps between an outer
  // jump's passes do not reset the outer one's count.
  JumpSite& site = jumps_[a.where().file + ":" + std::to_string(a.where().line)];
  const std::string but_atoms = std::to_string(sim_.step) + "|" + sim_.variables->fingerprint();
  const std::string state = but_atoms + "|" + std::to_string(sim_.atoms.n);
  site.same = state == site.state ? site.same + 1 : 0;
  site.atom_only = but_atoms == site.but_atoms ? site.atom_only + 1 : 0;
  site.state = state;
  site.but_atoms = but_atoms;
  if (site.same >= kMaxIdleJumps)
    a.fail_line("endless loop: jumped " + std::to_string(kMaxIdleJumps) +
                " times with no variable, step or atom count changing (missing 'next'?)");
  if (site.atom_only >= kMaxAtomOnlyJumps)
    a.fail_line("endless loop: jumped " + std::to_string(kMaxAtomOnlyJumps) +
                " times with only the atom count changing (" + std::to_string(sim_.atoms.n) +
                " atoms; missing 'next'? count such a loop with 'variable i loop N' and 'next i')");
  Frame& f = stack_.back();
  if (target == "SELF" || target == f.path) {
    f.next = 0;
  } else {
    std::ifstream test(target);
    if (!test) a.fail(1, "SELF or a readable deck file");
    f = Frame{target, read_lines(target), 0};
  }
  if (a.size() > 2) {
    jump_label_ = a[2];
    // Make sure the label exists so a typo does not silently skip the rest.
    bool found = false;
    for (auto& l : f.lines) {
      std::istringstream ss(strip_comment(l));
      std::string x, y;
      ss >> x >> y;
      if (x == "label" && y == jump_label_) found = true;
    }
    if (!found) a.fail(2, "a label defined in " + f.path);
  }
}

void Input::cmd_if(const Args& a) {
  // if "cond" then "cmd" ... [elif "cond" "cmd" ...] [else "cmd" ...]
  std::size_t i = 1;
  bool done = false;
  auto run_block = [&](std::size_t from) {
    std::size_t k = from;
    for (; k < a.size() && a[k] != "elif" && a[k] != "else"; ++k) {
      if (!done) one(a[k], a.where());
    }
    return k;
  };
  const std::string& cond = a.word(i, "a condition in quotes");
  if (a.word(i + 1, "'then'") != "then") a.fail(i + 1, "'then'");
  auto test = [&](const std::string& c) {
    try {
      return evaluate_boolean(c) != 0.0;
    } catch (const ExpressionError& e) {
      a.fail_line(std::string("in if condition '") + c + "': " + e.what());
    }
  };
  const bool truth = test(cond);
  if (truth) {
    run_block(i + 2);
    return;
  }
  std::size_t k = i + 2;
  while (k < a.size() && a[k] != "elif" && a[k] != "else") ++k;
  while (k < a.size()) {
    if (a[k] == "elif") {
      const std::string& c2 = a.word(k + 1, "a condition after elif");
      if (test(c2)) {
        run_block(k + 2);
        return;
      }
      k += 2;
      while (k < a.size() && a[k] != "elif" && a[k] != "else") ++k;
    } else {  // else
      run_block(k + 1);
      return;
    }
  }
}

void Input::cmd_print(const Args& a) {
  const std::string& text = a.word(1, "the text to print");
  bool to_screen = true;
  for (std::size_t i = 2; i < a.size(); i += 2) {
    const std::string& k = a[i];
    if (k == "file" || k == "append") {
      const std::string& path = a.word(i + 1, "a file name");
      FILE* fp = std::fopen(path.c_str(), k == "file" ? "w" : "a");
      if (!fp) a.fail(i + 1, "a writable file");
      std::fprintf(fp, "%s\n", text.c_str());
      std::fclose(fp);
    } else if (k == "screen") {
      to_screen = a.yes_no(i + 1, "yes or no");
    } else {
      a.fail(i, "file, append or screen");
    }
  }
  if (to_screen) sim_.print(text);
}

}  // namespace sable
