// The ground-truth file of bowg_generate_pipe_sequence
// (ground_truth_report.h): the roll differences of the matches, the frame
// spacing and odometry lines and the header text.
#include "ground_truth_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "bowg_pipe_sim/sequence_stats.h"

namespace bowg {
namespace generate_pipe_sequence_app {
namespace {

double wrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

double medianRollDifference(const std::vector<pipe_sim::FrameState>& frames,
                            const eval::GroundTruth& gt) {
  std::vector<double> roll_differences;
  for (const auto& kv : gt.loops) {
    for (int m : kv.second) {
      roll_differences.push_back(
          std::abs(wrapAngle(frames[kv.first].roll_rad - frames[m].roll_rad)) * 180 / M_PI);
    }
  }
  return pipe_sim::median(roll_differences);
}

std::string spacingLine(const pipe_sim::SequenceStats& stats) {
  char spacing[160];
  std::snprintf(spacing, sizeof(spacing),
                "%.1f m driven (odometer), frame spacing min %.2f / median %.2f / max %.2f cm",
                stats.driven_m, 100 * stats.spacing_min_m, 100 * stats.spacing_median_m,
                100 * stats.spacing_max_m);
  return spacing;
}

std::string odometryLine(const pipe_sim::OdometryNoise& o, double drift_m, double driven_m) {
  // Also as a share of the metres driven, the way odometers are specified
  // (a one-frame sequence has driven nothing).
  const double percent = driven_m > 0 ? 100 * drift_m / driven_m : 0;
  char line[240];
  std::snprintf(line, sizeof(line),
                "end-point drift %.3f m (%.2f %% of the metres driven); slip %g, slip noise %g, "
                "heading drift %g deg/sqrt(m), roll drift %g deg/sqrt(m)",
                drift_m, percent, o.scale_bias, o.scale_noise, o.heading_drift_deg,
                o.roll_drift_deg);
  return line;
}

/// The second mission's line (--again): where it starts and what differs.
std::string againLine(const Args& args, int first_frame) {
  const AgainArgs& a = args.again;
  std::ostringstream line;
  line << "mission 2 (second survey, missions.csv) from frame " << first_frame << ": seed "
       << a.seed << ", speed " << a.speed_mps << " m/s, route "
       << (a.route_nodes.empty() ? "the first mission's" : "nodes " + a.route_nodes)
       << ", marks changed " << a.marks_changed << ", odometry restarted\n";
  return line.str();
}

std::string headerText(const Args& args, std::size_t frames, const eval::GroundTruth& gt,
                       const GroundTruthSummary& summary, const std::vector<int>& mission_starts) {
  const pipe_sim::SequenceOptions& s = args.sequence;
  const std::string route_name =
      args.route_nodes.empty() ? args.route : "nodes " + args.route_nodes;
  std::ostringstream header;
  header << "bowg_ros pipe sequence ground truth (docs/pipe_sequence.md)\n"
         << "query: matches; 0-based index of the image messages (frames)\n"
         << "frames " << frames << ", seed " << s.seed << ", laps " << s.laps
         << ", marks_per_metre " << args.texture.marks_per_metre << ", grain_repeat "
         << args.texture.grain_repeat << ", roll_amplitude_deg " << s.roll_amplitude_deg << "\n"
         << "route " << route_name << ", network " << s.network_width_m << " x "
         << s.network_height_m << " m, roll_knot_spacing_m " << s.roll_knot_spacing_m
         << ", exposure_variation " << s.exposure_variation << ", exposure_step "
         << s.exposure_step << "\n"
         << "speed " << s.speed_mps << " m/s, rate " << s.frame_rate_hz << " Hz, speed_variation "
         << s.speed_variation << ", speed_knot_seconds " << s.speed_knot_s << ", allow_reverse "
         << (s.allow_reverse ? "yes" : "no") << "\n"
         << "texture "
         << (args.texture_images.empty() ? "procedural"
                                         : "quilted from the images in " + args.texture_images);
  if (!args.texture_images.empty()) {
    header << " (" << args.texture.grain_images.size() << " images, crop " << args.texture_crop
           << ")";
  }
  header << "\n";
  if (mission_starts.size() > 1) header << againLine(args, mission_starts[1]);
  header << summary.spacing << "\n"
         << "odometry (odometry.csv, /odom): " << summary.odometry << "\n"
         << "tolerances: distance < " << args.gt_options.max_distance_m << " m, heading < "
         << args.gt_options.max_heading_deg << " deg, excluding the last "
         << args.gt_options.exclude_recent_m << " m driven\n"
         << "queries with a revisit " << gt.positives() << ", median roll difference "
         << summary.median_roll_deg << " deg";
  return header.str();
}

}  // namespace

GroundTruthSummary writeSequenceGroundTruth(const Args& args,
                                            const std::vector<pipe_sim::FrameState>& frames,
                                            const std::vector<int>& mission_starts,
                                            const std::vector<eval::TravelPose>& travel,
                                            double odometry_drift_m) {
  const eval::GroundTruth gt = eval::groundTruthFromPoses(travel, args.gt_options);
  GroundTruthSummary summary;
  summary.positives = gt.positives();
  summary.median_roll_deg = medianRollDifference(frames, gt);
  const pipe_sim::SequenceStats stats = pipe_sim::sequenceStats(frames, mission_starts);
  summary.spacing = spacingLine(stats);
  // The drift is the last odometry run's: relative to that mission's metres.
  const int last_start = mission_starts.empty() ? 0 : mission_starts.back();
  const double run_driven_m =
      frames.empty() ? 0 : stats.driven_m - (last_start > 0 ? frames[last_start - 1].odometer : 0);
  summary.odometry = odometryLine(args.odometry, odometry_drift_m, run_driven_m);
  eval::writeGroundTruth(args.gt, gt, headerText(args, frames.size(), gt, summary, mission_starts));
  return summary;
}

}  // namespace generate_pipe_sequence_app
}  // namespace bowg
