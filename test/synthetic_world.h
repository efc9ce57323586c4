// Synthetic camera sequences for the rostests: a long strip of random
// texture (distinct everywhere, so every place is unique) that a virtual
// camera slides along. Revisiting a place = viewing the same strip position
// again, slightly shifted and re-lit. Deterministic for a given seed.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace bowg_ros {
namespace test {

/// A width x height 8-bit strip of random ellipses, rectangles and lines.
cv::Mat makeWorld(int width, int height, std::uint64_t seed);

/// The camera view (view_width wide, full strip height) at column x, with
/// `brightness` added (revisits under other light).
cv::Mat viewAt(const cv::Mat& world, int x, int view_width, int brightness = 0);

/// Strip x position of each frame of a sequence that goes forward
/// `forward` frames by `step` px from 0, then (if revisit > 0) comes back to
/// the start and goes forward again `revisit` frames, `offset` px beside the
/// first pass. Frame forward + j views the place of frame j.
std::vector<int> trajectory(int forward, int revisit, int step, int offset);

}  // namespace test
}  // namespace bowg_ros
