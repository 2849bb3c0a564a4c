// sable -in deck [-var NAME VALUE ...] [-log FILE|none] [-echo none|screen] [-screen none]
// sable --export-yade deck [-var NAME VALUE ...] -o script.py   (tools/export_yade.h)
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/engine/error.h"
#include "core/input/input.h"
#include "core/engine/simulation.h"
#include "core/input/variable.h"
#include "tools/export_yade.h"

int main(int argc, char** argv) {
  using namespace sable;
  Simulation sim;
  Input input(sim);
  std::string deck, log = "log.sable", yade_script;
  bool export_yade_mode = false;
  auto usage = [] {
    std::fprintf(stderr, "usage: sable -in deck [-var NAME VALUE ...] [-log FILE|none] [-echo none|screen] [-screen none]\n"
                         "       sable --export-yade deck [-var NAME VALUE ...] -o script.py\n");
    return 2;
  };
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&](const char* what) -> std::string {
        if (i + 1 >= argc) fail(std::string("command line: ") + a + " needs " + what);
        return argv[++i];
      };
      if (a == "-in" || a == "-i") deck = value("a deck file");
      else if (a == "--export-yade") {
        deck = value("a deck file");
        export_yade_mode = true;
      } else if (a == "-o") yade_script = value("a script file name");
      else if (a == "-log" || a == "-l") log = value("a log file name or none");
      else if (a == "-echo" || a == "-e") input.echo_screen = (value("none or screen") == "screen");
      else if (a == "-screen" || a == "-sc") {
        if (value("none or a file") == "none") sim.screen = nullptr;
      } else if (a == "-var" || a == "-v") {
        const std::string name = value("a variable name");
        std::vector<std::string> vals;
        while (i + 1 < argc && argv[i + 1][0] != '-') vals.push_back(argv[++i]);
        if (vals.empty()) fail("command line: -var " + name + " needs at least one value");
        sim.variables->define_index(name, vals);
      } else if (a == "-h" || a == "-help") {
        return usage();
      } else {
        fail("command line: unknown option '" + a + "' (expected -in, -var, -log, -echo, -screen)");
      }
    }
    if (deck.empty()) return usage();
    if (export_yade_mode) {
      if (yade_script.empty()) fail("command line: --export-yade needs -o script.py");
      sim.open_log("none");
      export_yade(sim, input, deck, yade_script);
      return 0;
    }
    sim.open_log(log);
    input.file(deck);
  } catch (const std::exception& e) {
    sim.flush_outputs();
    std::fprintf(stderr, "ERROR: %s\n", e.what());
    if (sim.logfile) std::fprintf(sim.logfile, "ERROR: %s\n", e.what());
    if (sim.screen && sim.screen != stdout) std::fprintf(sim.screen, "ERROR: %s\n", e.what());
    return 1;
  } catch (...) {  // nothing leaves sable as an uncaught exception (that would abort with a core dump)
    std::fprintf(stderr, "ERROR: internal error (an exception of unknown type); please report it with this deck\n");
    return 1;
  }
  return 0;
}
