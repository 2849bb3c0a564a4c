#pragma once
// The file of a text dump: each snapshot goes out in one write(), so a kill
// never cuts an earlier one; single-file dumps keep it open between snapshots.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "core/engine/error.h"

namespace sable {

class DumpFile {
 public:
  DumpFile() = default;
  DumpFile(const DumpFile&) = delete;
  DumpFile& operator=(const DumpFile&) = delete;
  ~DumpFile() { close(); }

  // `keep`: append to an existing file instead of truncating it when opening it.
  // `multifile`: close after the snapshot (the dump base renames the temporary file).
  void write(const std::string& out, const std::string& path, bool keep, bool multifile, const std::string& id) {
    if (multifile || fd_ < 0 || path != path_) {
      close();
      fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | (keep ? 0 : O_TRUNC), 0644);
      if (fd_ < 0) fail("dump " + id + ": cannot open '" + path + "' for writing: " + std::strerror(errno));
      path_ = path;
    }
    for (std::size_t done = 0; done < out.size();) {
      const ssize_t w = ::write(fd_, out.data() + done, out.size() - done);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) fail("dump " + id + ": writing '" + path + "' failed: " + std::strerror(errno));
      done += static_cast<std::size_t>(w);
    }
    if (multifile) close();
  }

 private:
  void close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  int fd_ = -1;
  std::string path_;
};

}  // namespace sable
