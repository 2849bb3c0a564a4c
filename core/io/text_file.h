#pragma once
// Small text outputs shared by the VTK dumps and the XDMF sidecars: a whole
// file replaced at once, and text escaped for an XML attribute or element.
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/engine/error.h"

namespace sable {

// Content goes to path.tmp, then is renamed: readers (and a killed run) never see a half-written file.
inline void write_file_atomic(const std::string& path, const std::string& text, const std::string& who) {
  const std::string tmp = path + ".tmp";
  FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) fail(who + ": cannot open '" + tmp + "' for writing");
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok) fail(who + ": writing '" + tmp + "' failed");
  std::filesystem::rename(tmp, path);
}

inline std::string xml_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    if (c == '&') r += "&amp;";
    else if (c == '<') r += "&lt;";
    else if (c == '>') r += "&gt;";
    else if (c == '"') r += "&quot;";
    else r += c;
  }
  return r;
}

}  // namespace sable
