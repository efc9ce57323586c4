// The pipe wall's albedo as a function of the wall point: (edge, s, theta),
// s = metres along the edge from edge.from, theta = angle about the edge axis
// (0 = world up, increasing towards edge_direction x up). Built to ALIAS, as
// real pipes do (method notes, "What defeats the classic pipeline in pipes"):
//  - a material grain that is statistically the same everywhere but, as in
//    a real pipe, not a copy: a fraction `grain_repeat` of it (noise energy,
//    pits, flecks, scratches) is one shared tile repeated in every section,
//    the rest is drawn afresh for every section of every edge (seeded by
//    seed, edge and section index). The shared part still fools a naive
//    matcher; 1 gives the old pixel-identical tile, 0 no shared grain.
//    The grain is procedural, or quilted from photographs of real pipe
//    walls (grain_images, quilted_grain.h) with the same mix;
//  - a circumferential joint (groove + weld bead) every `joint_spacing`;
//  - a longitudinal weld seam along every pipe at the same angle;
//  - and, fixed to places, sparse unique marks (stains, cracks, deposits),
//    `marks_per_metre` of them on average, which are what tells a true
//    revisit from a look-alike (wall_marks.h); a later inspection of the
//    same network sees a share `marks_changed` of them replaced by others.
// Everything is baked into one texture per edge (plus two half-resolution
// mip levels) so that rendering is a lookup.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "bowg_pipe_sim/pipe_network.h"
#include "bowg_pipe_sim/quilted_grain.h"
#include "bowg_pipe_sim/wall_marks.h"

namespace bowg {
namespace pipe_sim {

struct WallTextureOptions {
  std::uint64_t seed = 1;
  double texel_m = 0.001;        ///< texel size along the pipe (m)
  int circumference_texels = 512;
  double joint_spacing_m = 0.5;  ///< distance between circumferential joints
  double marks_per_metre = 1.0;  ///< unique marks per metre of pipe, >= 0
  /// Share of the marks, in [0, 1], removed and replaced by as many new ones
  /// (changeMarks, drawn from marks_change_seed): the same network inspected
  /// again months later. 0 = the marks of `seed` as they are.
  double marks_changed = 0.0;
  std::uint64_t marks_change_seed = 0;
  /// Fraction of the grain shared by every section, in [0, 1]: 1 = every
  /// section's grain is a pixel-identical copy, 0 = every section has its own.
  double grain_repeat = 0.5;
  /// Grey images (CV_8U, loadGrainImages) to quilt the grain from instead of
  /// the procedural noise, pits and scratches (QuiltedGrain); empty = the
  /// procedural grain. The shared / own mix of grain_repeat is the same.
  std::vector<cv::Mat> grain_images;
  /// Margin baked beyond both ends of an edge (mitred elbows reach one
  /// radius past the node).
  double margin_m = 0.12;
  void validate() const;  ///< throws std::invalid_argument naming the field
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

  /// The unique marks drawn, sorted by edge (placeMarks, then changeMarks
  /// when marks_changed > 0).
  const std::vector<WallMark>& marks() const { return marks_; }
  const WallTextureOptions& options() const { return options_; }
  /// What every section has in common (rows = one joint spacing): the shared
  /// part of the grain (weighted by grain_repeat), the joint and the seam.
  const cv::Mat& tile() const { return tile_; }
  /// The albedo of section `section` (rows from s = section * joint_spacing)
  /// of `edge` before marks: the shared tile plus that section's own grain.
  cv::Mat sectionGrain(int edge, long section) const;

 private:
  void bakeTile();
  /// Adds weight * (the grain field seeded by `seed`): procedural noise, or
  /// the quilted field scaled to the procedural grain's spread.
  void addGrain(cv::Mat& tex, std::uint64_t seed, double weight) const;
  void addGrainFeatures(cv::Mat& tex, std::uint64_t seed, double fraction) const;
  void addJointAndSeam(cv::Mat& tex) const;
  void drawMark(cv::Mat& texture, const WallMark& mark) const;

  WallTextureOptions options_;
  double radius_ = 0.076;
  cv::Mat tile_;          // CV_32F albedo
  cv::Mat shared_noise_;  // CV_32F, grain mean + sqrt(grain_repeat) * shared field
  std::shared_ptr<const QuiltedGrain> quilt_;  // null: procedural grain
  double grain_mean_ = 0.48, grain_spread_ = 0;  // of the procedural grain
  std::vector<WallMark> marks_;
  std::vector<std::vector<cv::Mat>> levels_;
};

}  // namespace pipe_sim
}  // namespace bowg
