#pragma once
// Named groups as bits of Atoms::mask ("all" is bit 0).
#include <cstdint>
#include <string>
#include <vector>

namespace sable {

class Args;

class Groups {
 public:
  Groups() { names_.push_back("all"); }
  int find(const std::string& name) const;  // -1 when absent
  int existing(const Args& a, std::size_t i) const;  // the group word i names, or an error there
  int find_or_create(const std::string& name);
  std::uint32_t bit(int g) const { return 1u << g; }
  const std::string& name(int g) const { return names_[g]; }
  std::size_t size() const { return names_.size(); }

 private:
  std::vector<std::string> names_;
};

}  // namespace sable
