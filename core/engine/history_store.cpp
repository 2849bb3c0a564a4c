#include "core/engine/history_store.h"

#include <cstdint>

#include "core/io/restart.h"

namespace sable {

void HistoryStore::append(const HistoryStore& from) {
  tag_.insert(tag_.end(), from.tag_.begin(), from.tag_.end());
  partner_.insert(partner_.end(), from.partner_.begin(), from.partner_.end());
  element_.insert(element_.end(), from.element_.begin(), from.element_.end());
  hist_.insert(hist_.end(), from.hist_.begin(), from.hist_.end());
}

void HistoryStore::renumber(const std::vector<long>& old_ids, const std::vector<long>& new_ids) {
  auto now = [&](long id) {  // the grain's new id, or kWall - 1 when deleted
    const auto at = std::lower_bound(old_ids.begin(), old_ids.end(), id);
    return at == old_ids.end() || *at != id ? kWall - 1 : new_ids[static_cast<std::size_t>(at - old_ids.begin())];
  };
  const std::size_t hs = static_cast<std::size_t>(size_);
  std::size_t kept = 0;
  for (std::size_t r = 0; r < tag_.size(); ++r) {
    const long tag = now(tag_[r]), partner = partner_[r] == kWall ? kWall : now(partner_[r]);
    if (tag == kWall - 1 || partner == kWall - 1) continue;
    set_key(kept, {tag, partner, element_[r]});
    std::copy_n(hist_.begin() + r * hs, hs, hist_.begin() + kept * hs);
    ++kept;
  }
  resize(kept);
}

void HistoryStore::write(restart::Packer& p) const {
  p.put<std::int32_t>(size_);
  p.put_vector(std::vector<std::int64_t>(tag_.begin(), tag_.end()));
  p.put_vector(std::vector<std::int64_t>(partner_.begin(), partner_.end()));
  p.put_vector(element_);
  p.put_vector(hist_);
}

bool HistoryStore::read(restart::Unpacker& u) {
  const int size = u.get<std::int32_t>();
  const auto tags = u.get_vector<std::int64_t>();
  const auto partners = u.get_vector<std::int64_t>();
  std::vector<int> element = u.get_vector<int>();
  std::vector<double> hist = u.get_vector<double>();
  clear();
  if (size != size_ || partners.size() != tags.size() || element.size() != tags.size() ||
      hist.size() != tags.size() * static_cast<std::size_t>(size_))
    return false;
  tag_.assign(tags.begin(), tags.end());
  partner_.assign(partners.begin(), partners.end());
  element_ = std::move(element);
  hist_ = std::move(hist);
  return true;
}

}  // namespace sable
