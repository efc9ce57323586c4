// The pipe wall's albedo as a function of the wall point: (edge, s, theta),
// s = metres along the edge from edge.from, theta = angle about the edge axis
// (0 = world up, increasing towards edge_direction x up). Built to ALIAS, as
// real pipes do (method notes, "What defeats the classic pipeline in pipes"):
//  - one material grain tile, identical in every pipe section;
//  - a circumferential joint (groove + weld bead) every `joint_spacing`;
//  - a longitudinal weld seam along every pipe at the same angle;
//  - and, fixed to places, sparse unique marks (stains, cracks, deposits),
//    `marks_per_metre` of them on average, which are what tells a true
//    revisit from a look-alike.
// Everything is baked into one texture per edge (plus two half-resolution
// mip levels) so that rendering is a lookup.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "bowg_pipe_sim/pipe_network.h"

namespace bowg {
namespace pipe_sim {

struct WallTextureOptions {
  std::uint64_t seed = 1;
  double texel_m = 0.001;        ///< texel size along the pipe (m)
  int circumference_texels = 512;
  double joint_spacing_m = 0.5;  ///< distance between circumferential joints
  double marks_per_metre = 1.0;  ///< unique marks per metre of pipe, >= 0
  /// Margin baked beyond both ends of an edge (mitred elbows reach one
  /// radius past the node).
  double margin_m = 0.12;
  void validate() const;  ///< throws std::invalid_argument naming the field
};

/// One unique mark, for documentation and tests.
struct WallMark {
  enum class Type { kStain, kCrack, kDeposit };
  Type type = Type::kStain;
  int edge = 0;
  double s = 0, theta = 0;  ///< centre (m, rad)
  double size_m = 0;        ///< rough extent
};

class WallTexture {
 public:
  WallTexture(const PipeNetwork& network, const WallTextureOptions& options);

  /// Albedo texture of `edge` at mip `level` (0 = full): rows = s, from
  /// -margin_m in steps of texel_m << level; cols = theta, 2*pi/cols each.
  /// CV_8U, albedo = value / 255.
  const cv::Mat& texture(int edge, int level) const { return levels_[edge][level]; }
  static constexpr int kLevels = 3;

  /// Bilinear albedo in [0, 1] at a wall point (theta wraps, s clamps).
  float albedo(int edge, double s, double theta, int level = 0) const;

  const std::vector<WallMark>& marks() const { return marks_; }
  const WallTextureOptions& options() const { return options_; }
  /// The grain tile (rows = one joint spacing), identical in every section.
  const cv::Mat& tile() const { return tile_; }

 private:
  void bakeTile();
  void drawMark(cv::Mat& texture, const WallMark& mark, std::uint64_t seed) const;

  WallTextureOptions options_;
  double radius_ = 0.076;
  cv::Mat tile_;  // CV_32F albedo
  std::vector<WallMark> marks_;
  std::vector<std::vector<cv::Mat>> levels_;
};

}  // namespace pipe_sim
}  // namespace bowg
