// plugin load FILE: a shared library whose static registrars add styles and contact
// models. dlopen runs those registrars, so the tag that the plugin's sources carry
// (core/input/plugin_abi.h) is read from the file first: a plugin built for another
// sable, or not against its headers, is refused before any of its code runs.
#include <dlfcn.h>
#include <elf.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "core/input/args.h"
#include "core/input/plugin_abi.h"
#include "core/input/style_registry.h"

namespace sable {
namespace {

constexpr const char* kTagSection = ".sable_plugin_abi";
constexpr std::size_t kMaxSection = 1 << 20;  // a section table or tag list beyond this is not a plugin's

// The bytes of one section of the file (empty if it cannot be read).
std::string section_bytes(std::ifstream& in, const Elf64_Shdr& s) {
  if (s.sh_type == SHT_NOBITS || s.sh_size > kMaxSection) return {};
  std::string b(s.sh_size, '\0');
  in.seekg(static_cast<std::streamoff>(s.sh_offset));
  return in.read(b.data(), static_cast<std::streamsize>(b.size())) ? b : std::string();
}

// The contents of FILE's tag section; nullopt when FILE is no 64-bit ELF file
// (dlopen then says why it cannot load it), empty when it has no such section.
std::optional<std::string> tag_section(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  Elf64_Ehdr eh;
  if (!in.read(reinterpret_cast<char*>(&eh), sizeof eh) || std::memcmp(eh.e_ident, ELFMAG, SELFMAG) != 0 ||
      eh.e_ident[EI_CLASS] != ELFCLASS64 || eh.e_shentsize != sizeof(Elf64_Shdr) || eh.e_shstrndx >= eh.e_shnum)
    return std::nullopt;
  std::vector<Elf64_Shdr> sh(eh.e_shnum);
  in.seekg(static_cast<std::streamoff>(eh.e_shoff));
  if (!in.read(reinterpret_cast<char*>(sh.data()), static_cast<std::streamsize>(sh.size() * sizeof(Elf64_Shdr))))
    return std::nullopt;
  const std::string names = section_bytes(in, sh[eh.e_shstrndx]);
  for (const Elf64_Shdr& s : sh)
    if (s.sh_name < names.size() && std::strcmp(names.c_str() + s.sh_name, kTagSection) == 0)
      return section_bytes(in, s);
  return std::string();
}

// The distinct tags of the section (one per source file, NUL-terminated, padded with NULs).
std::vector<std::string> distinct_tags(const std::string& section) {
  std::vector<std::string> tags;
  for (std::size_t at = 0; at < section.size();) {
    const std::size_t end = std::min(section.find('\0', at), section.size());
    const std::string t = section.substr(at, end - at);
    if (!t.empty() && std::find(tags.begin(), tags.end(), t) == tags.end()) tags.push_back(t);
    at = end + 1;
  }
  return tags;
}

// "0.8.0 (sable 0.8, C++ 202002L, cxx11-abi 1, openmp)" from a tag.
std::string described(const std::string& tag) {
  const std::string head = "sable-plugin ";
  const std::size_t semi = tag.find("; ");
  if (tag.rfind(head, 0) != 0 || semi == std::string::npos) return "'" + tag + "'";
  return tag.substr(head.size(), semi - head.size()) + " (" + tag.substr(semi + 2) + ")";
}

// Refuses FILE (word 2) unless all its sources were built for this sable's plugin ABI.
void check_tag(const std::string& path, const Args& a) {
  const std::optional<std::string> section = tag_section(path);
  if (!section) return;
  const std::vector<std::string> tags = distinct_tags(*section);
  const std::string ours = "this is sable " + described(SABLE_PLUGIN_TAG);
  const std::string rebuild = "; rebuild it against this sable's installed headers (find_package(sable " +
                              std::to_string(SABLE_VERSION_MAJOR) + "." + std::to_string(SABLE_VERSION_MINOR) +
                              ") and sable::plugin, contact_models/README.md)";
  if (tags.empty())
    a.fail(2, "a sable plugin, but it was not built against sable's headers (no " + std::string(kTagSection) +
                  " section); " + ours + rebuild);
  for (const std::string& t : tags)
    if (t.find("; ") == std::string::npos || t.substr(t.find("; ") + 2) != SABLE_PLUGIN_ABI)
      a.fail(2, "a plugin built for this sable, but it was built for sable " + described(t) + "; " + ours + rebuild);
}

void cmd_plugin(Simulation&, const Args& a) {
  if (a.word(1, "'load'") != "load") a.fail(1, "'load'");
  const std::string& path = a.word(2, "a shared library file");
  check_tag(path, a);
  if (!dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL)) a.fail(2, std::string("a loadable shared library (") + dlerror() + ")");
}

}  // namespace

SABLE_COMMAND("plugin", cmd_plugin);

}  // namespace sable
