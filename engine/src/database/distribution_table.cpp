#include "bowg/database/distribution_table.h"

#include "bowg/core/heap_bytes.h"

namespace bowg {

void DistributionTable::reset(int bins) {
  bins_ = bins;
  values_.clear();
}

void DistributionTable::append(const std::vector<double>& vector) {
  values_.insert(values_.end(), vector.begin(), vector.end());
}

void DistributionTable::copy(EntryId id, std::vector<double>* out) const {
  const std::size_t m = static_cast<std::size_t>(bins_);
  const auto first = values_.begin() + static_cast<std::ptrdiff_t>(id * m);
  out->assign(first, first + static_cast<std::ptrdiff_t>(m));
}

std::size_t DistributionTable::heapBytes() const { return vectorHeapBytes(values_); }

}  // namespace bowg
