// Intensity-centroid orientation of a keypoint (Rosin 1999, as used by ORB:
// Rublee et al., ICCV 2011, Sec. 3.2). The paper's pipe setting (Sec. III-A)
// detects GFTT corners, which have no orientation; robots roll inside pipes,
// so the descriptors are steered by this angle to survive the roll.
#pragma once

#include <opencv2/core.hpp>

namespace bowg {

/// Orientation in degrees [0, 360) of the intensity centroid of the disc of
/// radius `radius` (pixels u, v with u^2 + v^2 <= radius * (radius + 1))
/// around the pixel cvRound(pt): atan2(m01, m10) with m10 = sum u I(u, v),
/// m01 = sum v I(u, v), image axes (x right, y down), so that a clockwise
/// on-screen rotation of the image by 90 degrees adds 90 degrees.
/// The disc is symmetric under 90-degree rotations and mirroring, so such
/// rotations change the angle by exactly 90 degrees. A flat patch gives 0.
/// `image` is 8-bit single-channel; the disc must lie inside the image
/// (throws std::invalid_argument otherwise). `radius` >= 1.
float intensityCentroidAngle(const cv::Mat& image, cv::Point2f pt, int radius);

}  // namespace bowg
