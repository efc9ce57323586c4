#include "bowg_pipe_sim/wall_marks.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "bowg_pipe_sim/random.h"

namespace bowg {
namespace pipe_sim {
namespace {

constexpr double kTwoPi = 6.283185307179586;

/// A mark at a random place of `edge` (of `length` m): position, type,
/// size, then its shape seed, in this order (the order of the draws is part
/// of what a seed means).
WallMark drawMark(Random* rng, int edge, double length) {
  WallMark mark;
  mark.edge = edge;
  mark.s = rng->uniform(0.0, length);
  mark.theta = rng->uniform(0.0, kTwoPi);
  mark.type = static_cast<WallMark::Type>(rng->index(3));
  mark.size_m = mark.type == WallMark::Type::kCrack   ? rng->uniform(0.06, 0.18)
                : mark.type == WallMark::Type::kStain ? rng->uniform(0.025, 0.06)
                                                      : rng->uniform(0.012, 0.03);
  mark.shape_seed = rng->next();
  return mark;
}

/// An edge chosen in proportion to its length, so that new marks are as
/// dense everywhere as the old ones.
int randomEdge(Random* rng, const PipeNetwork& network) {
  std::vector<double> cumulative;
  double total = 0;
  for (std::size_t e = 0; e < network.edges.size(); ++e) {
    total += network.edgeLength(static_cast<int>(e));
    cumulative.push_back(total);
  }
  const double u = rng->uniform(0.0, total);
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), u);
  return static_cast<int>(std::min<std::ptrdiff_t>(
      it - cumulative.begin(), static_cast<std::ptrdiff_t>(cumulative.size()) - 1));
}

}  // namespace

std::vector<WallMark> placeMarks(const PipeNetwork& network, double marks_per_metre,
                                 std::uint64_t seed) {
  std::vector<WallMark> marks;
  for (std::size_t e = 0; e < network.edges.size(); ++e) {
    const double length = network.edgeLength(static_cast<int>(e));
    Random rng(hashCombine(seed, 0x6d61726bULL, e));
    const int count = static_cast<int>(std::floor(marks_per_metre * length + rng.uniform()));
    for (int i = 0; i < count; ++i) marks.push_back(drawMark(&rng, static_cast<int>(e), length));
  }
  return marks;
}

std::vector<WallMark> changeMarks(const std::vector<WallMark>& marks, const PipeNetwork& network,
                                  double fraction, std::uint64_t seed) {
  if (!(fraction >= 0 && fraction <= 1)) {
    throw std::invalid_argument("changeMarks: the fraction must be in [0, 1]");
  }
  const std::size_t changed = static_cast<std::size_t>(std::lround(fraction * marks.size()));
  Random rng(hashCombine(seed, 0x6368616eULL));
  // The first `changed` of a partial Fisher-Yates shuffle are removed.
  std::vector<std::size_t> order(marks.size());
  std::iota(order.begin(), order.end(), 0);
  for (std::size_t i = 0; i < changed; ++i) {
    std::swap(order[i], order[i + rng.index(static_cast<int>(marks.size() - i))]);
  }
  std::vector<bool> removed(marks.size(), false);
  for (std::size_t i = 0; i < changed; ++i) removed[order[i]] = true;
  std::vector<WallMark> result;
  for (std::size_t i = 0; i < marks.size(); ++i) {
    if (!removed[i]) result.push_back(marks[i]);
  }
  for (std::size_t i = 0; i < changed; ++i) {
    const int edge = randomEdge(&rng, network);
    result.push_back(drawMark(&rng, edge, network.edgeLength(edge)));
  }
  std::stable_sort(result.begin(), result.end(),
                   [](const WallMark& a, const WallMark& b) { return a.edge < b.edge; });
  return result;
}

}  // namespace pipe_sim
}  // namespace bowg
