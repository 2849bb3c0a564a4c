#include "core/io/h5_series.h"

#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <type_traits>

#include "core/engine/error.h"

namespace sable {

static_assert(std::is_same_v<hid_t, std::int64_t>, "H5Series stores hid_t as int64_t");

namespace {

[[noreturn]] void h5fail(const std::string& path, const std::string& what) {
  fail("HDF5 file '" + path + "': cannot " + what);
}

// The series alive (flush_all). Outputs are written by core's serial code only.
std::vector<H5Series*>& live() {
  static std::vector<H5Series*> all;
  return all;
}

hid_t open_rdwr(const std::string& path, unsigned flags) {
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR | flags, fapl);
  H5Pclose(fapl);
  return file;
}
hid_t open_for_append(const std::string& path) { return open_rdwr(path, H5F_ACC_SWMR_WRITE); }

// Attributes of a file or dataset: strings (variable length; a list or one), or one double.
bool write_strings(hid_t obj, const std::string& name, const std::vector<std::string>& values) {
  std::vector<const char*> p;
  for (auto& v : values) p.push_back(v.c_str());
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  const hsize_t n = values.size();
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t attr = H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
  const bool ok = attr >= 0 && H5Awrite(attr, type, p.data()) >= 0;
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
  return ok;
}
bool write_string(hid_t obj, const std::string& name, const std::string& value) {
  const char* p = value.c_str();
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
  const bool ok = attr >= 0 && H5Awrite(attr, type, &p) >= 0;
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
  return ok;
}
bool write_double(hid_t obj, const std::string& name, double value) {
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  const bool ok = attr >= 0 && H5Awrite(attr, H5T_NATIVE_DOUBLE, &value) >= 0;
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  return ok;
}

// The unit of time of a deck's unit style (sable's `units` accepts si only).
std::string time_unit(const std::string& style) {
  return style == "si" || style == "cgs" ? "s" : style == "lj" ? "tau" : "unknown (units " + style + ")";
}

}  // namespace

H5Series::H5Series(const std::string& path, std::size_t block_rows)
    : path_(path), block_rows_(std::max<std::size_t>(block_rows, 1)) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // our messages instead of HDF5's error stack
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST);  // SWMR needs the latest format
  file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  if (file_ < 0) h5fail(path, "be created (is the directory writable, or the file open elsewhere?)");
  live().push_back(this);
}

H5Series::~H5Series() {
  auto& all = live();
  all.erase(std::remove(all.begin(), all.end(), this), all.end());
  if (file_ >= 0) H5Fclose(file_);
  try {
    flush();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "WARNING: %s\n", e.what());
  }
}

void H5Series::attribute(const std::string& name, const std::vector<std::string>& values) {
  if (!write_strings(file_, name, values)) h5fail(path_, "write attribute '" + name + "'");
}

void H5Series::constant(const std::string& name, const std::vector<double>& values, std::vector<std::size_t> shape) {
  if (shape.empty()) shape.push_back(values.size());
  const std::vector<hsize_t> dims(shape.begin(), shape.end());
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t d = H5Dcreate2(file_, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const bool ok = d >= 0 && H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0;
  if (d >= 0) H5Dclose(d);
  H5Sclose(space);
  if (!ok) h5fail(path_, "write dataset '" + name + "'");
}

int H5Series::series(const std::string& name, const std::vector<std::size_t>& row_shape, bool integer) {
  if (step_ >= 0) h5fail(path_, "declare series '" + name + "' before the time axis");
  Series s;
  s.integer = integer;
  std::vector<hsize_t> dims{0}, maxdims{H5S_UNLIMITED}, chunk{1};
  hsize_t row = 1;
  for (auto k : row_shape) {
    s.shape.push_back(k);
    dims.push_back(k);
    maxdims.push_back(k);
    chunk.push_back(k);
    row *= k;
  }
  chunk[0] = std::clamp<hsize_t>(8192 / std::max<hsize_t>(row, 1), 1, 1024);  // chunks of ~64 KiB at most
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims.data());
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data());
  const hid_t dset =
      H5Dcreate2(file_, name.c_str(), integer ? H5T_STD_I64LE : H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Pclose(dcpl);
  H5Sclose(space);
  if (dset < 0) h5fail(path_, "create dataset '" + name + "'");
  H5Dclose(dset);
  s.name = name;
  s.row_bytes = static_cast<std::size_t>(row) * 8;  // 64-bit values
  series_.push_back(s);
  return static_cast<int>(series_.size()) - 1;
}

void H5Series::time_axis(const std::string& unit_style) {
  time_ = series("time", {}, false);
  step_ = series("step", {}, true);
  const hid_t d = H5Dopen2(file_, "time", H5P_DEFAULT);
  const bool ok = d >= 0 && write_string(d, "units", time_unit(unit_style)) && write_string(file_, "units", unit_style);
  if (d >= 0) H5Dclose(d);
  if (!ok) h5fail(path_, "write the attributes 'units' of the file and of dataset 'time'");
}

void H5Series::end_record(long step, double time, double dt) {
  if (time_ < 0) h5fail(path_, "end a record: its layout has no time axis (time_axis())");
  if (!dt_written_ && dt_ == 0.0) dt_ = dt;
  append(time_, &time);
  append(step_, static_cast<std::int64_t>(step));
}

// Attributes cannot be added in SWMR mode: the time step goes in with a plain
// open before the first block (the deck's `timestep` may follow the output's line).
void H5Series::write_timestep() {
  const hid_t file = open_rdwr(path_, 0);
  if (file < 0) h5fail(path_, "be opened to write its time step (was it moved or opened elsewhere?)");
  const hid_t d = H5Dopen2(file, "time", H5P_DEFAULT);
  bool ok = d >= 0 && write_double(d, "timestep", dt_) && write_double(file, "timestep", dt_);
  if (d >= 0) H5Dclose(d);
  ok = H5Fclose(file) >= 0 && ok;
  if (!ok) h5fail(path_, "write the attribute 'timestep'");
  dt_written_ = true;
}

// Closed between blocks, so that a killed run leaves a file marked consistent.
void H5Series::start() {
  if (H5Fclose(file_) < 0) h5fail(path_, "be closed after its layout was written");
  file_ = -1;
  started_ = true;
}

void H5Series::append_raw(int k, const void* row) {
  if (!started_) h5fail(path_, "append a record before its layout is complete (start())");
  Series& s = series_[k];
  const auto* p = static_cast<const unsigned char*>(row);
  s.pending.insert(s.pending.end(), p, p + s.row_bytes);
  pending_bytes_ += s.row_bytes;
  if (k + 1 < static_cast<int>(series_.size())) return;  // the last-declared series ends a record
  ++records_;
  if (records_ >= block_ || pending_bytes_ >= kBlockBytes) flush();  // blocks of whole records
}

void H5Series::append(int k, const double* row) { append_raw(k, row); }
void H5Series::append(int k, std::int64_t value) { append_raw(k, &value); }

// Extends s by its pending rows and writes them; the dataset is flushed so
// that the next one (the step last) reaches the disk after it.
bool H5Series::write_series(hid_t file, Series& s) {
  const unsigned long long n = s.pending.size() / std::max<std::size_t>(s.row_bytes, 1);
  std::vector<hsize_t> dims{s.rows + n}, start{s.rows}, count{n};
  for (auto d : s.shape) {
    dims.push_back(d);
    start.push_back(0);
    count.push_back(d);
  }
  const hid_t dset = H5Dopen2(file, s.name.c_str(), H5P_DEFAULT);
  if (dset < 0) return false;
  bool ok = H5Dset_extent(dset, dims.data()) >= 0;
  const hid_t fspace = H5Dget_space(dset);
  const hid_t mspace = H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr);
  ok = ok && H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr) >= 0;
  ok = ok && H5Dwrite(dset, s.integer ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT,
                      s.pending.data()) >= 0;
  ok = ok && H5Dflush(dset) >= 0;
  H5Sclose(mspace);
  H5Sclose(fspace);
  H5Dclose(dset);
  if (ok) s.rows += n;
  return ok;
}

// One open of the file per block. On failure the block is dropped, so that
// the error is raised once (a later flush, e.g. on the error's way out, has nothing to write).
void H5Series::flush() {
  if (pending_bytes_ == 0) return;
  if (time_ >= 0 && !dt_written_) write_timestep();
  const hid_t file = open_for_append(path_);
  bool ok = file >= 0;
  for (Series& s : series_) {
    if (ok && !s.pending.empty()) ok = write_series(file, s);
    s.pending.clear();
  }
  records_ = pending_bytes_ = 0;
  block_ = std::min(2 * block_, block_rows_);
  if (file >= 0) ok = H5Fclose(file) >= 0 && ok;
  if (file < 0) h5fail(path_, "be opened to append records (was it moved or opened elsewhere?)");
  if (!ok) h5fail(path_, "append to a dataset (disk full?)");
  if (on_written) on_written(static_cast<std::size_t>(series_.back().rows));
}

void H5Series::flush_all() {
  std::string first;
  for (H5Series* h : live()) {
    try {
      h->flush();
    } catch (const std::exception& e) {
      if (first.empty()) first = e.what();
    }
  }
  if (first.empty()) return;
  if (std::current_exception()) {
    std::fprintf(stderr, "WARNING: %s\n", first.c_str());
    return;
  }
  fail(first);
}

}  // namespace sable
