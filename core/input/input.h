#pragma once
// Reads decks line by line as LIGGGHTS does: comments, '&' continuation,
// quotes, ${name}/$x substitution, immediate $(expr), then dispatches the
// command. Flow commands (include, label, jump, next, if, print, variable,
// log, echo) live here; every other command is a registered style/command.
#include <exception>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/input/args.h"

namespace sable {

class Simulation;

// Several MPI ranks: a command or style that does not run there yet stops at its
// line (core/input/several_ranks.cpp); nothing on one rank.
void check_several_ranks(const Simulation& sim, const Args& a);

class Input {
 public:
  explicit Input(Simulation& sim);
  void file(const std::string& path);          // run a whole deck file
  // Run deck text held in memory, located as `name` in messages (tests, -in -).
  void text(const std::string& name, const std::string& deck);
  void one(const std::string& line, const DeckLocation& where);  // run one command line
  // Split a line into words after substitution (exposed for tests).
  std::vector<std::string> parse(const std::string& line, const DeckLocation& where);
  const DeckLocation& where() const { return where_; }
  // `echo` / -echo: where the deck's commands are echoed (LAMMPS' none, screen, log, both).
  bool echo_screen = false, echo_log = false;
  bool set_echo(const std::string& mode);  // false: not one of the four
  // Sees each command line before substitution; returning true consumes it
  // (sable --export-yade translates `run` and `print` instead of executing them).
  std::function<bool(const std::string& line, const DeckLocation& where)> intercept;

 private:
  Simulation& sim_;
  DeckLocation where_;
  struct Frame {
    std::string path;
    std::vector<std::string> lines;  // physical lines
    std::size_t next = 0;            // index of next physical line
  };
  std::vector<Frame> stack_;
  std::string jump_label_;  // skip commands until this label
  bool skip_jump_ = false;  // set when `next` exhausts a variable
  void run_frame();
  std::string substitute(const std::string& line, const DeckLocation& where);
  void execute(const Args& args);
  void cmd_jump(const Args& a);
  void cmd_if(const Args& a);
  void cmd_print(const Args& a);
  void cmd_include(const Args& a);
  [[noreturn]] void rethrow_located(const std::exception& e, const std::string& line, const DeckLocation& where);
  static constexpr std::size_t kMaxIncludeDepth = 32;  // deeper is a file including itself
  static constexpr int kMaxIdleJumps = 10000;
  static constexpr int kMaxAtomOnlyJumps = 10000;
  struct JumpSite {  // the state at a jump line's previous pass (see cmd_jump)
    std::string state, but_atoms;
    int same = 0, atom_only = 0;
  };
  std::map<std::string, JumpSite> jumps_;  // by file:line
};

}  // namespace sable
