// Hand-made islands for the temporal-verification tests.
#pragma once

#include "bowg/detection/islands.h"

namespace bowg {
namespace testing {

/// The island of entries first..last (best entry: the first).
inline Island island(EntryId first, EntryId last) {
  Island i;
  i.first = first;
  i.last = last;
  i.best_entry = first;
  i.size = static_cast<int>(last - first + 1);
  return i;
}

}  // namespace testing
}  // namespace bowg
