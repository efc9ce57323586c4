// A walk over the union of the ids of two id-sorted sparse vectors (a BoW
// vector and a group vector): the inverse index has one posting per id of
// that union, and a query one term. Private to the database stage.
#pragma once

#include <cstddef>
#include <vector>

#include "bowg/core/types.h"

namespace bowg {

/// f(id, a_item, b_item) for each id of the union in ascending order, the
/// item nullptr where that vector lacks the id.
template <typename A, typename B, typename F>
void forEachId(const std::vector<A>& a, const std::vector<B>& b, F f) {
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    const bool in_a = i < a.size() && (j == b.size() || a[i].first <= b[j].first);
    const bool in_b = j < b.size() && (i == a.size() || b[j].first <= a[i].first);
    const WordId id = in_a ? a[i].first : b[j].first;
    f(id, in_a ? &a[i] : nullptr, in_b ? &b[j] : nullptr);
    if (in_a) ++i;
    if (in_b) ++j;
  }
}

}  // namespace bowg
