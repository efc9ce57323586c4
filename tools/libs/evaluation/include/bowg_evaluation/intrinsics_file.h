// Pinhole intrinsics of an image folder (`bowg_evaluate --intrinsics FILE`;
// a bag has its camera_info): with them the detector gives each loop its
// relative pose and, with odometry, its metric translation.
//
// Format: CSV, the header `fx,fy,cx,cy` (pixels) and one row; the generator
// writes it beside its frames (intrinsics.csv).
#pragma once

#include <string>

#include "bowg/core/types.h"

namespace bowg {
namespace eval {

/// Throws bowg::FormatError ("<source>:<line>: <why>") on another header, a
/// missing, extra or non-numeric cell, or a focal length that is not > 0.
CameraIntrinsics parseIntrinsics(const std::string& text, const std::string& source);
/// Same from a file; bowg::IoError when it cannot be read.
CameraIntrinsics readIntrinsics(const std::string& path);
/// The file's text for `k` (round trip with parseIntrinsics).
std::string intrinsicsToCsv(const CameraIntrinsics& k);

}  // namespace eval
}  // namespace bowg
