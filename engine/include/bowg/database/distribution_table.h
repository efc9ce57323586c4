// The database's distribution table (paper Sec. III-C): every entry's
// distribution vector for the current m, in one contiguous array. A query
// reads it for thousands of candidates; separate allocations per entry made
// that stage cache-miss bound (70 % of the query time at 20,000 entries).
// The vectors are rebuilt from the stored keypoint positions when m changes.
#pragma once

#include <cstddef>
#include <vector>

#include "bowg/core/types.h"

namespace bowg {

class DistributionTable {
 public:
  explicit DistributionTable(int bins) : bins_(bins) {}
  int bins() const { return bins_; }
  /// Empties the table for vectors of `bins` bins (>= 1, checked by the caller).
  void reset(int bins);
  /// Appends the next entry's vector (bins() values).
  void append(const std::vector<double>& vector);
  /// Entry `id`'s vector into `out` (reused: no allocation once sized).
  void copy(EntryId id, std::vector<double>* out) const;
  /// Entry `id`'s bins() values, valid until the next append or reset.
  const double* values(EntryId id) const {
    return values_.data() + static_cast<std::size_t>(id) * static_cast<std::size_t>(bins_);
  }
  void reserve(std::size_t entries) { values_.reserve(entries * static_cast<std::size_t>(bins_)); }
  std::size_t heapBytes() const;

 private:
  int bins_;
  /// Entry i's vector at [i * m, i * m + m).
  std::vector<double> values_;
};

}  // namespace bowg
