#pragma once
// The words of one deck command plus where they came from, with typed
// accessors whose errors name file, line, word and what was expected.
#include <initializer_list>
#include <string>
#include <vector>

namespace sable {

struct DeckLocation {
  std::string file = "(none)";
  int line = 0;
};

class Args {
 public:
  Args() = default;
  Args(std::vector<std::string> words, DeckLocation where) : w_(std::move(words)), where_(std::move(where)) {}

  std::size_t size() const { return w_.size(); }
  const std::string& operator[](std::size_t i) const { return w_[i]; }
  const std::vector<std::string>& words() const { return w_; }
  const DeckLocation& where() const { return where_; }
  const std::string& command() const { return w_.front(); }

  // Word i, or an error saying what was expected there.
  const std::string& word(std::size_t i, const std::string& what) const;
  double num(std::size_t i, const std::string& what) const;
  long integer(std::size_t i, const std::string& what) const;
  bool yes_no(std::size_t i, const std::string& what) const;  // yes/no/on/off
  // Word i as one of `options`: its index; else an error naming them ("a, b or c", then `note`).
  int choice(std::size_t i, std::initializer_list<const char*> options, const std::string& note = "") const;
  // `units box` pairs from word `from` on (sable moves atoms in box units only): `keyword` is what
  // else may stand there, `lattice` the error that says so to a deck asking for lattice units.
  void box_units_only(std::size_t from, const std::string& keyword, const std::string& lattice) const;
  // Error pointing at word i (or at the end of the line when i >= size()).
  [[noreturn]] void fail(std::size_t i, const std::string& expected) const;
  // Error about the whole command.
  [[noreturn]] void fail_line(const std::string& msg) const;
  // Require at least n words.
  void need(std::size_t n, const std::string& usage) const;
  // Words from i on, as a new Args with the same location (for sub-parsers).
  Args tail(std::size_t i) const;
  std::string joined(std::size_t from = 0) const;

 private:
  std::vector<std::string> w_;
  DeckLocation where_;
};

bool parse_double(const std::string& s, double& out);
bool parse_long(const std::string& s, long& out);

}  // namespace sable
