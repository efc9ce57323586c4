// Which database entries are one place: entries joined by accepted loops
// (a loop says the query and its match were taken at the same place), as
// disjoint sets. On a circuit driven lap after lap, the geometric re-ranking
// picks the best of several true places (the same stretch on each earlier
// lap) and its choice jumps between laps from query to query; each jump
// would restart the temporal chain although the robot never left the place.
// With the links, an island continues a chain that ends at a place it is
// linked to (TemporalVerificationOptions::linked_places).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/detection/islands.h"

namespace bowg {

class PlaceLinks {
 public:
  /// Joins the places of entries `a` and `b`.
  void link(EntryId a, EntryId b);
  /// The smallest entry id of `e`'s place (e itself when never linked).
  EntryId root(EntryId e) const;
  /// Whether an entry of `a` (first..last) and one of `b` are one place.
  bool linked(const Island& a, const Island& b) const;
  /// How many entries `e`'s place holds (1 when never linked).
  std::size_t placeSize(EntryId e) const;

  /// For persistence: every entry's parent, `entries` of them (an entry
  /// never linked is its own parent; parents are never larger ids).
  std::vector<EntryId> parents(std::size_t entries) const;
  /// Restores parents() output; throws std::invalid_argument naming the
  /// first entry whose parent is larger than itself.
  void restore(std::vector<EntryId> parents);
  void clear() {
    parent_.clear();
    size_.clear();
  }

 private:
  // Grown on demand to the largest linked id; mutable for path halving.
  mutable std::vector<EntryId> parent_;
  // Entries of each place, read at its root (parent_'s length).
  std::vector<std::uint32_t> size_;
};

}  // namespace bowg
