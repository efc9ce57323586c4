// Word groups (paper Sec. III-A "Word Group Definition"), the online word-group
// table, refined weights (eq. 1) and the word-group score (eq. 3).
#include "bowg/scoring/word_groups.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "bowg/core/heap_bytes.h"
#include "bowg/core/id_index_sort.h"
#include "scoring/neighbour_count.h"

namespace bowg {
namespace {

// WordGroupTable::version(): a fresh value per table state, process-wide.
std::uint64_t nextTableVersion() {
  static std::atomic<std::uint64_t> last{0};
  return ++last;
}

// The grid has at most about 3 * (kCellsPerPoint * n + kMinCells) cells.
const double kCellsPerPoint = 4.0;
const double kMinCells = 16.0;

[[noreturn]] void throwBadWeight(const char* function, const GroupEntry& e) {
  throw std::invalid_argument(std::string(function) + ": weight of group " +
                              std::to_string(e.first) + " must be finite and > 0 (got " +
                              std::to_string(e.second) + ")");
}

// Checked for every group of every scored entry: the test inline, the
// message out of line.
inline void checkWeight(const char* function, const GroupEntry& e) {
  if (!std::isfinite(e.second) || !(e.second > 0.0)) throwBadWeight(function, e);
}

// The merge of two id-sorted sparse vectors: shared(ia, ib) for each group
// id that a[ia] and b[ib] share, in id order (eq. 3's dot product has only
// shared groups).
template <typename Shared>
void forEachSharedGroup(const GroupVector& a, const GroupVector& b, Shared shared) {
  std::size_t ia = 0, ib = 0;
  while (ia < a.size() && ib < b.size()) {
    if (a[ia].first < b[ib].first) {
      ++ia;
    } else if (b[ib].first < a[ia].first) {
      ++ib;
    } else {
      shared(ia, ib);
      ++ia;
      ++ib;
    }
  }
}

// Relative error bound of a squared distance computed in float from float
// coordinates (two subtractions, two squares and a sum, each rounded by at
// most 2^-24: < 4e-7), with room to spare: a float distance farther than
// this from the radius decides as the double one does.
const double kFloatBand = 2e-6;
// The float test applies to coordinates and radii in these ranges (no
// overflow, no underflow that the band does not cover).
const double kFloatMaxCoordinate = 1e6;
const double kFloatMinRadius = 1e-3;

// Uniform grid over the keypoints in compressed-row form: the coordinates of
// the points of cell c are xs_, ys_[start_[c] .. start_[c+1]), so that a
// neighbour scan reads contiguous memory. The coordinates are the
// keypoints' floats: the scan runs four to a vector instruction.
class PointGrid {
 public:
  /// `cell` must be > 0; the points lie in [min_x, min_x + nx*cell) x ...
  PointGrid(const std::vector<Keypoint>& kps, double min_x, double min_y, double cell,
            std::int64_t nx, std::int64_t ny)
      : min_x_(min_x), min_y_(min_y), cell_(cell), nx_(nx), ny_(ny) {
    const std::size_t n = kps.size();
    std::vector<std::int64_t> cell_of(n);
    start_.assign(static_cast<std::size_t>(nx * ny + 1), 0);
    bool small = true;
    for (std::size_t i = 0; i < n; ++i) {
      cell_of[i] = index(coord(kps[i].x, min_x_, nx_), coord(kps[i].y, min_y_, ny_));
      ++start_[cell_of[i] + 1];
      small = small && std::fabs(kps[i].x) <= kFloatMaxCoordinate &&
              std::fabs(kps[i].y) <= kFloatMaxCoordinate;
    }
    float_coordinates_ = small;
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    xs_.resize(n);
    ys_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t slot = fill[cell_of[i]]++;
      xs_[slot] = kps[i].x;
      ys_[slot] = kps[i].y;
    }
  }

  /// Number of points other than the point itself (at x, y, one of the
  /// grid's points) at distance < radius. Scans the cells that the disc's
  /// bounding box touches: the 3x3 block around the point when radius ==
  /// cell, often fewer for smaller radii.
  int countNeighbours(float x, float y, double radius) const {
    const double r2 = radius * radius;
    // Nothing is strictly closer than 0 (radius^2 can underflow to 0).
    if (!(r2 > 0.0)) return 0;
    // The margin covers rounding in x -/+ reach (see also the cell margin).
    const double reach = radius * (1.0 + 1e-9);
    const std::int64_t x0 = coord(x - reach, min_x_, nx_), x1 = coord(x + reach, min_x_, nx_);
    const std::int64_t y0 = coord(y - reach, min_y_, ny_), y1 = coord(y + reach, min_y_, ny_);
    const bool in_float =
        float_coordinates_ && radius >= kFloatMinRadius && radius <= kFloatMaxCoordinate;
    // The rows' counts (exact as doubles below 2^53).
    double n = 0;
    for (std::int64_t gy = y0; gy <= y1; ++gy) {
      // Cells x0..x1 of one row are contiguous in the compressed rows.
      const std::uint32_t begin = start_[index(x0, gy)];
      const std::uint32_t end = start_[index(x1, gy) + 1];
      n += in_float ? countInFloat(x, y, r2, begin, end) : countInDouble(x, y, r2, begin, end);
    }
    // The point itself was counted (distance 0 < r2, and its cell lies in
    // the scanned block); a coincident *other* point is a neighbour.
    return static_cast<int>(n - 1);
  }

 private:
  // Points s in [begin, end) strictly closer than sqrt(r2), in double:
  // the definition.
  double countInDouble(float x, float y, double r2, std::uint32_t begin, std::uint32_t end) const {
    const float* xs = xs_.data();
    const float* ys = ys_.data();
    // A double count, without a branch, so that the loop vectorises:
    // x86-64's baseline vector unit compares doubles into 64-bit masks it
    // can add as doubles but not as 32-bit integers.
    double n = 0;
    for (std::size_t s = begin; s < end; ++s) {
      const double dx = static_cast<double>(xs[s]) - x;
      const double dy = static_cast<double>(ys[s]) - y;
      n += dx * dx + dy * dy < r2 ? 1.0 : 0.0;
    }
    return n;
  }

  // The same count by the float distances: those below r2 (1 - band) are
  // closer, those above r2 (1 + band) are not; when one lies between, the
  // run is counted again in double.
  double countInFloat(float x, float y, double r2, std::uint32_t begin, std::uint32_t end) const {
    const float* xs = xs_.data();
    const float* ys = ys_.data();
    const float below = static_cast<float>(r2 * (1.0 - kFloatBand));
    const float above = static_cast<float>(r2 * (1.0 + kFloatBand));
    const neighbour_count::Counts c = count_within_(xs, ys, begin, end, x, y, below, above);
    return c.maybe == c.sure ? static_cast<double>(c.sure) : countInDouble(x, y, r2, begin, end);
  }

  std::int64_t coord(double v, double origin, std::int64_t count) const {
    // Clamped to the grid in double: a far point's cell number may not fit
    // an integer (converting it would be undefined).
    const double c = std::floor((v - origin) / cell_);
    if (!(c > 0.0)) return 0;
    return c >= static_cast<double>(count - 1) ? count - 1 : static_cast<std::int64_t>(c);
  }
  std::int64_t index(std::int64_t gx, std::int64_t gy) const { return gy * nx_ + gx; }

  double min_x_, min_y_, cell_;
  std::int64_t nx_, ny_;
  std::vector<std::uint32_t> start_;
  std::vector<float> xs_, ys_;
  bool float_coordinates_ = true;
  neighbour_count::CountWithin count_within_ = neighbour_count::bestCountWithin();
};

// The median of the positive radii radius_scale * size (there is one:
// the largest radius is > 0).
double medianPositiveRadius(const std::vector<Keypoint>& keypoints, double radius_scale) {
  std::vector<double> radii;
  radii.reserve(keypoints.size());
  for (const Keypoint& k : keypoints) {
    const double r = radius_scale * k.size;
    if (r > 0.0) radii.push_back(r);
  }
  std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
  return radii[radii.size() / 2];
}

}  // namespace

GroupVector buildWordGroups(const std::vector<Keypoint>& keypoints,
                            const std::vector<WordId>& words, const WordGroupOptions& options) {
  if (keypoints.size() != words.size()) {
    throw std::invalid_argument("buildWordGroups: " + std::to_string(keypoints.size()) +
                                " keypoints but " + std::to_string(words.size()) + " words");
  }
  options.validate();
  if (keypoints.size() < 2) return {};

  // The grid cell is the largest radius, so every neighbour of a point lies in
  // the 3x3 block of cells around it (no all-pairs search).
  double max_radius = 0.0;
  double min_x = std::numeric_limits<double>::infinity(), min_y = min_x;
  double max_x = -min_x, max_y = -min_x;
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    const Keypoint& k = keypoints[i];
    if (!std::isfinite(k.x) || !std::isfinite(k.y)) {
      throw std::invalid_argument("buildWordGroups: keypoint " + std::to_string(i) +
                                  " has a non-finite position");
    }
    if (!std::isfinite(k.size) || !(k.size >= 0.f)) {
      throw std::invalid_argument("buildWordGroups: keypoint " + std::to_string(i) +
                                  " has an invalid size (must be finite and >= 0, got " +
                                  std::to_string(k.size) + ")");
    }
    max_radius = std::max(max_radius, options.radius_scale * k.size);
    min_x = std::min(min_x, static_cast<double>(k.x));
    min_y = std::min(min_y, static_cast<double>(k.y));
    max_x = std::max(max_x, static_cast<double>(k.x));
    max_y = std::max(max_y, static_cast<double>(k.y));
  }
  if (!std::isfinite(max_radius)) {
    throw std::invalid_argument("buildWordGroups: radius_scale * size overflows");
  }
  if (!(max_radius > 0.0)) return {};  // all sizes 0: nothing is closer than 0

  // Any cell size is correct (a point scans the cells its disc's bounding
  // box touches). The median radius keeps the scan of most points to about
  // 3x3 cells: multi-scale features have radii 1-8x apart, and cells of the
  // largest radius made every small feature compare itself with a third of
  // the image. The budget bounds the number of cells by O(n) when the radii
  // are small against the spacing of the points.
  const double ex = max_x - min_x, ey = max_y - min_y;
  const double budget = kCellsPerPoint * static_cast<double>(keypoints.size()) + kMinCells;
  const double cell = std::max({medianPositiveRadius(keypoints, options.radius_scale), ex / budget,
                                ey / budget, std::sqrt(ex * ey / budget)});
  const std::int64_t nx = static_cast<std::int64_t>(std::floor(ex / cell)) + 1;
  const std::int64_t ny = static_cast<std::int64_t>(std::floor(ey / cell)) + 1;
  const PointGrid grid(keypoints, min_x, min_y, cell, nx, ny);

  // (word, feature) of each feature with neighbours, its count apart.
  std::vector<IdIndexPair> found;
  std::vector<int> neighbours(keypoints.size(), 0);
  found.reserve(keypoints.size());
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    const double radius = options.radius_scale * keypoints[i].size;
    if (!(radius > 0.0)) continue;
    const int n = grid.countNeighbours(keypoints[i].x, keypoints[i].y, radius);
    if (n > 0) {
      neighbours[i] = n;  // weight = words in the group - 1
      found.emplace_back(words[i], static_cast<std::uint32_t>(i));
    }
  }
  // Several features with the same word add into the one group i (whole
  // counts: the sum does not depend on the order).
  sortIdIndexPairs(&found);
  GroupVector groups;
  groups.reserve(found.size());
  for (const IdIndexPair& e : found) {
    const double n = static_cast<double>(neighbours[e.second]);
    if (!groups.empty() && groups.back().first == e.first) {
      groups.back().second += n;
    } else {
      groups.emplace_back(e.first, n);
    }
  }
  return groups;
}

WordGroupTable::WordGroupTable() : version_(nextTableVersion()) {}

void WordGroupTable::add(const GroupVector& raw) {
  for (const GroupEntry& e : raw) checkWeight("WordGroupTable::add", e);
  version_ = nextTableVersion();
  for (const GroupEntry& e : raw) {
    if (e.first >= cumulative_.size())
      cumulative_.resize(static_cast<std::size_t>(e.first) + 1, 0.0);
    if (cumulative_[e.first] == 0.0) ++seen_;
    cumulative_[e.first] += e.second;
    total_ += e.second;
  }
}

void WordGroupTable::clear() {
  version_ = nextTableVersion();
  cumulative_.clear();
  seen_ = 0;
  total_ = 0.0;
}

double WordGroupTable::cumulative(WordId group) const {
  return group < cumulative_.size() ? cumulative_[group] : 0.0;
}

std::size_t WordGroupTable::heapBytes() const { return vectorHeapBytes(cumulative_); }

double WordGroupTable::idf(WordId group) const {
  const double c = cumulative(group);
  if (c <= 0.0) return 0.0;
  // IDF part of eq. 1: log(sum_t sum_i w / sum_t w^(i)); >= 0 since c <= total.
  return std::log(total_ / c);
}

GroupVector groupTermFrequencies(const GroupVector& raw) {
  double sum = 0.0;
  for (const GroupEntry& e : raw) {
    checkWeight("groupTermFrequencies", e);
    sum += e.second;
  }
  GroupVector tf;
  tf.reserve(raw.size());
  // TF part of eq. 1: w^(i) / sum_i w^(i).
  for (const GroupEntry& e : raw) tf.emplace_back(e.first, e.second / sum);
  return tf;
}

GroupVector refineGroupWeights(const GroupVector& raw, const WordGroupTable& table) {
  return refineGroupWeights(raw, table, nullptr);
}

GroupVector refineGroupWeights(const GroupVector& raw, const WordGroupTable& table,
                               std::vector<double>* idf) {
  GroupVector refined;
  refined.reserve(raw.size());
  if (idf != nullptr) {
    idf->clear();
    idf->reserve(raw.size());
  }
  for (const GroupEntry& e : groupTermFrequencies(raw)) {
    // Eq. 1. A group present in every database weight (idf 0) or unknown to
    // the table carries no information: dropped (GroupVector holds no zeros).
    const double group_idf = table.idf(e.first);
    const double w = e.second * group_idf;
    if (w > 0.0) {
      refined.emplace_back(e.first, w);
      if (idf != nullptr) idf->push_back(group_idf);
    }
  }
  return refined;
}

double groupScoreFromDot(double dot) {
  if (std::isnan(dot)) throw std::invalid_argument("groupScoreFromDot: dot product is NaN");
  // Eq. 3. The refined weights are not unit vectors (TF sums to 1, IDF can
  // exceed 1), so the dot product can exceed 1: the score saturates at 1.
  if (dot > 1.0) return 1.0;
  return 1.0 - std::sqrt(1.0 - dot);
}

double groupScore(const GroupVector& a_refined, const GroupVector& b_refined) {
  double dot = 0.0;
  forEachSharedGroup(a_refined, b_refined, [&](std::size_t ia, std::size_t ib) {
    dot += a_refined[ia].second * b_refined[ib].second;
  });
  return groupScoreFromDot(dot);
}

double groupScoreWithIdf(const GroupVector& a_refined, const std::vector<double>& a_idf,
                         const GroupVector& b_raw) {
  if (a_idf.size() != a_refined.size()) {
    throw std::invalid_argument("groupScoreWithIdf: " + std::to_string(a_refined.size()) +
                                " groups but " + std::to_string(a_idf.size()) + " IDFs");
  }
  // b's TF denominator over all its groups, as groupTermFrequencies sums it.
  double sum = 0.0;
  for (const GroupEntry& e : b_raw) {
    checkWeight("groupScoreWithIdf", e);
    sum += e.second;
  }
  double dot = 0.0;
  forEachSharedGroup(a_refined, b_raw, [&](std::size_t ia, std::size_t ib) {
    // b's refined weight (eq. 1) with a's IDF of the group; a shared group
    // has IDF > 0 (a kept it), so b keeps it too.
    dot += a_refined[ia].second * ((b_raw[ib].second / sum) * a_idf[ia]);
  });
  return groupScoreFromDot(dot);
}

}  // namespace bowg
