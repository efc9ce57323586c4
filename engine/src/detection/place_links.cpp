#include "bowg/detection/place_links.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace bowg {

EntryId PlaceLinks::root(EntryId e) const {
  if (e >= parent_.size()) return e;
  // Path halving; parents are never larger, so the root is the smallest id.
  while (parent_[e] != e) e = parent_[e] = parent_[parent_[e]];
  return e;
}

void PlaceLinks::link(EntryId a, EntryId b) {
  const std::size_t needed = static_cast<std::size_t>(std::max(a, b)) + 1;
  while (parent_.size() < needed) parent_.push_back(static_cast<EntryId>(parent_.size()));
  size_.resize(parent_.size(), 1);
  const EntryId ra = root(a), rb = root(b);
  if (ra == rb) return;
  const EntryId joined = std::min(ra, rb), other = std::max(ra, rb);
  parent_[other] = joined;
  size_[joined] += size_[other];
}

std::size_t PlaceLinks::placeSize(EntryId e) const {
  const EntryId r = root(e);
  return r < size_.size() ? size_[r] : 1;
}

bool PlaceLinks::linked(const Island& a, const Island& b) const {
  for (EntryId e = a.first; e <= a.last; ++e) {
    const EntryId r = root(e);
    for (EntryId f = b.first; f <= b.last; ++f) {
      if (root(f) == r) return true;
    }
  }
  return false;
}

std::vector<EntryId> PlaceLinks::parents(std::size_t entries) const {
  std::vector<EntryId> out(entries);
  for (std::size_t i = 0; i < entries; ++i) {
    out[i] = i < parent_.size() ? parent_[i] : static_cast<EntryId>(i);
  }
  return out;
}

void PlaceLinks::restore(std::vector<EntryId> parents) {
  for (std::size_t i = 0; i < parents.size(); ++i) {
    if (parents[i] > i) {
      throw std::invalid_argument("place link of entry " + std::to_string(i) +
                                  " points to a later entry (" + std::to_string(parents[i]) + ")");
    }
  }
  parent_ = std::move(parents);
  size_.assign(parent_.size(), 0);
  for (std::size_t i = 0; i < parent_.size(); ++i) ++size_[root(static_cast<EntryId>(i))];
}

}  // namespace bowg
