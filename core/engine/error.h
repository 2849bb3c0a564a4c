#pragma once
// Errors: every message names where it came from (deck file, line, word) or,
// during a run, the step, the atom and the cause.
#include <stdexcept>
#include <string>

namespace sable {

class SableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

[[noreturn]] inline void fail(const std::string& msg) { throw SableError(msg); }

}  // namespace sable
