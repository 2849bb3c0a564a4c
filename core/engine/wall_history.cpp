#include "core/engine/wall_history.h"

#include <cstdint>

#include "core/io/restart.h"

namespace sable {

void WallHistory::renumber(const std::vector<long>& old_ids, const std::vector<long>& new_ids) {
  const std::size_t hs = static_cast<std::size_t>(size_);
  std::size_t kept = 0;
  for (std::size_t r = 0; r < tag_.size(); ++r) {
    const auto at = std::lower_bound(old_ids.begin(), old_ids.end(), tag_[r]);
    if (at == old_ids.end() || *at != tag_[r]) continue;
    tag_[kept] = new_ids[static_cast<std::size_t>(at - old_ids.begin())];
    element_[kept] = element_[r];
    std::copy_n(hist_.begin() + r * hs, hs, hist_.begin() + kept * hs);
    ++kept;
  }
  tag_.resize(kept);
  element_.resize(kept);
  hist_.resize(kept * hs);
}

void WallHistory::write(restart::Packer& p) const {
  p.put<std::int32_t>(size_);
  const std::vector<std::int64_t> tags(tag_.begin(), tag_.end());
  p.put_vector(tags);
  p.put_vector(element_);
  p.put_vector(hist_);
}

bool WallHistory::read(restart::Unpacker& u) {
  const int size = u.get<std::int32_t>();
  const auto tags = u.get_vector<std::int64_t>();
  std::vector<int> element = u.get_vector<int>();
  std::vector<double> hist = u.get_vector<double>();
  configure(size_);
  if (size != size_ || element.size() != tags.size() || hist.size() != tags.size() * static_cast<std::size_t>(size_))
    return false;
  tag_.assign(tags.begin(), tags.end());
  element_ = std::move(element);
  hist_ = std::move(hist);
  return true;
}

}  // namespace sable
