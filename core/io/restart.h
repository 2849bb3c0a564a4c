#pragma once
// write_restart FILE / read_restart FILE: a binary snapshot of the state a
// LIGGGHTS-style deck cannot re-declare (box, step, time, groups, atoms with
// every extra column, contact history, fix states). As in LIGGGHTS, the deck
// that reads it declares pair style, walls and fixes again; their history
// re-attaches by atom ids (pair history, at the next setup) and by fix ID +
// style (fix states: among them the walls' contact history).
//
// File layout (native byte order, format version kFormat):
//   "SABLE RESTART\n" "format N\n"       text header, readable with `head -2`
//   u32 0x01020304                        byte-order mark
//   sections: u64 name length, name, u64 payload length, payload
//     info, box, time, types, groups, atoms, pair, fixes   (unknown ones are skipped)
//   section "end": u64 FNV-1a hash of every byte before it (truncation, corruption)
// Written to FILE.tmp.PID and renamed, so a killed run never leaves a partial file.
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace sable {

class Simulation;

namespace restart {

constexpr std::uint32_t kFormat = 3;  // 2: wall history in fix states; 3: every history keyed (grain, partner, element)

// Appends trivially copyable values, strings and vectors to a byte string.
class Packer {
 public:
  std::string bytes;
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void put_string(const std::string& s) {
    put<std::uint64_t>(s.size());
    bytes += s;
  }
  template <class T>
  void put_vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<std::uint64_t>(v.size());
    bytes.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
};

// Reads what Packer wrote; running past the end throws an error naming `what`.
class Unpacker {
 public:
  Unpacker(const std::string& bytes, std::string what)
      : p_(bytes.data()), end_(p_ + bytes.size()), what_(std::move(what)) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    std::memcpy(&v, take(sizeof v), sizeof v);
    return v;
  }
  std::string get_string() {
    const auto n = get<std::uint64_t>();
    return std::string(take(n), n);
  }
  template <class T>
  std::vector<T> get_vector() {
    const auto n = get<std::uint64_t>();
    if (n > static_cast<std::uint64_t>(end_ - p_) / sizeof(T)) truncated(n * sizeof(T));
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), take(n * sizeof(T)), n * sizeof(T));
    return v;
  }
  std::size_t left() const { return static_cast<std::size_t>(end_ - p_); }

 private:
  const char* p_;
  const char* end_;
  std::string what_;
  const char* take(std::uint64_t n) {
    if (n > left()) truncated(n);
    const char* at = p_;
    p_ += n;
    return at;
  }
  [[noreturn]] void truncated(std::uint64_t n) const;
};

// The commands' work, for tests and tools. `path` is used as given ('*' already replaced).
void write(Simulation& sim, const std::string& path);
void read(Simulation& sim, const std::string& path);
// One line per section: what a restart file holds (sizes, pair model, fix states).
std::string summary(const std::string& path);

}  // namespace restart
}  // namespace sable
