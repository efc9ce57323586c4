// The parameter table: one row per user parameter (see parameter_table.h).
// Ranges are the ones options.h documents; where options.h leaves a side open
// (e.g. "> 0") the table picks a generous finite bound, because the dynamic
// reconfigure GUI and the README need one.
#include "bowg/parameters/parameter_table.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>

#include "bowg/core/errors.h"

namespace bowg {
namespace {

/// A row plus the accessors that tie it to a PipelineOptions field. Exactly
/// one accessor matching info.type is set.
struct Row {
  ParameterInfo info;
  std::function<bool*(PipelineOptions*)> as_bool;
  std::function<int*(PipelineOptions*)> as_int;
  std::function<double*(PipelineOptions*)> as_double;
  std::function<std::string*(PipelineOptions*)> as_string;
  std::function<void(PipelineOptions*, const std::string&)> set_enum;
  std::function<std::string(const PipelineOptions&)> get_enum;
};

Row boolRow(const std::string& name, const std::string& group, const std::string& field, bool live,
            std::function<bool*(PipelineOptions*)> f, const std::string& d) {
  Row r;
  r.info = ParameterInfo{name, ParameterType::kBool, group, field, 0, 1, {}, live, d};
  r.as_bool = std::move(f);
  return r;
}

Row intRow(const std::string& name, const std::string& group, const std::string& field, int lo,
           int hi, bool live, std::function<int*(PipelineOptions*)> f, const std::string& d) {
  Row r;
  r.info =
      ParameterInfo{name, ParameterType::kInt, group, field, double(lo), double(hi), {}, live, d};
  r.as_int = std::move(f);
  return r;
}

Row doubleRow(const std::string& name, const std::string& group, const std::string& field,
              double lo, double hi, bool live, std::function<double*(PipelineOptions*)> f,
              const std::string& d) {
  Row r;
  r.info = ParameterInfo{name, ParameterType::kDouble, group, field, lo, hi, {}, live, d};
  r.as_double = std::move(f);
  return r;
}

Row stringRow(const std::string& name, const std::string& group, const std::string& field,
              std::function<std::string*(PipelineOptions*)> f, const std::string& d) {
  Row r;
  r.info = ParameterInfo{name, ParameterType::kString, group, field, 0, 0, {}, false, d};
  r.as_string = std::move(f);
  return r;
}

Row enumRow(const std::string& name, const std::string& group, const std::string& field,
            std::vector<std::string> choices,
            std::function<void(PipelineOptions*, const std::string&)> set,
            std::function<std::string(const PipelineOptions&)> get, const std::string& d) {
  Row r;
  r.info =
      ParameterInfo{name, ParameterType::kEnum, group, field, 0, 0, std::move(choices), false, d};
  r.set_enum = std::move(set);
  r.get_enum = std::move(get);
  return r;
}

#define BOWG_FIELD(type, expr) [](PipelineOptions* o) -> type* { return &o->expr; }

std::vector<Row> makeRows() {
  const std::string det = "detector";
  const std::string fea = "features";
  std::vector<Row> rows;
  // --- Scoring (paper Sec. III-B, DBoW2's metrics).
  rows.push_back(enumRow(
      "scoring", det, "scoring", {"l1", "l2", "chi_square", "kl", "bhattacharyya", "dot_product"},
      [](PipelineOptions* o, const std::string& v) {
        o->detector.scoring = scoringTypeFromString(v);
      },
      [](const PipelineOptions& o) { return toString(o.detector.scoring); },
      "Word-score metric s_w (DBoW2 numbering); a run-time choice, independent of the "
      "vocabulary file"));
  // --- Word groups (Sec. III-A).
  rows.push_back(boolRow("word_groups", det, "word_groups.enabled", true,
                         BOWG_FIELD(bool, detector.word_groups.enabled),
                         "Ablation switch: word groups and the group score eta_g (off = pure "
                         "bag of words)"));
  rows.push_back(doubleRow("group_radius_scale", det, "word_groups.radius_scale", 0.01, 10.0, false,
                           BOWG_FIELD(double, detector.word_groups.radius_scale),
                           "A neighbour joins a word group when closer than this times the "
                           "keypoint size (paper: 1)"));
  // --- Distribution score (Sec. III-C).
  rows.push_back(boolRow("distribution", det, "distribution.enabled", true,
                         BOWG_FIELD(bool, detector.distribution.enabled),
                         "Ablation switch: the roll-invariant feature-distribution score eta_d "
                         "(on in pipes, off for generic scenes)"));
  rows.push_back(intRow("fan_bins", det, "distribution.fan_bins", 1, 64, true,
                        BOWG_FIELD(int, detector.distribution.fan_bins),
                        "m: number of fan-shaped bins of angle 2*pi/m around the principal point"));
  // --- Similarity (eqs. 2-5, 9).
  rows.push_back(doubleRow("lambda_1", det, "similarity.lambda_1", 0.0, 1.0, true,
                           BOWG_FIELD(double, detector.similarity.lambda_1),
                           "lambda_1: weight of the normalised word score eta_w (eqs. 5, 9)"));
  rows.push_back(doubleRow("lambda_2", det, "similarity.lambda_2", 0.0, 1.0, true,
                           BOWG_FIELD(double, detector.similarity.lambda_2),
                           "lambda_2: weight of eta_g when the distribution score is on (eq. 9); "
                           "lambda_1 + lambda_2 <= 1"));
  rows.push_back(doubleRow("min_word_normaliser", det, "similarity.min_word_normaliser", 0.0, 1.0,
                           false, BOWG_FIELD(double, detector.similarity.min_word_normaliser),
                           "No loop when s_w(I_t, I_t-1) is below this (DLoopDetector's "
                           "min_nss_factor)"));
  rows.push_back(doubleRow("min_group_normaliser", det, "similarity.min_group_normaliser", 0.0, 1.0,
                           false, BOWG_FIELD(double, detector.similarity.min_group_normaliser),
                           "No loop when s_g(I_t, I_t-1) is below this"));
  rows.push_back(doubleRow("min_distribution_normaliser", det,
                           "similarity.min_distribution_normaliser", 0.0, 1.0, false,
                           BOWG_FIELD(double, detector.similarity.min_distribution_normaliser),
                           "No loop when s_d(I_t, I_t-1) is below this"));
  rows.push_back(doubleRow("normaliser_floor", det, "similarity.normaliser_floor", 0.0, 10.0,
                           false, BOWG_FIELD(double, detector.similarity.normaliser_floor),
                           "Each normaliser is at least this times the median normaliser of the "
                           "last normaliser_window keyframes (0 = the paper's s(I_t, I_t-1) "
                           "alone; docs/method.md)"));
  rows.push_back(intRow("normaliser_window", det, "similarity.normaliser_window", 1, 100000,
                        false, BOWG_FIELD(int, detector.similarity.normaliser_window),
                        "Keyframes in the median of the normaliser floor"));
  rows.push_back(doubleRow("normaliser_distance_m", det, "similarity.normaliser_distance_m", 0.0,
                           100.0, false,
                           BOWG_FIELD(double, detector.similarity.normaliser_distance_m),
                           "With odometry: normalise by the score against the newest keyframe "
                           "driven at least this far back instead of I_t-1 (0 = I_t-1 always)"));
  // --- Temporal score (eqs. 6-7).
  rows.push_back(boolRow("temporal_score", det, "temporal_score.enabled", true,
                         BOWG_FIELD(bool, detector.temporal_score.enabled),
                         "Ablation switch: the adaptive temporal score eta_temp (eqs. 6-7)"));
  rows.push_back(doubleRow("w_max", det, "temporal_score.w_max", 0.0, 0.99, true,
                           BOWG_FIELD(double, detector.temporal_score.w_max),
                           "w_max: largest weight of the previous query's score (eq. 6)"));
  rows.push_back(doubleRow("alpha", det, "temporal_score.alpha", 0.001, 10.0, true,
                           BOWG_FIELD(double, detector.temporal_score.alpha),
                           "alpha: scale of the score difference in eq. 6 (not the acceptance "
                           "threshold, see min_score)"));
  rows.push_back(intRow("alignment_window", det, "temporal_score.alignment_window", 0, 1000, false,
                        BOWG_FIELD(int, detector.temporal_score.alignment_window),
                        "r: eq. 7's previous score is the best of the previous query's scores "
                        "of entries tj-1-r .. tj-1+r, so passes at different speeds keep it "
                        "(0 = eq. 7 exactly; docs/method.md)"));
  rows.push_back(intRow("temporal_memory", det, "temporal_score.max_missed_queries", 0, 100, false,
                        BOWG_FIELD(int, detector.temporal_score.max_missed_queries),
                        "Queries that cannot be scored (no candidate, small normaliser) that "
                        "eq. 7's previous scores survive (0 = the paper: forgotten at once)"));
  rows.push_back(doubleRow("alignment_window_m", det, "temporal_score.alignment_window_m", 0.0,
                           100.0, false,
                           BOWG_FIELD(double, detector.temporal_score.alignment_window_m),
                           "With odometry: eq. 7's previous score is the best among the entries "
                           "within this many metres of where tj was when the previous query was "
                           "taken (0 = alignment_window in keyframes)"));
  // --- Islands (Sec. III-D).
  rows.push_back(doubleRow("min_score", det, "islands.min_score", 0.0, 10.0, true,
                           BOWG_FIELD(double, detector.islands.min_score),
                           "Acceptance threshold on the final score eta (the paper's second "
                           "alpha)"));
  rows.push_back(intRow("recent_exclusion", det, "islands.recent_exclusion", 0, 1000000, false,
                        BOWG_FIELD(int, detector.islands.recent_exclusion),
                        "The most recent keyframes are never loop candidates"));
  rows.push_back(doubleRow("recent_exclusion_m", det, "islands.recent_exclusion_m", 0.0, 1e6,
                           false, BOWG_FIELD(double, detector.islands.recent_exclusion_m),
                           "The same window in metres driven, used instead when odometry gives "
                           "the keyframes an odometer (0 = keyframes always)"));
  rows.push_back(intRow("max_intra_island_gap", det, "islands.max_intra_island_gap", 0, 10000,
                        false, BOWG_FIELD(int, detector.islands.max_intra_island_gap),
                        "Candidates whose ids differ by at most this form one island"));
  rows.push_back(intRow("min_island_size", det, "islands.min_island_size", 1, 10000, false,
                        BOWG_FIELD(int, detector.islands.min_island_size),
                        "Islands with fewer members are ignored"));
  // --- Temporal verification.
  rows.push_back(intRow("temporal_k", det, "temporal_verification.k", 0, 100, true,
                        BOWG_FIELD(int, detector.temporal_verification.k),
                        "k: previous queries whose best islands must agree (0 = off)"));
  rows.push_back(intRow("max_island_distance", det, "temporal_verification.max_island_distance", 0,
                        10000, false,
                        BOWG_FIELD(int, detector.temporal_verification.max_island_distance),
                        "Two islands agree when their id intervals are at most this far apart"));
  rows.push_back(intRow("temporal_max_missed", det, "temporal_verification.max_missed_queries", 0,
                        100, false,
                        BOWG_FIELD(int, detector.temporal_verification.max_missed_queries),
                        "Queries without an island that do not break the temporal chain "
                        "(0 = DLoopDetector: the first one breaks it)"));
  rows.push_back(doubleRow("max_island_distance_m", det,
                           "temporal_verification.max_island_distance_m", 0.0, 100.0, false,
                           BOWG_FIELD(double, detector.temporal_verification.max_island_distance_m),
                           "With odometry: the previous island moved by the metres driven must "
                           "come within this of the current one (0 = max_island_distance in ids)"));
  rows.push_back(intRow("temporal_hypotheses", det, "temporal_verification.hypotheses", 1, 100,
                        false, BOWG_FIELD(int, detector.temporal_verification.hypotheses),
                        "Islands per query followed with their own temporal chains "
                        "(1 = DLoopDetector: the chosen island only)"));
  rows.push_back(doubleRow("temporal_min_step_m", det, "temporal_verification.min_step_m", 0.0,
                           100.0, false,
                           BOWG_FIELD(double, detector.temporal_verification.min_step_m),
                           "With odometry: a query counts towards the temporal chain only after "
                           "this many metres driven since the last one that did (0 = every query)"));
  // --- Geometric verification.
  rows.push_back(boolRow("geometric_verification", det, "geometric.enabled", true,
                         BOWG_FIELD(bool, detector.geometric.enabled),
                         "Ablation switch: fundamental-matrix RANSAC on direct-index "
                         "correspondences"));
  rows.push_back(intRow("direct_index_level", det, "geometric.direct_index_level", 1, 10, true,
                        BOWG_FIELD(int, detector.geometric.direct_index_level),
                        "Vocabulary level of the direct index (1..L; paper Table III: 4 of 6)"));
  rows.push_back(boolRow("exhaustive_matching", det, "geometric.exhaustive", true,
                         BOWG_FIELD(bool, detector.geometric.exhaustive),
                         "Match every feature against every feature instead of using the direct "
                         "index"));
  rows.push_back(intRow("max_hamming", det, "geometric.max_hamming", 0, 256, false,
                        BOWG_FIELD(int, detector.geometric.max_hamming),
                        "Largest Hamming distance of a correspondence (bits of 256)"));
  rows.push_back(doubleRow("max_neighbour_ratio", det, "geometric.max_neighbour_ratio", 0.01, 1.0,
                           false, BOWG_FIELD(double, detector.geometric.max_neighbour_ratio),
                           "Best/second-best distance ratio test for correspondences"));
  rows.push_back(doubleRow("ransac_threshold_px", det, "geometric.ransac_threshold_px", 0.1, 100.0,
                           false, BOWG_FIELD(double, detector.geometric.ransac_threshold_px),
                           "RANSAC reprojection threshold (px)"));
  rows.push_back(doubleRow("ransac_confidence", det, "geometric.ransac_confidence", 0.5, 0.9999,
                           false, BOWG_FIELD(double, detector.geometric.ransac_confidence),
                           "RANSAC confidence"));
  rows.push_back(intRow("min_inliers", det, "geometric.min_inliers", 8, 10000, true,
                        BOWG_FIELD(int, detector.geometric.min_inliers),
                        "Accept a loop with at least this many RANSAC inliers"));
  rows.push_back(intRow("verified_candidates", det, "geometric.candidates", 1, 100, false,
                        BOWG_FIELD(int, detector.geometric.candidates),
                        "Geometric re-ranking: verify the best entries of this many top islands "
                        "and keep the one with the most inliers (1 = the paper)"));
  // --- Features (Sec. III-A).
  rows.push_back(enumRow(
      "feature_detector", fea, "detector", {"gftt", "orb"},
      [](PipelineOptions* o, const std::string& v) {
        o->features.detector =
            v == "gftt" ? FeatureOptions::Detector::kGftt : FeatureOptions::Detector::kOrb;
      },
      [](const PipelineOptions& o) {
        return std::string(o.features.detector == FeatureOptions::Detector::kGftt ? "gftt" : "orb");
      },
      "Keypoint detector: GFTT corners (pipes) or multi-scale ORB/FAST (generic scenes)"));
  rows.push_back(enumRow(
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
  rows.push_back(intRow("gftt_max_corners", fea, "gftt_max_corners", 1, 100000, false,
                        BOWG_FIELD(int, features.gftt_max_corners),
                        "GFTT: most corners per image"));
  rows.push_back(doubleRow("gftt_quality_level", fea, "gftt_quality_level", 1e-6, 1.0, false,
                           BOWG_FIELD(double, features.gftt_quality_level),
                           "GFTT: minimum corner quality relative to the best corner"));
  rows.push_back(doubleRow("gftt_min_distance", fea, "gftt_min_distance", 0.0, 1000.0, false,
                           BOWG_FIELD(double, features.gftt_min_distance),
                           "GFTT: minimum distance between corners (px)"));
  rows.push_back(intRow("gftt_block_size", fea, "gftt_block_size", 1, 99, false,
                        BOWG_FIELD(int, features.gftt_block_size),
                        "GFTT: derivative covariation block size (px)"));
  rows.push_back(boolRow("gftt_use_harris", fea, "gftt_use_harris", false,
                         BOWG_FIELD(bool, features.gftt_use_harris),
                         "GFTT: Harris response instead of Shi-Tomasi"));
  rows.push_back(doubleRow("gftt_keypoint_size", fea, "gftt_keypoint_size", 1.0, 1000.0, false,
                           BOWG_FIELD(double, features.gftt_keypoint_size),
                           "Size given to GFTT corners (px): word-group radius and descriptor "
                           "patch"));
  rows.push_back(intRow("orb_max_features", fea, "orb_max_features", 1, 100000, false,
                        BOWG_FIELD(int, features.orb_max_features),
                        "ORB: most features per image"));
  rows.push_back(doubleRow("orb_scale_factor", fea, "orb_scale_factor", 1.001, 4.0, false,
                           BOWG_FIELD(double, features.orb_scale_factor),
                           "ORB: pyramid scale factor"));
  rows.push_back(intRow("orb_levels", fea, "orb_levels", 1, 32, false,
                        BOWG_FIELD(int, features.orb_levels), "ORB: pyramid levels"));
  rows.push_back(intRow("orb_fast_threshold", fea, "orb_fast_threshold", 1, 255, false,
                        BOWG_FIELD(int, features.orb_fast_threshold), "ORB: FAST threshold"));
  rows.push_back(boolRow("compute_orientation", fea, "compute_orientation", false,
                         BOWG_FIELD(bool, features.compute_orientation),
                         "Steer descriptors by the intensity-centroid orientation (pipe robots "
                         "roll)"));
  rows.push_back(stringRow("brief_pattern_path", fea, "brief_pattern_path",
                           BOWG_FIELD(std::string, features.brief_pattern_path),
                           "BRIEF test-pattern file (VINS brief_pattern.yml layout)"));
  rows.push_back(stringRow("mask_path", fea, "mask_path",
                           BOWG_FIELD(std::string, features.mask_path),
                           "Optional 8-bit mask image (non-zero = usable), e.g. to blank text "
                           "overlays"));
  return rows;
}

#undef BOWG_FIELD

const std::vector<Row>& rows() {
  static const std::vector<Row> table = makeRows();
  return table;
}

const Row& rowOf(const std::string& name) {
  for (const Row& r : rows()) {
    if (r.info.name == name) return r;
  }
  throw InvalidParameter("unknown parameter '" + name +
                         "' (see the parameter table in the README for the valid names)");
}

/// Shortest text that reads back to the same double.
std::string formatDouble(double v) {
  for (int precision = 6; precision <= 17; ++precision) {
    std::ostringstream s;
    s.precision(precision);
    s << v;
    if (std::strtod(s.str().c_str(), nullptr) == v) return s.str();
  }
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

bool parseDouble(const std::string& text, double* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(*value);
}

bool parseBool(const std::string& text, bool* value) {
  // The spellings yaml 1.1 (rosparam, PyYAML) reads as booleans, plus 0/1.
  static const char* kTrue[] = {"true", "True", "TRUE", "yes", "Yes", "on", "On", "1"};
  static const char* kFalse[] = {"false", "False", "FALSE", "no", "No", "off", "Off", "0"};
  for (const char* t : kTrue) {
    if (text == t) return (*value = true), true;
  }
  for (const char* f : kFalse) {
    if (text == f) return (*value = false), true;
  }
  return false;
}

void checkRange(const ParameterInfo& info, double v) {
  if (v < info.min_value || v > info.max_value) {
    throw InvalidParameter(info.name + ": " + formatDouble(v) + " is outside [" +
                           formatDouble(info.min_value) + ", " + formatDouble(info.max_value) +
                           "]");
  }
}

void setNumeric(const Row& r, double v, PipelineOptions* o) {
  const ParameterInfo& info = r.info;
  switch (info.type) {
    case ParameterType::kBool:
      if (v != 0.0 && v != 1.0) {
        throw InvalidParameter(info.name + ": a boolean must be 0 or 1, got " + formatDouble(v));
      }
      *r.as_bool(o) = v != 0.0;
      return;
    case ParameterType::kInt:
      if (!std::isfinite(v) || std::floor(v) != v) {
        throw InvalidParameter(info.name + ": an integer is required, got " + formatDouble(v));
      }
      checkRange(info, v);
      *r.as_int(o) = static_cast<int>(v);
      return;
    case ParameterType::kDouble:
      if (!std::isfinite(v)) throw InvalidParameter(info.name + ": value is not finite");
      checkRange(info, v);
      *r.as_double(o) = v;
      return;
    case ParameterType::kString:
    case ParameterType::kEnum:
      break;
  }
  throw InvalidParameter(info.name + ": is a " + toString(info.type) +
                         " parameter and cannot take the number " + formatDouble(v));
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return std::string();
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

}  // namespace

const char* toString(ParameterType t) {
  switch (t) {
    case ParameterType::kBool:
      return "bool";
    case ParameterType::kInt:
      return "int";
    case ParameterType::kDouble:
      return "double";
    case ParameterType::kString:
      return "string";
    case ParameterType::kEnum:
      return "enum";
  }
  return "?";
}

void PipelineOptions::validate() const {
  detector.validate();
  features.validate();
}

const std::vector<ParameterInfo>& parameterTable() {
  static const std::vector<ParameterInfo> table = [] {
    std::vector<ParameterInfo> t;
    for (const Row& r : rows()) t.push_back(r.info);
    return t;
  }();
  return table;
}

const ParameterInfo* findParameter(const std::string& name) {
  for (const ParameterInfo& p : parameterTable()) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

void setParameter(const std::string& name, const std::string& value, PipelineOptions* options) {
  const Row& r = rowOf(name);
  const ParameterInfo& info = r.info;
  switch (info.type) {
    case ParameterType::kBool: {
      bool b = false;
      if (!parseBool(value, &b)) {
        throw InvalidParameter(name + ": '" + value + "' is not a boolean (true/false)");
      }
      *r.as_bool(options) = b;
      return;
    }
    case ParameterType::kInt:
    case ParameterType::kDouble: {
      double v = 0;
      if (!parseDouble(value, &v)) {
        throw InvalidParameter(name + ": '" + value + "' is not a number");
      }
      setNumeric(r, v, options);
      return;
    }
    case ParameterType::kString:
      *r.as_string(options) = value;
      return;
    case ParameterType::kEnum: {
      if (std::find(info.choices.begin(), info.choices.end(), value) == info.choices.end()) {
        std::string list;
        for (const std::string& c : info.choices) list += (list.empty() ? "" : ", ") + c;
        throw InvalidParameter(name + ": '" + value + "' is not one of " + list);
      }
      r.set_enum(options, value);
      return;
    }
  }
}

void setParameter(const std::string& name, double value, PipelineOptions* options) {
  setNumeric(rowOf(name), value, options);
}

std::string getParameter(const std::string& name, const PipelineOptions& options) {
  const Row& r = rowOf(name);
  // The accessors take a pointer (they also write); reading through a copy
  // keeps `options` const.
  PipelineOptions copy = options;
  switch (r.info.type) {
    case ParameterType::kBool:
      return *r.as_bool(&copy) ? "true" : "false";
    case ParameterType::kInt:
      return std::to_string(*r.as_int(&copy));
    case ParameterType::kDouble:
      return formatDouble(*r.as_double(&copy));
    case ParameterType::kString:
      return *r.as_string(&copy);
    case ParameterType::kEnum:
      return r.get_enum(options);
  }
  return std::string();
}

std::string defaultValue(const std::string& name) { return getParameter(name, PipelineOptions()); }

void applyParameters(const std::map<std::string, std::string>& values, PipelineOptions* options,
                     const std::string& source) {
  const std::string where = source.empty() ? std::string() : source + ": ";
  PipelineOptions result = *options;
  for (const auto& kv : values) {
    try {
      setParameter(kv.first, kv.second, &result);
    } catch (const InvalidParameter& e) {
      throw InvalidParameter(where + e.what());
    }
  }
  try {
    result.validate();
  } catch (const InvalidParameter& e) {
    throw InvalidParameter(where + e.what());
  }
  *options = result;
}

std::map<std::string, std::string> readFlatYaml(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError("cannot open parameter file '" + path + "'");
  std::map<std::string, std::string> values;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string where = path + ":" + std::to_string(number) + ": ";
    // Strip a comment: '#' at the start or after a blank, outside quotes.
    char quote = 0;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (quote) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) {
        line.erase(i);
        break;
      }
    }
    if (trim(line).empty() || trim(line) == "---") continue;
    if (line[0] == ' ' || line[0] == '\t' || trim(line)[0] == '-') {
      throw FormatError(where + "only flat 'key: value' lines are supported (no nesting, lists)");
    }
    const auto colon = line.find(':');
    if (colon == std::string::npos) throw FormatError(where + "expected 'key: value'");
    const std::string key = trim(line.substr(0, colon));
    std::string value = trim(line.substr(colon + 1));
    if (key.empty()) throw FormatError(where + "empty key");
    if (value.empty()) {
      throw FormatError(where + "'" + key + "' has no value (nested maps are not supported)");
    }
    if (value[0] == '[' || value[0] == '{') {
      throw FormatError(where + "'" + key + "': lists and maps are not supported");
    }
    if (value.size() >= 2 && (value[0] == '"' || value[0] == '\'') && value.back() == value[0]) {
      value = value.substr(1, value.size() - 2);
    }
    if (!values.emplace(key, value).second) {
      throw FormatError(where + "duplicate key '" + key + "'");
    }
  }
  return values;
}

PipelineOptions loadParameterFile(const std::string& path, const PipelineOptions& base) {
  PipelineOptions options = base;
  applyParameters(readFlatYaml(path), &options, path);
  return options;
}

std::vector<std::string> correctLiveParameters(int vocabulary_depth, PipelineOptions* options) {
  std::vector<std::string> corrections;
  for (const Row& r : rows()) {
    const ParameterInfo& info = r.info;
    if (info.type == ParameterType::kDouble) {
      double* v = r.as_double(options);
      const double c = std::isfinite(*v) ? std::min(std::max(*v, info.min_value), info.max_value)
                                         : info.min_value;
      if (c != *v) {
        corrections.push_back(info.name + " " + formatDouble(*v) + " is outside [" +
                              formatDouble(info.min_value) + ", " + formatDouble(info.max_value) +
                              "]: set to " + formatDouble(c));
        *v = c;
      }
    } else if (info.type == ParameterType::kInt) {
      int* v = r.as_int(options);
      const int c = std::min(std::max(*v, static_cast<int>(info.min_value)),
                             static_cast<int>(info.max_value));
      if (c != *v) {
        corrections.push_back(info.name + " " + std::to_string(*v) + " is outside [" +
                              formatDouble(info.min_value) + ", " + formatDouble(info.max_value) +
                              "]: set to " + std::to_string(c));
        *v = c;
      }
    }
  }
  SimilarityOptions& s = options->detector.similarity;
  // Eq. 9 weighs eta_d by 1 - lambda_1 - lambda_2, which must not be negative;
  // lambda_1 is the one the user most likely just moved, so lambda_2 gives way.
  if (s.lambda_1 + s.lambda_2 > 1.0) {
    const double l2 = 1.0 - s.lambda_1;
    corrections.push_back("lambda_1 + lambda_2 = " + formatDouble(s.lambda_1 + s.lambda_2) +
                          " > 1: lambda_2 set to 1 - lambda_1 = " + formatDouble(l2));
    s.lambda_2 = l2;
  }
  int& level = options->detector.geometric.direct_index_level;
  if (vocabulary_depth > 0 && level > vocabulary_depth) {
    corrections.push_back("direct_index_level " + std::to_string(level) +
                          " exceeds the vocabulary depth L = " + std::to_string(vocabulary_depth) +
                          ": set to " + std::to_string(vocabulary_depth));
    level = vocabulary_depth;
  }
  return corrections;
}

}  // namespace bowg
