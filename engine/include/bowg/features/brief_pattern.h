// The BRIEF test pattern file of VINS-Mono / VINS-Fusion (brief_pattern.yml,
// the pattern their brief_k10L6.bin vocabulary was trained with): OpenCV
// FileStorage YAML (read with the project's own YAML-subset reader) with four
// integer sequences x1, y1, x2, y2 of 256 entries,
// pair i comparing pixel (x1[i], y1[i]) with (x2[i], y2[i]) relative to the
// keypoint.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace bowg {

/// Number of tests (bits) in a pattern file: one per descriptor bit.
constexpr int kBriefPatternPairs = 256;
/// Largest accepted |coordinate| in a pattern file (px). VINS' pattern stays
/// within 24 (a 48 px patch); anything far larger is a corrupt file.
constexpr int kBriefPatternMaxOffset = 128;

/// Loads a pattern file; element i is (x1, y1, x2, y2) of test i.
/// Throws IoError (missing / unreadable) or FormatError (not YAML, missing
/// or non-integer sequence, wrong length, offset too large), naming the path.
std::vector<cv::Vec4i> loadBriefPattern(const std::string& path);

}  // namespace bowg
