#pragma once
// The file of a text dump: each snapshot goes out in one write(), so a kill
// never cuts an earlier one; single-file dumps keep it open between snapshots.
// And the head of a LAMMPS text snapshot (dump custom, dump local).
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "core/engine/domain.h"
#include "core/engine/error.h"

namespace sable {

// ITEM: TIMESTEP, ITEM: <count_item> ("NUMBER OF ATOMS", "NUMBER OF ENTRIES") and
// ITEM: BOX BOUNDS with the box; the ITEM line of the rows is the caller's.
inline void append_snapshot_head(std::string& out, const Domain& d, long step, const char* count_item, std::size_t n) {
  char buf[256];
  // Domain keeps only periodic flags, so LIGGGHTS' m/s letters print as f.
  std::snprintf(buf, sizeof buf, "ITEM: TIMESTEP\n%ld\nITEM: %s\n%zu\nITEM: BOX BOUNDS %s %s %s\n", step, count_item, n,
                d.periodic[0] ? "pp" : "ff", d.periodic[1] ? "pp" : "ff", d.periodic[2] ? "pp" : "ff");
  out += buf;
  for (int k = 0; k < 3; ++k) {
    std::snprintf(buf, sizeof buf, "%g %g\n", d.lo[k], d.hi[k]);
    out += buf;
  }
}

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
