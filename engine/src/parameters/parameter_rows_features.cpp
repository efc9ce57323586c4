// Parameter rows of the feature stage (paper Sec. III-A).
#include <string>
#include <vector>

#include "parameters/parameter_rows.h"

namespace bowg {
namespace parameter_rows {

// One statement per row, in the README table's order: long because the table
// is, and kept in one piece so that the order is visible.
void addFeatureRows(std::vector<Row>* rows) {
  const std::string fea = "features";
  // --- Features (Sec. III-A).
  rows->push_back(enumRow(
      "feature_detector", fea, "detector", {"gftt", "orb"},
      [](PipelineOptions* o, const std::string& v) {
        o->features.detector =
            v == "gftt" ? FeatureOptions::Detector::kGftt : FeatureOptions::Detector::kOrb;
      },
      [](const PipelineOptions& o) {
        return std::string(o.features.detector == FeatureOptions::Detector::kGftt ? "gftt" : "orb");
      },
      "Keypoint detector: GFTT corners (pipes) or multi-scale ORB/FAST (generic scenes)"));
  rows->push_back(enumRow(
      "descriptor", fea, "descriptor", {"orb", "brief"},
      [](PipelineOptions* o, const std::string& v) {
        o->features.descriptor = v == "orb" ? FeatureOptions::DescriptorType::kOrb
                                            : FeatureOptions::DescriptorType::kBrief;
      },
      [](const PipelineOptions& o) {
        return std::string(o.features.descriptor == FeatureOptions::DescriptorType::kOrb ? "orb"
                                                                                         : "brief");
      },
      "256-bit descriptor: ORB rBRIEF or plain BRIEF (VINS brief_k10L6.bin, needs "
      "brief_pattern_path)"));
  rows->push_back(intRow("gftt_max_corners", fea, "gftt_max_corners", 1, 100000, false,
                         BOWG_FIELD(int, features.gftt_max_corners),
                         "GFTT: most corners per image"));
  rows->push_back(doubleRow("gftt_quality_level", fea, "gftt_quality_level", 1e-6, 1.0, false,
                            BOWG_FIELD(double, features.gftt_quality_level),
                            "GFTT: minimum corner quality relative to the best corner"));
  rows->push_back(doubleRow("gftt_min_distance", fea, "gftt_min_distance", 0.0, 1000.0, false,
                            BOWG_FIELD(double, features.gftt_min_distance),
                            "GFTT: minimum distance between corners (px)"));
  rows->push_back(intRow("gftt_block_size", fea, "gftt_block_size", 1, 99, false,
                         BOWG_FIELD(int, features.gftt_block_size),
                         "GFTT: derivative covariation block size (px)"));
  rows->push_back(boolRow("gftt_use_harris", fea, "gftt_use_harris", false,
                          BOWG_FIELD(bool, features.gftt_use_harris),
                          "GFTT: Harris response instead of Shi-Tomasi"));
  rows->push_back(doubleRow("gftt_keypoint_size", fea, "gftt_keypoint_size", 1.0, 1000.0, false,
                            BOWG_FIELD(double, features.gftt_keypoint_size),
                            "Size given to GFTT corners (px): word-group radius and descriptor "
                            "patch"));
  rows->push_back(intRow("gftt_levels", fea, "gftt_levels", 1, 32, false,
                         BOWG_FIELD(int, features.gftt_levels),
                         "GFTT: pyramid levels the corners are found on (scale "
                         "orb_scale_factor; 1 = the image alone; ORB descriptor only)"));
  rows->push_back(intRow("max_image_pixels", fea, "max_image_pixels", 1, 1 << 30, false,
                         BOWG_FIELD(int, features.max_image_pixels),
                         "Largest image accepted (width x height); larger frames are dropped "
                         "and counted (nodelet) or skipped with a warning (tools)"));
  rows->push_back(intRow("orb_max_features", fea, "orb_max_features", 1, 100000, false,
                         BOWG_FIELD(int, features.orb_max_features),
                         "ORB: most features per image"));
  rows->push_back(doubleRow("orb_scale_factor", fea, "orb_scale_factor", 1.001, 4.0, false,
                            BOWG_FIELD(double, features.orb_scale_factor),
                            "ORB: pyramid scale factor"));
  rows->push_back(intRow("orb_levels", fea, "orb_levels", 1, 32, false,
                         BOWG_FIELD(int, features.orb_levels), "ORB: pyramid levels"));
  rows->push_back(intRow("orb_fast_threshold", fea, "orb_fast_threshold", 1, 255, false,
                         BOWG_FIELD(int, features.orb_fast_threshold), "ORB: FAST threshold"));
  rows->push_back(boolRow("compute_orientation", fea, "compute_orientation", false,
                          BOWG_FIELD(bool, features.compute_orientation),
                          "Steer descriptors by the intensity-centroid orientation (pipe robots "
                          "roll)"));
  rows->push_back(stringRow("brief_pattern_path", fea, "brief_pattern_path",
                            BOWG_FIELD(std::string, features.brief_pattern_path),
                            "BRIEF test-pattern file (VINS brief_pattern.yml layout)"));
  rows->push_back(stringRow("mask_path", fea, "mask_path",
                            BOWG_FIELD(std::string, features.mask_path),
                            "Optional 8-bit mask image (non-zero = usable), e.g. to blank text "
                            "overlays"));
}

}  // namespace parameter_rows
}  // namespace bowg
