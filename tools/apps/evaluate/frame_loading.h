// The frames bowg_evaluate runs the detector over: features extracted once
// from an image folder or a bag (images converted as the nodelet converts
// them), with intrinsics and optional odometers.
#pragma once

#include <cstddef>
#include <vector>

#include "bowg/detection/odometry_input.h"
#include "bowg/features/feature_extractor.h"
#include "bowg_evaluation/detector_run.h"
#include "evaluate_args.h"

namespace bowg {
namespace evaluate_app {

/// Extracts the features of every image once (shared by every run).
std::vector<eval::FrameInput> loadFrames(const Args& a, const FeatureExtractor& extractor);

/// Sets every frame's odometer from --odometry (one per frame at least).
void attachOdometry(const std::string& path, std::vector<eval::FrameInput>* frames);
/// Sets every frame's odometry position from `path` (odometry_file.h);
/// throws bowg::FormatError naming the file when it lists fewer frames.
void attachOdometryPositions(const std::string& path, std::vector<eval::FrameInput>* frames);
/// The odometry the frames come with, as the detector reads it
/// (odometry_input.h): positions when any frame has a position and an
/// odometer, else an odometer when any has one, else none.
OdometryInput odometryInputOf(const std::vector<eval::FrameInput>& frames);
/// How many frames carry a heading (the heading gate applies to them only).
std::size_t framesWithHeading(const std::vector<eval::FrameInput>& frames);

}  // namespace evaluate_app
}  // namespace bowg
