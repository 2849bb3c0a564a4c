#pragma once
// The words of one deck command plus where they came from, with typed
// accessors whose errors name file, line, word and what was expected.
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
