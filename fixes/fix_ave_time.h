#pragma once
// Pieces shared by fix ave/time and fix ave/histo: the sampling schedule
// (LIGGGHTS' nextvalid()), the text file and the HDF5 time series. Both
// outputs are kill-safe: a run killed at any instant leaves files that parse.
#include <cstdint>
#include <string>
#include <vector>

#include "core/args.h"

namespace sable::ave {

// Steps on which inputs are sampled: Nrepeat samples Nevery apart, ending on a
// multiple of Nfreq that is >= start.
struct Schedule {
  long nevery = 1, nrepeat = 1, nfreq = 1, start = 0;
  void parse(const Args& a, std::size_t i);  // Nevery Nrepeat Nfreq at words i..i+2, with LIGGGHTS' checks
  long first_after(long step) const;         // the first sampling step >= step of the next average
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
  void open(const std::string& path, const Args& a, std::size_t word);  // truncates; errors point at `word`
  bool is_open() const { return fd_ >= 0; }
  void header(const std::string& text);  // the title lines
  void block(const std::string& text);   // one output (lines ending in '\n')
  bool overwrite = false;

 private:
  int fd_ = -1;
  std::string path_, header_;
  void write_all(int fd, const std::string& s);
};

// An HDF5 file of growing datasets (rows appended during the run), written in
// SWMR mode: every append extends, writes and flushes, in an order that keeps
// the file on disk readable at any instant. A cleanly closed file opens
// normally; the file of a killed run opens with H5F_ACC_SWMR_READ (h5py:
// File(name, 'r', swmr=True)). Append the step dataset last: its length is the
// number of complete records.
class H5Series {
 public:
  explicit H5Series(const std::string& path);  // creates (truncates) the file
  H5Series(const H5Series&) = delete;
  H5Series& operator=(const H5Series&) = delete;
  ~H5Series();
  // Before start(): root attributes, constant datasets, growing datasets.
  void attribute(const std::string& name, const std::vector<std::string>& values);
  void constant(const std::string& name, const std::vector<double>& values);
  int series(const std::string& name, const std::vector<std::size_t>& row_shape, bool integer);
  void start();
  void append(int series, const double* row);
  void append(int series, std::int64_t value);  // integer series of scalars (steps)
  const std::string& path() const { return path_; }

 private:
  struct Series {
    std::int64_t dset;
    std::vector<unsigned long long> shape;  // row shape
    bool integer;
    unsigned long long rows = 0;
  };
  std::string path_;
  std::int64_t file_ = -1;
  std::vector<Series> series_;
  void append_raw(int series, const void* row);
};

}  // namespace sable::ave
