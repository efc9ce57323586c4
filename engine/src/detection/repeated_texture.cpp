#include "bowg/detection/repeated_texture.h"

#include <algorithm>
#include <cmath>

namespace bowg {

std::vector<EntryId> repeatedTextureEntries(const Database& database, double query_odometer,
                                            const VerifiedChainOptions& chain,
                                            const IslandOptions& islands) {
  std::vector<EntryId> ids;
  const int n = chain.repeated_texture_keyframes;
  const std::size_t size = database.size();
  if (std::isfinite(query_odometer)) {
    const std::vector<double>& odometers = database.odometers();
    const double near = chain.repeated_texture_min_m;
    const double far = std::max(near, islands.recent_exclusion_m);
    for (int j = 0; j < n; ++j) {
      const double back = n == 1 ? near : near + (far - near) * j / (n - 1);
      // The newest entry driven at least `back` before the query.
      const std::size_t k = static_cast<std::size_t>(
          std::upper_bound(odometers.begin(), odometers.end(), query_odometer - back) -
          odometers.begin());
      if (k == 0) break;
      const EntryId id = static_cast<EntryId>(k - 1);
      if (!std::isfinite(database.entries()[id].odometer)) continue;
      if (ids.empty() || ids.back() != id) ids.push_back(id);
    }
    return ids;
  }
  const std::size_t window = static_cast<std::size_t>(islands.recent_exclusion);
  for (int j = 1; j <= n; ++j) {
    const std::size_t back = std::max<std::size_t>(
        1, window * static_cast<std::size_t>(j) / static_cast<std::size_t>(n));
    if (back > size) break;
    const EntryId id = static_cast<EntryId>(size - back);
    if (ids.empty() || ids.back() != id) ids.push_back(id);
  }
  return ids;
}

void markRepeated(const VerificationView& query, const VerificationView& entry,
                  const GeometricVerificationOptions& options, std::vector<char>* repeated) {
  for (const auto& p : findCorrespondences(query, entry, options)) (*repeated)[p.first] = 1;
}

int uniqueInliers(const std::vector<Correspondence>& inliers, const std::vector<char>& repeated) {
  int unique = 0;
  for (const Correspondence& c : inliers) {
    if (c.query_index >= repeated.size() || !repeated[c.query_index]) ++unique;
  }
  return unique;
}

}  // namespace bowg
