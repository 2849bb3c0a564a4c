#pragma once
// Base of dumps (LIGGGHTS `dump ID group style N file args`). Files are
// written to a temporary name and renamed, so a killed run never leaves a
// half-written snapshot.
#include <string>
#include <vector>

#include "core/input/args.h"

namespace sable {

class Simulation;
class YadeScript;  // core/io/yade_script.h

class Dump {
 public:
  Dump(Simulation& sim, const Args& args);  // args: ID group style N file ...
  virtual ~Dump() = default;
  Simulation& sim;
  Args args;
  std::string id, style, file;
  int group = 0;
  std::uint32_t groupbit = 1;
  long every = 1;
  bool sort_by_id = false;
  bool multifile = false;   // '*' in the file name
  virtual void init() {}
  void write(long step);    // called when step % every == 0
  virtual bool modify_param(const Args& args, std::size_t& i);  // dump_modify keywords
  virtual void flush() {}
  // sable --export-yade: this dump as a recorder of the YADE script (core/io/yade_script.h).
  virtual void export_yade(YadeScript&) const {
    args.fail(3, "dump custom or local (export-yade translates these text dumps only; '" + style + "' is not translated)");
  }

 protected:
  // Write one snapshot to `path` (already temporary when multifile).
  virtual void write_snapshot(long step, const std::string& path, bool append) = 0;
  std::vector<std::size_t> selected_atoms() const;  // group members, sorted by id if asked
  bool first_ = true;
};

}  // namespace sable
