// sable's command line, read as LAMMPS and LIGGGHTS read theirs (README, "Running a deck"):
//   sable [-in deck] [-var NAME VALUE ...] [-log FILE|none] [-echo none|screen|log|both]
//         [-screen none|FILE] [-progress on|off|SECONDS]   (no -in: the deck on standard input)
//   sable --export-yade deck [-var NAME VALUE ...] -o script.py   (tools/export_yade.h)
//   sable --version | -h | --help
#include <unistd.h>

#include <cmath>
#include <chrono>
#include <cstdio>
#include <thread>
#include <cstdlib>
#include <initializer_list>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/engine/comm.h"
#include "core/engine/error.h"
#include "core/engine/simulation.h"
#include "core/engine/threads.h"
#include "core/engine/version.h"
#include "core/input/input.h"
#include "core/input/variable.h"
#include "tools/export_yade.h"

namespace {

using namespace sable;

const char* kUsage =
    "usage: sable [-in DECK] [-var NAME VALUE ...] [-log FILE|none] [-echo none|screen|log|both]\n"
    "             [-screen none|FILE] [-progress on|off|SECONDS]\n"
    "       sable --export-yade DECK [-var NAME VALUE ...] -o SCRIPT.py\n"
    "       sable --version | -h | --help\n";

const char* kHelp =
    "\n"
    "  -in DECK, -i DECK        run the deck (without -in: the deck piped on standard input,\n"
    "                           as in 'sable < in.deck'; '-in -' reads it there too)\n"
    "  -var NAME VALUE ...      define an index variable before the deck runs (-v)\n"
    "  -log FILE|none           the log file (default log.sable) (-l)\n"
    "  -echo none|screen|log|both   echo the deck's commands there (default none) (-e)\n"
    "  -screen none|FILE        screen output to nowhere or to FILE (default the terminal) (-sc)\n"
    "  -progress on|off|S       the screen's 'Progress: ... s left' lines during runs, every S\n"
    "                           wall seconds (on: 10); never written to the log\n"
    "  --export-yade DECK -o F  write a YADE script of the deck's scene instead of running it\n"
    "  --version                print the version and git commit\n"
    "  -h, --help               print this help\n"
    "\n"
    "sable runs as one process; its threads are OpenMP's: OMP_NUM_THREADS=N sable -in DECK.\n";

struct Options {
  std::string deck, log = "log.sable", screen, echo = "none", yade_script;
  std::vector<std::pair<std::string, std::vector<std::string>>> vars;
  bool export_yade = false, progress = true, version = false, help = false;
  double progress_every_s = 10.0;
};

// -progress S: wall seconds between progress lines (0: every step).
double seconds(const std::string& option, const std::string& v) {
  char* end = nullptr;
  const double s = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0' || !(s >= 0.0) || !std::isfinite(s))
    fail("command line: " + option + " '" + v + "': expected on, off or a number of seconds >= 0");
  return s;
}

Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* what) -> std::string {
      if (i + 1 >= argc) fail("command line: " + a + " needs " + what);
      return argv[++i];
    };
    auto choice = [&](const std::string& v, std::initializer_list<const char*> allowed, const char* what) {
      for (const char* c : allowed)
        if (v == c) return v;
      fail("command line: " + a + " '" + v + "': expected " + what);
    };
    if (a == "-in" || a == "-i") o.deck = value("a deck file (or - for standard input)");
    else if (a == "--export-yade") {
      o.deck = value("a deck file");
      o.export_yade = true;
    } else if (a == "-o") o.yade_script = value("a script file name");
    else if (a == "-log" || a == "-l") o.log = value("a log file name or none");
    else if (a == "-echo" || a == "-e")
      o.echo = choice(value("none, screen, log or both"), {"none", "screen", "log", "both"}, "none, screen, log or both");
    else if (a == "-screen" || a == "-sc") o.screen = value("none or a file name");
    else if (a == "-progress") {
      const std::string v = value("on, off or a number of seconds");
      o.progress = v != "off";
      if (v != "on" && v != "off") o.progress_every_s = seconds(a, v);
    }
    else if (a == "-var" || a == "-v") {
      const std::string name = value("a variable name");
      std::vector<std::string> vals;
      while (i + 1 < argc && argv[i + 1][0] != '-') vals.push_back(argv[++i]);
      if (vals.empty()) fail("command line: -var " + name + " needs at least one value");
      o.vars.emplace_back(name, vals);
    } else if (a == "-h" || a == "-help" || a == "--help") o.help = true;
    else if (a == "--version" || a == "-version") o.version = true;
    else
      fail("command line: unknown option '" + a +
           "' (expected -in, -var, -log, -echo, -screen, -progress, --export-yade, --version, --help)");
  }
  return o;
}

// A launcher's rank count that this process's MPI does not see: mpirun of a build without
// MPI (or another MPI's launcher) starts N copies that each run the whole deck and write the
// same files. Refuse, saying how sable uses a machine's cores instead.
std::string mpi_launch_problem(const Comm& comm) {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "MV2_COMM_WORLD_SIZE"}) {
    const char* v = std::getenv(var);
    if (v && std::atol(v) > 1 && comm.size() == 1)
      return std::string(Comm::built_with_mpi() ? "sable's MPI sees one process, but it" : "sable was built without MPI, but") +
             " was started as one of " + v + " processes (" + var + "=" + v + "): mpirun would run " + v +
             " independent copies of the deck, all writing the same files. "
             "Run one process and give it threads instead: OMP_NUM_THREADS=N sable -in DECK";
  }
  return "";
}

// The first lines of the screen and the log: what ran, from which commit, on how many threads.
void print_banner(Simulation& sim) {
  sim.print(version_line());
#ifdef _OPENMP
  sim.print("  OpenMP threads: " + std::to_string(atom_pass_threads()) + " (set with OMP_NUM_THREADS; one process)");
#else
  sim.print("  threads: 1 (built without OpenMP)");
#endif
}

// The deck piped to sable (`sable < in.deck`, as LAMMPS reads one); messages name it "stdin".
std::string read_stdin_deck() {
  std::ostringstream text;
  text << std::cin.rdbuf();
  if (text.str().find_first_not_of(" \t\r\n") == std::string::npos)
    fail("command line: standard input holds no deck (give one with -in DECK or pipe it: sable < in.deck)");
  return text.str();
}

struct CloseFile {
  void operator()(FILE* f) const { std::fclose(f); }
};

// -screen none|FILE: the screen output to nowhere or to FILE (held open by screen_file).
void open_screen(const Options& o, Simulation& sim, std::unique_ptr<FILE, CloseFile>& screen_file) {
  if (o.screen == "none" || sim.comm.rank() != 0) sim.screen = nullptr;
  else if (!o.screen.empty()) {
    screen_file.reset(std::fopen(o.screen.c_str(), "w"));
    if (!screen_file) fail("command line: -screen '" + o.screen + "': cannot open this file for writing");
    sim.screen = screen_file.get();
  }
}

int run(const Options& o, Simulation& sim, Input& input, std::unique_ptr<FILE, CloseFile>& screen_file) {
  open_screen(o, sim, screen_file);
  sim.progress = o.progress;
  sim.progress_every_s = o.progress_every_s;
  input.set_echo(o.echo);
  for (const auto& [name, vals] : o.vars) sim.variables->define_index(name, vals);
  if (o.export_yade) {
    if (o.yade_script.empty()) fail("command line: --export-yade needs -o script.py");
    if (sim.comm.size() > 1) fail("command line: --export-yade runs on one rank (without mpirun)");
    sim.open_log("none");
    export_yade(sim, input, o.deck, o.yade_script);
    return 0;
  }
  const bool piped = o.deck.empty() || o.deck == "-";
  if (piped && sim.comm.size() > 1)  // mpirun hands standard input to rank 0 alone
    fail("command line: on several MPI ranks the deck is read from a file: -in DECK");
  const std::string piped_deck = piped ? read_stdin_deck() : "";  // an empty one stops before the log opens
  sim.open_log(o.log);
  print_banner(sim);
  if (piped) input.text("stdin", piped_deck);
  else input.file(o.deck);
  return 0;
}

// Several ranks: an error may be this rank's alone (a grain that blew up, a file only
// rank 0 writes), the others waiting in a collective: rank 0 says it and ends every
// rank; another rank waits a moment for rank 0 to do so (the same error, met by all),
// and says it itself otherwise.
[[noreturn]] void stop_ranks(Simulation& sim, const char* what) {
  const int r = sim.comm.rank();
  if (r != 0) std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const std::string msg = r == 0 ? std::string("ERROR: ") + what : "ERROR on proc " + std::to_string(r) + ": " + what;
  std::fprintf(stderr, "%s\n", msg.c_str());
  if (sim.logfile) std::fprintf(sim.logfile, "%s\n", msg.c_str());
  if (sim.screen && sim.screen != stdout) std::fprintf(sim.screen, "%s\n", msg.c_str());
  std::fflush(nullptr);
  Comm::abort(1);
}

// Everything between MPI's start and end (main): returns the exit status.
int sable_main(int argc, char** argv) {
  std::unique_ptr<FILE, CloseFile> screen_file;  // -screen FILE; outlives sim, which writes to it
  Simulation sim;
  Input input(sim);
  try {
    const Options o = parse_options(argc, argv);
    if (o.help) {
      std::printf("%s%s%s", kUsage, kHelp,
                  Comm::built_with_mpi() ? "Built with MPI: mpirun -np N sable -in DECK splits the box over N ranks "
                                           "(docs/parallel.md says which commands run there).\n"
                                         : "Built without MPI.\n");
      return 0;
    }
    if (o.version) {
      std::printf("%s\n", version_line().c_str());
      return 0;
    }
    if (const std::string why = mpi_launch_problem(sim.comm); !why.empty()) fail(why);
    if (o.deck.empty() && isatty(STDIN_FILENO)) {  // nothing to run: say how
      std::fprintf(stderr, "%s", kUsage);
      return 2;
    }
    return run(o, sim, input, screen_file);
  } catch (const std::exception& e) {
    sim.flush_outputs();
    if (sim.comm.size() > 1) stop_ranks(sim, e.what());
    std::fprintf(stderr, "ERROR: %s\n", e.what());
    if (sim.logfile) std::fprintf(sim.logfile, "ERROR: %s\n", e.what());
    if (sim.screen && sim.screen != stdout) std::fprintf(sim.screen, "ERROR: %s\n", e.what());
    return 1;
  } catch (...) {  // nothing leaves sable as an uncaught exception (that would abort with a core dump)
    std::fprintf(stderr, "ERROR: internal error (an exception of unknown type); please report it with this deck\n");
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  Comm::init(&argc, &argv);  // MPI_Init where built with MPI (before Simulation reads its rank)
  const int status = sable_main(argc, argv);
  Comm::finalize();  // every rank, error or not: a collective end, no hang
  return status;
}
