// Options of the detection stage (paper Sec. III-D: islands, temporal and
// geometric verification) and LoopDetectorOptions, which gathers every
// stage's options of one keyframe's query; it may be swapped between
// keyframes (the nodelet tunes it live).
#pragma once

#include <string>

#include "bowg/scoring/scoring_options.h"
#include "bowg/vocabulary/bow_vector.h"

namespace bowg {

/// Candidate selection and islands (paper Sec. III-D "Islands Matching",
/// after DLoopDetector).
struct IslandOptions {
  /// Acceptance threshold on eta (the paper's second "alpha"), >= 0.
  double min_score = 0.3;
  /// Added to min_score for a query without odometry (images only): no
  /// odometry gate stands between a look-alike and the verified chain, so
  /// its candidates must clear a higher bar (islandOptionsFor). >= 0.
  double images_only_score_margin = 0.0;
  /// The most recent keyframes are never candidates (the robot just saw
  /// them). >= 0.
  int recent_exclusion = 20;
  /// The same window in metres driven, used instead of recent_exclusion when
  /// the query has an odometer (KeyframeInput::odometer): entries driven less
  /// than this before the query, or without an odometer, are never
  /// candidates. A window in metres holds whatever the keyframe spacing; in
  /// keyframes it is a distance only for one spacing. 0 = keyframes always.
  /// >= 0.
  double recent_exclusion_m = 0.0;
  /// The window in metres for a query with an odometer but no odometry
  /// position (a cable counter, a wheel encoder alone): without positions no
  /// gate tells the look-alikes of the robot's own last metres (the same
  /// texture, the same bend seen a few metres back) from a revisit, and a
  /// loop that short tells a pose graph little the odometer does not.
  /// 0 = recent_exclusion_m. >= 0.
  double recent_exclusion_odometer_m = 0.0;
  /// Entries whose ids differ by at most this belong to one island. >= 0.
  int max_intra_island_gap = 3;
  /// Islands with fewer members are ignored. >= 1.
  int min_island_size = 1;
  /// Odometry gate: where the query and an entry have odometry positions of
  /// one run (KeyframeInput::position) and odometers, the entry is a
  /// candidate only when the positions are at most
  ///   odometry_gate_m + odometry_gate_drift * |metres driven between them|
  /// apart: dead reckoning drifts with the metres driven, a look-alike of a
  /// periodic pipe sits metres away. In the suite's tuning half nearly every
  /// false loop was 1-5 m from its query by the drifting odometry.
  /// 0 = no gate. >= 0, both.
  double odometry_gate_m = 0.0;
  double odometry_gate_drift = 0.1;
  /// Heading gate: where the query and an entry have odometry headings
  /// (KeyframeInput::heading) and odometers of one run, the entry is a
  /// candidate only when the robot faced the same way at both, within
  ///   heading_gate_deg + heading_gate_drift_deg * sqrt(|metres driven between them|)
  /// degrees: a heading's error is a random walk in the metres driven. A
  /// camera looking along the pipe sees one section from both sides of a
  /// junction, and the robot turning into the cross pipe there sees the
  /// straight pass a few centimetres away with the same marks in view: the
  /// positions agree, the headings are 65-90 degrees apart. 0 = no gate.
  /// In [0, 180] and >= 0.
  double heading_gate_deg = 0.0;
  double heading_gate_drift_deg = 1.5;
  /// Loop-anchored gate (odometry_gate.h, LoopAnchor): after an accepted
  /// loop (q0, m0) of the same odometry run, an entry e is a candidate of
  /// query q only when q's odometry displacement since q0 and e's since m0
  /// agree within
  ///   odometry_anchor_m + odometry_gate_drift * (|driven q0..q| + |driven m0..e|)
  /// metres, judged by the one of the last kLoopAnchors loops that gives e
  /// the smallest radius. Dead reckoning drifts metres over a lap but only centimetres
  /// over the last metre: right after a loop the robot knows where along
  /// the earlier pass it is to a keyframe or two, closer than the
  /// periodic look-alikes (every 0.5-2 m in the tuning half) that the
  /// absolute gate's radius still admits. 0 = off. >= 0.
  double odometry_anchor_m = 0.0;
  /// A place (keyframes joined by accepted loops, PlaceLinks) keeps at most
  /// this many keyframes in the inverse index: a keyframe whose loop makes
  /// its place larger stays out of it (DatabaseEntry::searchable), later
  /// passes find the place in the keyframes indexed before. The postings a
  /// query walks then grow with the places driven, not with the laps of a
  /// circuit. 0 = no limit: every keyframe, as DBoW2 and the paper. >= 0.
  int indexed_per_place = 0;
  void validate() const;
};

/// Temporal verification (paper Sec. III-D, DLoopDetector's k).
struct TemporalVerificationOptions {
  /// k: number of previous consecutive queries whose best islands must be
  /// consistent with the current one. 0 disables the check.
  int k = 3;
  /// Two islands are consistent when the gap between their id intervals is
  /// at most this (0 = they must overlap). >= 0.
  int max_island_distance = 3;
  /// A query without an island (nothing above min_score) does not break the
  /// chain for up to this many consecutive queries; it does not count towards
  /// k either, and the allowed island distance grows to
  /// max_island_distance * (1 + missed) (the place moved on meanwhile).
  /// 0 = the first such query breaks the chain (DLoopDetector). >= 0.
  int max_missed_queries = 0;
  /// Consistency in metres driven, used instead of max_island_distance when
  /// both queries and the islands' entries have odometers: the previous
  /// island shifted by the metres driven between the two queries must come
  /// within this of the current island (the same place seen from a moving
  /// robot, whatever the keyframe spacing of either pass). 0 = ids always.
  /// >= 0.
  double max_island_distance_m = 0.0;
  /// Hypotheses followed per query: the query's island (the best-scored one,
  /// or the geometric re-ranking's choice) and the next best-scored islands,
  /// up to this many in all, each with its own chain. A new island extends
  /// the longest chain of any previous hypothesis it is consistent with. In
  /// pipes the chosen island often alternates between equally true places
  /// (the same stretch on two earlier laps) or one look-alike wins a single
  /// query: with one hypothesis either restarts the chain, with several the
  /// true place's chain survives. 1 = DLoopDetector (one chain). >= 1.
  int hypotheses = 1;
  /// Queries count towards the chain only once the robot drove at least this
  /// far since the last one that did (odometers known): a robot standing
  /// still sends the same view again and again, and k repeats of one view
  /// are one piece of evidence, not k. Such a query passes when the chain it
  /// continues already passed, and changes nothing. 0 = every query counts
  /// (DLoopDetector). >= 0.
  double min_step_m = 0.0;
  /// An island whose place is linked by accepted loops (PlaceLinks) to a
  /// followed island of the previous query that passes the chain continues
  /// that chain: on a circuit's later laps the chosen island jumps between
  /// equally true earlier laps of the same place. false = DLoopDetector (a
  /// chain follows one pass of the place).
  bool linked_places = false;
  /// An island whose best entry a recent loop anchors (anchoredByRecentLoop,
  /// odometry_gate.h: the odometry since a loop within the last few metres
  /// puts the robot there) passes the temporal verification: the loop and
  /// the odometry since it are the consistency the k previous queries would
  /// show, and at 15 cm between keyframes a revisit that lands between two
  /// earlier keyframes often has no k consecutive islands. Needs
  /// IslandOptions::odometry_anchor_m. false = DLoopDetector.
  bool anchored_chain = false;
  void validate() const;
};

/// Geometric verification (paper Sec. III-D): fundamental matrix by RANSAC on
/// correspondences found through the direct index.
struct GeometricVerificationOptions {
  bool enabled = true;
  /// Depth of the vocabulary level the direct index is built at (1..L); the
  /// paper's Table III uses levels 3-5 of an L=6 tree, 4 is its sweet spot.
  int direct_index_level = 4;
  /// Match every feature against every feature instead (slower, ~same recall).
  bool exhaustive = false;
  /// Correspondences: Hamming distance at most max_hamming and best/second
  /// best ratio below max_neighbour_ratio.
  int max_hamming = 64;
  double max_neighbour_ratio = 0.8;
  /// The fundamental matrix by fundamentalRansac (fundamental_ransac.h):
  /// OpenCV's model, inlier test and adaptive stop with a 7-point solver
  /// that costs ~1 us per sample instead of OpenCV's ~8 us, and its own
  /// sample sequence. false = cv::findFundamentalMat(FM_RANSAC), the paper's
  /// (DLoopDetector's) verification.
  bool native_ransac = true;
  /// The native RANSAC's least-squares refits of each new best model to its
  /// inliers while they gain inliers (FundamentalRansacOptions::refits;
  /// LO-RANSAC). 0 = plain RANSAC, as OpenCV's. >= 0; unused without
  /// native_ransac.
  int ransac_refits = 3;
  /// The RANSAC's sample sequence: 0 = the fixed default, another value
  /// another fixed sequence (the native RANSAC's generator seed; OpenCV's
  /// generator is fixed, so its correspondences come in an order shuffled
  /// by it). A candidate within a few inliers of min_inliers can fall either
  /// way with the sequence, and a loop decides the next queries' chains:
  /// evaluate with a few seeds to see how much a result owes to it. >= 0.
  int ransac_seed = 0;
  /// RANSAC: reprojection threshold (px) and confidence.
  double ransac_threshold_px = 2.0;
  double ransac_confidence = 0.99;
  /// Accept with at least this many inliers. >= 8.
  int min_inliers = 15;
  /// RANSAC draws at most ransacSampleBound(n, min_inliers,
  /// ransac_bound_confidence) samples (geometric_verification.h): enough to
  /// find a model with min_inliers of the n correspondences at that
  /// confidence, instead of OpenCV's fixed 1,000. A candidate whose full run
  /// ends below min_inliers is rejected either way (the best model only
  /// grows with the samples); the others keep their sample sequence, so a
  /// loop is lost only when the RANSAC finds its model after the bound. The
  /// bound's confidence is above the RANSAC's own because a marginal loop's
  /// first all-inlier sample often scores a few inliers short of its best.
  /// 0 = OpenCV's 1,000 (the paper's verification; also with OpenCV's RANSAC
  /// wherever OpenCV is older than 3.4.10 / 4.3, whose findFundamentalMat
  /// takes no sample limit: ransacSampleBoundAvailable()). 0 or in (0, 1).
  double ransac_bound_confidence = 0.9999;
  /// Geometric re-ranking: the best entries of the top `candidates` islands
  /// are verified and, among those with at least min_inliers
  /// correspondences, the one with the most inliers is the query's island
  /// (for the temporal verification and the loop; none: the best-scored
  /// island). Under aliasing the
  /// best-scored island is often a look-alike while the true place is among
  /// the next few; geometry separates them better than the word scores.
  /// 1 = the paper (only the best island is verified). >= 1.
  int candidates = 1;
  /// RANSACs the re-ranking may run, on the candidates with the most
  /// correspondences first. RANSAC is the cost of the re-ranking (1-4 ms
  /// each on 640x480 pipe frames with OpenCV's, 0.1-0.5 ms with the native
  /// one, ~0.05 ms for a correspondence search),
  /// and the candidate with the most correspondences nearly always has the
  /// most inliers: on the robustness suite's tuning half 2 gives the same
  /// recall at 100 % precision as an unbounded re-ranking at about half its
  /// time (docs/results.md). 0 = rank by correspondences alone and run
  /// RANSAC once, on the chosen island's entry, only when it passes the
  /// temporal verification. >= 0; unused with candidates = 1.
  int rerank_ransacs = 2;
  void validate() const;
};

/// The verified chain (verified_chain.h): what a loop needs that no odometry
/// position places (images only, an odometer only, or the first loop of a
/// revisit with positions). In a pipe that repeats every section a
/// look-alike passes every check of one query; what it cannot do is win the
/// geometric re-ranking query after query, each match following the robot,
/// with inliers on what the pipe does not repeat.
struct VerifiedChainOptions {
  /// Previous queries whose verified matches (the re-ranking's best two with
  /// at least min_inliers inliers) must lead, step by step as the robot
  /// moves, to the loop's match; a chain that leads back to a published
  /// loop passes at once. 0 = off: the paper's temporal verification alone.
  /// >= 0.
  int length = 0;
  /// Queries without a verified match the chain steps over, in a row. >= 0.
  int max_missed = 1;
  /// Queries whose verified matches all lead elsewhere (a look-alike won
  /// the re-ranking there) the walk steps over, at most this many in all;
  /// each also counts as a query without a match towards max_missed. Where
  /// the step across them is in keyframe ids (no odometer or no
  /// max_island_distance_m), the match must also advance at the chain's own
  /// rate, within 1.5 keyframes (VerifiedChain::passes): the step's band in
  /// ids widens with every query stepped over. 0 = such a query ends the
  /// walk. >= 0.
  int max_strays = 0;
  /// Each match of the chain (and the loop's) needs this many inliers on
  /// query features the robot's recent past does not repeat (the unique
  /// marks, the wall's own grain), unless the chain leads back to a
  /// published loop. Where the odometry gate judged the loop's match (both
  /// placed by positions of one odometry run), look-alikes beyond its
  /// radius are out already: the matches need this many on average, each
  /// at least half of it (rounded down). 0 = no such test. >= 0.
  int min_unique_inliers = 0;
  /// The recent past: this many keyframes, spread over the metres driven
  /// from repeated_texture_min_m to IslandOptions::recent_exclusion_m back
  /// (odometer), else over the recent_exclusion keyframes. Their
  /// correspondences with the query mark its repeated texture. >= 1.
  int repeated_texture_keyframes = 12;
  /// Nearer keyframes see the query's own wall, marks included. >= 0.
  double repeated_texture_min_m = 0.6;
  void validate() const;
};

/// The loop's translation in metres (metric_translation.h): from the
/// odometer's distance between the match and a neighbour keyframe, when
/// the keyframes carry odometers and intrinsics are known.
struct MetricTranslationOptions {
  bool enabled = true;
  /// The neighbour is the nearest keyframe at least this far from the match
  /// (m): a shorter baseline triangulates depth poorly ...
  double min_baseline_m = 0.03;
  /// ... and at most this far: the odometer's path length stands for the
  /// camera's displacement only over short, nearly straight stretches.
  double max_baseline_m = 0.5;
  /// Triangulated loop inliers the perspective-n-point fit needs and keeps.
  int min_points = 8;
  /// Relative error of the odometer over the baseline (the covariance's
  /// scale term).
  double odometer_sigma = 0.05;
  /// Bootstrap resamples the covariance is measured from (each one
  /// essential matrix and one PnP fit).
  int covariance_samples = 20;
  /// Factor on the covariance measured from those: 20 resamples and the
  /// first-order terms miss part of the error a neighbour's pose puts into
  /// every depth (a heavy tail: 77 % of the truths inside the raw 95 %
  /// ellipsoid), so the raw covariance is overconfident. 12 is the smallest
  /// of 1, 1.5, 2, 2.5, 3, 4, 5, 6, 8, 12, 16 whose ellipsoid holds the truth
  /// 95 % of the time on the robustness suite's tuning half
  /// (tools/suite/covariance_coverage.py; docs/pose_graph.md, "Metric loops").
  double covariance_scale = 12.0;
  void validate() const;
};

/// Everything the loop detector needs per keyframe.
struct LoopDetectorOptions {
  ScoringType scoring = ScoringType::kL1;
  WordGroupOptions word_groups;
  DistributionOptions distribution;
  SimilarityOptions similarity;
  TemporalScoreOptions temporal_score;
  IslandOptions islands;
  TemporalVerificationOptions temporal_verification;
  GeometricVerificationOptions geometric;
  VerifiedChainOptions chain;
  MetricTranslationOptions metric;

  /// Throws InvalidParameter("<stage>.<field>: <why>") on the first invalid
  /// value, e.g. "similarity.lambda_1 + similarity.lambda_2 must be <= 1".
  void validate() const;

  /// The ablation presets: "bow" (pure bag of words), "word_groups",
  /// "temporal" (+ temporal score), "distribution" (+ distribution score).
  /// Each row switches on one more module on top of the previous one and
  /// keeps every other field of base. "paper": the full method as the paper
  /// writes it, with this implementation's extensions switched off;
  /// "paper_bow": the same pipeline with pure bag-of-words scores (DBoW2 with
  /// DLoopDetector's checks); "configured": base unchanged. "without_<x>":
  /// base with one extension of this implementation switched back to the
  /// paper (x = floor, normaliser_distance, alignment, missed_queries,
  /// hypotheses, min_step, place_index, reranking, verified_chain), so that the suite shows what
  /// each extension adds to the configuration.
  static LoopDetectorOptions ablation(const std::string& row, const LoopDetectorOptions& base);
};

}  // namespace bowg
