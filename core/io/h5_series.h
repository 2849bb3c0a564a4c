#pragma once
// Output: HDF5 time series (fix ave/time, fix ave/histo, field outputs).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace sable {

// An HDF5 file of growing datasets (rows appended during the run). Rows are
// kept in memory and written in blocks, each in one open of the file in
// SWMR-write mode (extend, write, flush each dataset, close). A record ends
// with an append to the last-declared series (the step: declare it last, it
// is written last and its length counts the complete records). Blocks hold
// 1, 2, 4, ... records, then block_rows (kBlockRows) each: early records
// reach the disk at once, a long series costs one open per block_rows
// records. A block is also written at a record's end once kBlockBytes are
// buffered, at flush(), at flush_all() (Simulation::flush_outputs: the end
// of every run and before an error stops one) and at destruction. The rows
// written are those a row by row write gives, bit for bit.
// The file is closed between blocks, so a killed run's file opens normally
// (h5py: File(name, 'r')) and holds every record but the buffered ones: a
// kill loses fewer than block_rows records, and no more than the file
// already holds, plus the one being appended. A kill inside a block's write
// leaves the file readable with H5F_ACC_SWMR_READ (h5py: swmr=True).
// The time axis (time_axis(), every file sable's deck writes has one): the
// root attribute `units` (the deck's unit style), then two series declared
// last, `time` (the simulated time of each record; attribute `units`, the
// style's time unit) and `step`. Both `time` and the root carry the attribute
// `timestep` (dt of the first record: the deck may set it after the output's
// line; `time` holds each record's own time when dt changes between runs).
class H5Series {
 public:
  // Records per block, chosen so that a row every step costs a small run < 5 %
  // (input_scripts/bench/h5_record.in, figures in history.md).
  static constexpr std::size_t kBlockRows = 4096;
  static constexpr std::size_t kBlockBytes = std::size_t(1) << 20;  // bounds the memory of big rows (grids)

  // Creates (truncates) the file. block_rows: records per block (1: every record written at once).
  explicit H5Series(const std::string& path, std::size_t block_rows = kBlockRows);
  H5Series(const H5Series&) = delete;
  H5Series& operator=(const H5Series&) = delete;
  ~H5Series();  // writes the buffered rows (a failure is printed: destructors do not throw)
  // Before start(): root attributes, constant datasets, growing datasets.
  void attribute(const std::string& name, const std::vector<std::string>& values);
  // A constant dataset, 1-D or of the given shape (its product is values.size()).
  void constant(const std::string& name, const std::vector<double>& values, std::vector<std::size_t> shape = {});
  int series(const std::string& name, const std::vector<std::size_t>& row_shape, bool integer);
  // The time and step series, declared last (after every series()).
  void time_axis(const std::string& unit_style);
  void start();
  void append(int series, const double* row);
  void append(int series, std::int64_t value);  // integer series of scalars (steps)
  // Ends a record of a file with a time axis: its time, then its step. dt: the time step
  // (written as the `timestep` attribute with the first block).
  void end_record(long step, double time, double dt);
  // Called after each block reaches the file, with the complete records it holds (sidecars).
  std::function<void(std::size_t records)> on_written;
  void flush();  // writes the buffered rows now (nothing to do: the file is not opened)
  // flush() on every H5Series alive. Inside an exception handler a failure is
  // printed, not thrown, so the error being handled stays the one reported.
  static void flush_all();
  std::size_t buffered_records() const { return records_; }
  const std::string& path() const { return path_; }

 private:
  struct Series {
    std::string name;
    std::vector<unsigned long long> shape;  // row shape
    bool integer;
    unsigned long long rows = 0;            // rows in the file
    std::size_t row_bytes = 0;
    std::vector<unsigned char> pending;     // rows not yet written, as appended
  };
  std::string path_;
  std::int64_t file_ = -1;
  bool started_ = false;
  std::size_t block_rows_, block_ = 1, records_ = 0, pending_bytes_ = 0;  // block_: records in the next block
  int time_ = -1, step_ = -1;         // the time axis' series
  double dt_ = 0.0;                   // the first record's time step, until written
  bool dt_written_ = false;
  void write_timestep();
  std::vector<Series> series_;
  void append_raw(int series, const void* row);
  bool write_series(std::int64_t file, Series& s);
};

}  // namespace sable
