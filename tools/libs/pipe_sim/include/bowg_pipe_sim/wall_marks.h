// The unique wall marks (stains, cracks, deposits) of a pipe network, where
// they sit and how they change between two inspections of the same network:
// months later some cracks are new and some deposits were cleaned away, while
// everything else on the wall is as it was. WallTexture draws what these
// functions place (wall_texture.h).
#pragma once

#include <cstdint>
#include <vector>

#include "bowg_pipe_sim/pipe_network.h"

namespace bowg {
namespace pipe_sim {

/// One unique mark.
struct WallMark {
  enum class Type { kStain, kCrack, kDeposit };
  Type type = Type::kStain;
  int edge = 0;
  double s = 0, theta = 0;  ///< centre (m, rad)
  double size_m = 0;        ///< rough extent
  /// Seeds the mark's shape and shade: a mark kept from one inspection to
  /// the next looks the same.
  std::uint64_t shape_seed = 0;
};

/// The marks of `network`, `marks_per_metre` on average: per edge,
/// floor(marks_per_metre * length + u) of them, drawn by a generator seeded
/// with (seed, edge) so that an edge's marks do not depend on the other
/// edges. Sorted by edge, in drawing order within an edge.
std::vector<WallMark> placeMarks(const PipeNetwork& network, double marks_per_metre,
                                 std::uint64_t seed);

/// The marks of a later inspection: round(fraction * marks.size()) of
/// `marks`, chosen at random, removed, and as many new marks added at random
/// places (the edge chosen in proportion to its length), drawn from `seed`.
/// The count stays the same. Sorted by edge; within an edge the kept marks
/// in their order, then the new ones (drawn over the old). fraction in
/// [0, 1], else std::invalid_argument.
std::vector<WallMark> changeMarks(const std::vector<WallMark>& marks, const PipeNetwork& network,
                                  double fraction, std::uint64_t seed);

}  // namespace pipe_sim
}  // namespace bowg
