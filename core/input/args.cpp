#include "core/input/args.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "core/engine/error.h"

namespace sable {

bool parse_double(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtod(s.c_str(), &end);
  return end && *end == '\0' && errno == 0;
}

bool parse_long(const std::string& s, long& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtol(s.c_str(), &end, 10);
  return end && *end == '\0' && errno == 0;
}

void Args::fail(std::size_t i, const std::string& expected) const {
  std::string msg = where_.file + ":" + std::to_string(where_.line) + ": ";
  if (i < w_.size())
    msg += "'" + w_[i] + "' in '" + joined() + "': expected " + expected;
  else
    msg += "missing word at the end of '" + joined() + "': expected " + expected;
  throw SableError(msg);
}

void Args::fail_line(const std::string& msg) const {
  throw SableError(where_.file + ":" + std::to_string(where_.line) + ": '" + joined() + "': " + msg);
}

void Args::need(std::size_t n, const std::string& usage) const {
  if (w_.size() < n) fail(w_.size(), usage);
}

const std::string& Args::word(std::size_t i, const std::string& what) const {
  if (i >= w_.size()) fail(i, what);
  return w_[i];
}

double Args::num(std::size_t i, const std::string& what) const {
  double v;
  if (!parse_double(word(i, what), v)) fail(i, what + " (a number)");
  if (!std::isfinite(v)) fail(i, what + " (a finite number)");  // nan or inf would poison the run later
  return v;
}

long Args::integer(std::size_t i, const std::string& what) const {
  long v;
  if (!parse_long(word(i, what), v)) fail(i, what + " (an integer)");
  return v;
}

bool Args::yes_no(std::size_t i, const std::string& what) const {
  const std::string& s = word(i, what);
  if (s == "yes" || s == "on") return true;
  if (s == "no" || s == "off") return false;
  fail(i, what + " (yes/no or on/off)");
}

int Args::choice(std::size_t i, std::initializer_list<const char*> options, const std::string& note) const {
  std::string names;
  std::size_t k = 0;
  for (const char* o : options) {
    if (k > 0) names += k + 1 == options.size() ? " or " : ", ";
    names += o;
    ++k;
  }
  const std::string& w = word(i, names);
  k = 0;
  for (const char* o : options) {
    if (w == o) return static_cast<int>(k);
    ++k;
  }
  fail(i, names + note);
}

void Args::box_units_only(std::size_t from, const std::string& keyword, const std::string& lattice) const {
  for (std::size_t i = from; i < size(); i += 2) {
    if (w_[i] != "units") fail(i, keyword);
    const std::string& u = word(i + 1, "box");
    if (u == "lattice") fail(i + 1, lattice);
    if (u != "box") fail(i + 1, "box");
  }
}

Args Args::tail(std::size_t i) const {
  std::vector<std::string> rest(w_.begin() + std::min(i, w_.size()), w_.end());
  return Args(std::move(rest), where_);
}

std::string Args::joined(std::size_t from) const {
  std::string s;
  for (std::size_t k = from; k < w_.size(); ++k) {
    if (k > from) s += ' ';
    s += w_[k];
  }
  return s;
}

}  // namespace sable
