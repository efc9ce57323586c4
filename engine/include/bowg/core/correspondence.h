// A point correspondence between two keyframes: the unit that geometric
// verification produces and the metric translation, the pose graph's loop
// poses and the published loop messages read.
#pragma once

#include <cstdint>

namespace bowg {

/// One point correspondence that survived geometric verification.
struct Correspondence {
  std::uint32_t query_index = 0;  ///< feature index in the query keyframe
  std::uint32_t match_index = 0;  ///< feature index in the matched keyframe
  float query_x = 0, query_y = 0, match_x = 0, match_y = 0;
};

}  // namespace bowg
