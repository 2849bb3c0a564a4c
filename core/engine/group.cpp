#include "core/engine/group.h"

#include "core/engine/error.h"
#include "core/input/args.h"

namespace sable {

int Groups::find(const std::string& name) const {
  for (std::size_t g = 0; g < names_.size(); ++g)
    if (names_[g] == name) return static_cast<int>(g);
  return -1;
}

int Groups::existing(const Args& a, std::size_t i) const {
  const int g = find(a.word(i, "a group ID"));
  if (g < 0) a.fail(i, "an existing group ID (define it with 'group' first)");
  return g;
}

int Groups::find_or_create(const std::string& name) {
  int g = find(name);
  if (g >= 0) return g;
  if (names_.size() >= 32) fail("too many groups (32 at most), cannot create '" + name + "'");
  names_.push_back(name);
  return static_cast<int>(names_.size()) - 1;
}

}  // namespace sable
