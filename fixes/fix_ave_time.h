#pragma once
// Pieces shared by fix ave/time and fix ave/histo: the sampling schedule
// (LIGGGHTS' nextvalid()) and the text file (the HDF5 series: core/io/h5_series.h). Both
// outputs are kill-safe: a run killed at any instant leaves files that parse.
#include <cstdint>
#include <memory>
#include <string>

#include "core/engine/global_output.h"
#include <vector>

#include "core/input/args.h"
#include "core/io/h5_series.h"

namespace sable {
class Compute;
class Fix;
class Simulation;
}  // namespace sable

namespace sable::ave {

// One input of either fix: c_ID[i], f_ID[i], v_name (ave/histo: also an atom attribute, kind 'a').
struct Value {
  char kind = 0;
  std::string id, word;
  int index = 0;        // 0: the scalar (or the whole vector in vector mode)
  std::size_t at = 0;   // its word (errors point at it)
  bool off = false;     // ave/time's `off`
  GlobalOutput* g = nullptr;  // c_ID's or f_ID's global values
  Compute* c = nullptr;       // c_ID's compute (per-atom and local values)
  // Finds the compute, fix or variable it names, failing at its word; `self` (the
  // fix reading it) may not read itself (`doing`: what it would do, for the message).
  void resolve(Simulation& sim, const Args& a, const Fix* self, const char* doing);
};

// Steps on which inputs are sampled: Nrepeat samples Nevery apart, ending on a
// multiple of Nfreq that is >= start; and where the sampling stands.
struct Schedule {
  long nevery = 1, nrepeat = 1, nfreq = 1, start = 0;
  long nvalid = 0, irepeat = 0;              // the next sampling step; samples so far of this average
  void parse(const Args& a, std::size_t i);  // Nevery Nrepeat Nfreq at words i..i+2, with LIGGGHTS' checks
  long first_after(long step) const;         // the first sampling step >= step of the next average
  void begin(long step) {
    irepeat = 0;
    nvalid = first_after(step);
  }
  void resume(long step) {  // at a run's init: a sampling step passed unsampled starts afresh
    if (nvalid < step) begin(step);
  }
  // After the sample of `step`: true when it completes an average (the next sampling step is set).
  bool sampled(long step) {
    if (++irepeat < nrepeat) {
      nvalid += nevery;
      return false;
    }
    irepeat = 0;
    nvalid = step + nfreq - (nrepeat - 1) * nevery;
    return true;
  }
};

enum Ave { One, Running, Window };

// The keywords both fixes take: mode, ave, start, file, overwrite, hdf5,
// title1..3 (LIGGGHTS syntax).
struct Options {
  bool vector_mode = false, overwrite = false;
  Ave ave = One;
  long nwindow = 0;  // ave window M
  std::string file, h5file, title[3];
  bool titled[3] = {false, false, false};
  std::size_t file_at = 0;  // word of the file name (errors point at it)
  // Takes the keyword at word i and its arguments (advancing i) and returns
  // true, or returns false for a word that is none of these.
  bool parse(const Args& a, std::size_t& i, Schedule& sched, const char* start_what);
  void check(const Args& a) const;  // combinations LIGGGHTS refuses
  std::string title_or(int t, const std::string& dflt) const { return titled[t] ? title[t] : dflt; }
};

// A text file written as LIGGGHTS writes it, one block per output. Each block
// goes out in a single write() at once (nothing buffered), so a killed run
// leaves only complete lines. `overwrite` keeps the header and the latest block
// only, replacing the file atomically (temp + rename).
class TextFile {
 public:
  TextFile() = default;
  TextFile(const TextFile&) = delete;
  TextFile& operator=(const TextFile&) = delete;
  ~TextFile();
  void open(const Options& o, const Args& a);  // o.file, truncated (errors point at its word); o.overwrite
  bool is_open() const { return fd_ >= 0; }
  void header(const std::string& text);  // the title lines
  void block(const std::string& text);   // one output (lines ending in '\n')
  bool overwrite = false;

 private:
  int fd_ = -1;
  std::string path_, header_;
  void write_all(int fd, const std::string& s);
};

using sable::H5Series;  // core/io/h5_series.h

// The series file o.hdf5 names, with the words of the values (attribute `key`) and
// the fix's command (attribute "fix"); the caller adds its series, then starts it.
std::unique_ptr<H5Series> open_h5(const Options& o, const std::vector<Value>& values, const char* key, const Fix& fix);

}  // namespace sable::ave
