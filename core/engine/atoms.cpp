#include "core/engine/atoms.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/engine/threads.h"

namespace sable {

Atoms::Atoms() = default;

// Applies f(vector, stride) to every per-atom array, so one place knows them all.
#define SABLE_ATOM_ARRAYS(fn)  \
  fn(id, 1);                   \
  fn(type, 1);                 \
  fn(mask, 1);                 \
  fn(x, 3);                    \
  fn(v, 3);                    \
  fn(f, 3);                    \
  fn(omega, 3);                \
  fn(torque, 3);               \
  fn(radius, 1);               \
  fn(rmass, 1);                \
  fn(density, 1);              \
  fn(image, 3);                \
  for (auto& c : extra_) fn(c.data, c.stride)

template <class F>
void Atoms::for_each_array(F&& fn) const {
  SABLE_ATOM_ARRAYS(fn);
}

template <class F>
void Atoms::for_each_array(F&& fn) {
  SABLE_ATOM_ARRAYS(fn);
}
#undef SABLE_ATOM_ARRAYS

void Atoms::drop_ghosts() {
  if (nghost == 0) return;
  nghost = 0;
  for_each_array([this](auto& vec, int stride) { vec.resize(n * stride); });
  invalidate();
}

std::size_t Atoms::add_ghosts(std::size_t count) {
  const std::size_t first = nall();
  nghost += count;
  for_each_array([this](auto& vec, int stride) { vec.resize(nall() * stride); });
  for (auto& c : extra_) std::fill(c.data.begin() + first * c.stride, c.data.end(), c.init);
  invalidate();
  return first;
}

std::size_t Atoms::record_size() const {
  std::size_t s = 0;
  for_each_array([&](const auto&, int stride) { s += static_cast<std::size_t>(stride); });
  return s;
}

void Atoms::pack(std::size_t i, std::vector<double>& out) const {
  for_each_array([&](const auto& vec, int stride) {
    for (int k = 0; k < stride; ++k) out.push_back(static_cast<double>(vec[i * stride + k]));
  });
}

void Atoms::unpack(std::size_t i, const double* in) {
  for_each_array([&](auto& vec, int stride) {
    using T = typename std::remove_reference_t<decltype(vec)>::value_type;
    for (int k = 0; k < stride; ++k) vec[i * stride + k] = static_cast<T>(*in++);
  });
  if (i < n) max_id = std::max(max_id, id[i]);
  invalidate();
}

std::size_t Atoms::add(long aid, int atype, const double xyz[3], double r, double rho) {
  drop_ghosts();
  const std::size_t i = n++;
  for_each_array([this](auto& vec, int stride) { vec.resize(n * stride); });
  for (auto& c : extra_) std::fill(c.data.begin() + i * c.stride, c.data.end(), c.init);
  id[i] = aid;
  type[i] = atype;
  mask[i] = 1u;  // group "all"
  for (int k = 0; k < 3; ++k) {
    x[3 * i + k] = xyz[k];
    v[3 * i + k] = f[3 * i + k] = omega[3 * i + k] = torque[3 * i + k] = 0.0;
    image[3 * i + k] = 0;
  }
  set_radius_density(i, r, rho);
  max_id = std::max(max_id, aid);
  invalidate();
  return i;
}

void Atoms::set_radius_density(std::size_t i, double r, double rho) {
  radius[i] = r;
  density[i] = rho;
  rmass[i] = mass_of(r, rho);
}

double Atoms::mass_of(double r, double rho) const {
  return area_density ? std::numbers::pi * r * r * rho : 4.0 / 3.0 * std::numbers::pi * r * r * r * rho;
}

void Atoms::remove_if(const std::vector<char>& doomed) {
  drop_ghosts();
  std::vector<std::size_t> keep;
  keep.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!doomed[i]) keep.push_back(i);
  permute(keep);
}

// Each array is gathered into a kept buffer of its type and stride, which then
// swaps with it: after the first sort no allocation, zero-fill or page fault
// (fresh arrays cost a serial memset and the kernel's page clearing at every
// neighbour rebuild). On the per-atom passes' ranges (atom_pass_threaded): each
// thread writes the grains it owns (a sort moves them little).
void Atoms::permute(const std::vector<std::size_t>& order) {
  drop_ghosts();
  const std::size_t m = order.size();
  const bool threads = loop_thread_count(m, 4) > 1;
  for_each_array([&](auto& vec, int stride) {
    using Vec = std::remove_reference_t<decltype(vec)>;
    Vec& out = std::get<std::map<int, Vec>>(scratch_)[stride];
    out.resize(m * stride);
#pragma omp parallel if (threads)
    {
#ifdef _OPENMP
      std::size_t lo, hi;
      split.range(m, omp_get_thread_num(), omp_get_num_threads(), lo, hi);
#else
      const std::size_t lo = 0, hi = m;
#endif
      for (std::size_t i = lo; i < hi; ++i)
        for (int k = 0; k < stride; ++k) out[i * stride + k] = vec[order[i] * stride + k];
    }
    vec.swap(out);
  });
  n = m;
  invalidate();
}

std::size_t Atoms::index_of(long aid) const {
  if (!map_valid_) {
    long mx = 0;
    const std::size_t all = nall();
    for (std::size_t i = 0; i < all; ++i) mx = std::max(mx, id[i]);
    map_.assign(mx + 1, npos);
    for (std::size_t i = all; i-- > n;) map_[id[i]] = i;  // ghosts first: an owned atom's index wins
    for (std::size_t i = 0; i < n; ++i) map_[id[i]] = i;
    map_valid_ = true;
  }
  if (aid < 0 || static_cast<std::size_t>(aid) >= map_.size()) return npos;
  return map_[aid];
}

int Atoms::find_column(const std::string& name) const {
  for (std::size_t c = 0; c < extra_.size(); ++c)
    if (extra_[c].name == name) return static_cast<int>(c);
  return -1;
}

int Atoms::add_column(const std::string& name, int stride, double init) {
  drop_ghosts();  // the next neighbour build brings them back with the new column
  const int h = find_column(name);
  if (h >= 0) {
    Column& c = extra_[h];
    c.init = init;
    if (c.stride != stride) {
      c.stride = stride;
      c.data.assign(n * stride, init);
    }
    return h;
  }
  extra_.push_back({name, stride, init, std::vector<double>(n * stride, init)});
  return static_cast<int>(extra_.size()) - 1;
}

void Atoms::resize(std::size_t count) {
  drop_ghosts();
  const std::size_t old = n;
  n = count;
  for_each_array([this](auto& vec, int stride) { vec.resize(n * stride); });
  for (auto& c : extra_)
    if (n > old) std::fill(c.data.begin() + old * c.stride, c.data.end(), c.init);
  invalidate();
}

void Atoms::clear_forces() {
  std::fill(f.begin(), f.begin() + 3 * n, 0.0);
  std::fill(torque.begin(), torque.begin() + 3 * n, 0.0);
}

}  // namespace sable
