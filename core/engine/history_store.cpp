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

void HistoryStore::migrate(const std::function<int(long)>& dest, const std::vector<char>& flip,
                           std::vector<std::vector<double>>& out) {
  const std::size_t hs = static_cast<std::size_t>(size_);
  auto put = [&](int rank, long tag, long partner, int element, const double* h, bool turned) {
    std::vector<double>& o = out[static_cast<std::size_t>(rank)];
    o.push_back(static_cast<double>(tag));
    o.push_back(static_cast<double>(partner));
    o.push_back(element);
    for (std::size_t m = 0; m < hs; ++m) o.push_back(turned && flip[m] ? -h[m] : h[m]);
  };
  std::size_t kept = 0;
  for (std::size_t r = 0; r < tag_.size(); ++r) {
    const double* h = hist_.data() + r * hs;
    const int dt = dest(tag_[r]), dp = partner_[r] == kWall ? -2 : dest(partner_[r]);
    if (dt >= 0) put(dt, tag_[r], partner_[r], element_[r], h, false);
    if (dp >= 0 && dp != dt) put(dp, partner_[r], tag_[r], element_[r], h, true);
    if (dt != -1 && dp != -1) continue;  // neither grain stays here
    set_key(kept, key(r));
    std::copy_n(hist_.begin() + r * hs, hs, hist_.begin() + kept * hs);
    ++kept;
  }
  resize(kept);
}

std::size_t HistoryStore::receive(const double* in, std::size_t rows) {
  const std::size_t hs = static_cast<std::size_t>(size_), first = count();
  resize(first + rows);
  for (std::size_t r = 0; r < rows; ++r, in += 3 + hs) {
    set_key(first + r, {static_cast<long>(in[0]), static_cast<long>(in[1]), static_cast<int>(in[2])});
    std::copy_n(in + 3, hs, row(first + r));
  }
  return rows * (3 + hs);
}

void HistoryStore::sort() {
  std::vector<std::size_t> order(count());
  for (std::size_t r = 0; r < order.size(); ++r) order[r] = r;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  HistoryStore s;
  s.configure(size_);
  s.resize(order.size());
  for (std::size_t r = 0; r < order.size(); ++r) {
    s.set_key(r, key(order[r]));
    std::copy_n(row(order[r]), size_, s.row(r));
  }
  *this = std::move(s);
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
