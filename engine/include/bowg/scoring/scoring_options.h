// Options of the scoring stage (paper Sec. III-A to III-C, eqs. 2-7, 9): word
// groups, the distribution score, the similarity combination with its
// normalisation and the adaptive temporal score. Each struct documents its
// defaults; validate() throws InvalidParameter naming the offending field as
// "<member>.<field>", the member name in LoopDetectorOptions.
#pragma once

namespace bowg {

/// Word groups (paper Sec. III-A "Word Group Definition").
struct WordGroupOptions {
  /// Off = pure bag of words (ablation row 1).
  bool enabled = true;
  /// A neighbour joins the group of feature i when its distance is
  /// < radius_scale * size_i. The paper uses the keypoint size itself (1.0).
  double radius_scale = 1.0;
  void validate() const;
};

/// Feature-distribution score (paper Sec. III-C) over m fan bins.
struct DistributionOptions {
  /// Off for generic scenes; on in pipes (the paper disables it on public
  /// datasets).
  bool enabled = false;
  /// m, the number of fan-shaped bins of angle 2*pi/m. >= 1.
  int fan_bins = 8;
  void validate() const;
};

/// Similarity combination (paper eqs. 2-5, 9) and normalisation.
struct SimilarityOptions {
  /// lambda_1: weight of the normalised word score eta_w, in [0, 1].
  double lambda_1 = 0.5;
  /// lambda_2: weight of eta_g when the distribution score is on (eq. 9),
  /// in [0, 1], lambda_1 + lambda_2 <= 1. With the distribution score off,
  /// eq. 5 applies: lambda_1*eta_w + (1 - lambda_1)*eta_g.
  double lambda_2 = 0.3;
  /// Scores are normalised by the score against the previous keyframe
  /// (eta = s(I_t, I_tj) / s(I_t, I_t-1)). Below these minimum normaliser
  /// scores the keyframe yields no loop (DLoopDetector's min_nss_factor).
  double min_word_normaliser = 0.005;
  double min_group_normaliser = 0.005;
  double min_distribution_normaliser = 0.005;
  /// Normaliser floor (docs/method.md, normaliser_history.h): each normaliser
  /// is at least normaliser_floor times the median normaliser of the last
  /// normaliser_window keyframes, so that one unusually dissimilar previous
  /// keyframe cannot lift every score of a query. >= 0; 0 = the paper's
  /// s(I_t, I_t-1) alone (the default; the pipe presets use 1).
  double normaliser_floor = 0.0;
  /// Keyframes in that median, >= 1.
  int normaliser_window = 50;
  /// The normalisers' I_{t-1} in metres driven (docs/method.md): the newest
  /// entry driven at least this far before the query, when the query and
  /// that entry have odometers (else the previous keyframe). The paper's
  /// s(I_t, I_t-1) estimates the score of the same place seen one keyframe
  /// spacing away; a robot that stands still or crawls makes I_t-1 the same
  /// view, the estimate its self-similarity, and every eta of the query
  /// vanishes. In metres it is one estimate whatever the speed and keyframe
  /// spacing. 0 = the previous keyframe always (the paper). >= 0.
  double normaliser_distance_m = 0.0;
  /// Without odometry (the query has no odometer), the normalisers' I_{t-1}
  /// is the newest of the last normaliser_lookback keyframes whose word
  /// score with the query is at most the median s_w(I_t, I_t-1) of the last
  /// normaliser_window keyframes (docs/method.md): where the robot slowed
  /// down, its previous keyframe is nearly the same view and would silence
  /// the query, as normaliser_distance_m prevents with odometry. None of
  /// them (the robot stands still): the previous keyframe. 0 or 1 = the
  /// previous keyframe always (the paper). >= 0.
  int normaliser_lookback = 0;
  /// The lookback starts where s_w(I_t, I_t-1) exceeds this times that
  /// median: a robot that slowed down, not a previous keyframe that happens
  /// to score above the median (half of them do at a constant speed). >= 1.
  double normaliser_lookback_ratio = 1.0;
  void validate() const;
};

/// Adaptive temporal score (paper eqs. 6-7).
struct TemporalScoreOptions {
  bool enabled = true;
  /// w_max: the largest weight the previous query's score can get, [0, 1).
  double w_max = 0.6;
  /// alpha: scale of the score difference in eq. 6, > 0.
  double alpha = 0.2;
  /// r: eq. 7 reads eta(t-1, tj-1), which a true revisit only follows when
  /// both passes advance one keyframe per keyframe (same speed and spacing).
  /// With r > 0 the previous score is the best of the previous query's scores
  /// of entries tj-1-r .. tj-1+r (the best-aligned earlier entry), so a pass
  /// that advances 0 .. 1+r database entries per query (slower, stopped, up
  /// to 1+r times faster) or backs up by up to r-1 still carries its score
  /// (docs/method.md). 0 = eq. 7 exactly. >= 0.
  int alignment_window = 0;
  /// The previous scores survive this many consecutive queries that could
  /// not be scored (no candidate, normaliser too small); the window then
  /// centres on tj-1-missed and widens to r * (1 + missed). 0 = they are
  /// forgotten at the first such query (the paper). >= 0.
  int max_missed_queries = 0;
  /// The aligned window in metres driven, used instead of alignment_window
  /// when the query, the previous scored query and the entries have
  /// odometers: eta(t-1, .) is the best previous score among the entries
  /// whose odometer is within alignment_window_m of odometer(tj) - d, d the
  /// metres the robot drove from the previous scored query to this one. Both
  /// passes drive the same path between two places, whatever their speeds
  /// and keyframe spacings, so this is where tj's predecessor lies
  /// (temporal_alignment.h). 0 = keyframes always. >= 0.
  double alignment_window_m = 0.0;
  void validate() const;
};

}  // namespace bowg
