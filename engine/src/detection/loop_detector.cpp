// LoopDetector::process: the per-keyframe pipeline of the paper (Fig. 2,
// Sec. III-B/C/D). The file format and the reading/writing live in detector_file.cpp
// (saveDetectorFile / loadDetectorFile); save() and load() wrap them.
#include "bowg/detection/loop_detector.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "bowg/core/errors.h"
#include "bowg/database/database.h"
#include "bowg/detection/detector_file.h"
#include "bowg/detection/geometric_verification.h"
#include "bowg/detection/islands.h"
#include "bowg/scoring/similarity.h"
#include "bowg/scoring/temporal_alignment.h"
#include "bowg/scoring/word_groups.h"
#include "bowg/vocabulary/vocabulary.h"

namespace bowg {
namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Centre of the distribution fan (Sec. III-C): the principal point when the
// intrinsics are known, else the image centre, else (image size unknown) the
// centre of the keypoints' bounding box.
void fanCentre(const KeyframeInput& kf, double* cx, double* cy) {
  if (kf.intrinsics.valid) {
    *cx = kf.intrinsics.cx;
    *cy = kf.intrinsics.cy;
  } else if (kf.features.image_width > 0 && kf.features.image_height > 0) {
    *cx = 0.5 * kf.features.image_width;
    *cy = 0.5 * kf.features.image_height;
  } else if (!kf.features.keypoints.empty()) {
    float x0 = kf.features.keypoints[0].x, x1 = x0, y0 = kf.features.keypoints[0].y, y1 = y0;
    for (const auto& k : kf.features.keypoints) {
      x0 = std::min(x0, k.x);
      x1 = std::max(x1, k.x);
      y0 = std::min(y0, k.y);
      y1 = std::max(y1, k.y);
    }
    *cx = 0.5 * (x0 + x1);
    *cy = 0.5 * (y0 + y1);
  } else {
    *cx = *cy = 0.0;
  }
}

// A query that cannot be scored (no features, database too small, normaliser
// too small, no candidate): eq. 7's previous scores survive up to
// temporal_score.max_missed_queries such queries and the temporal chain up to
// temporal_verification.max_missed_queries (0 = the paper: forgotten at once).
void recordUnscoredQuery(const LoopDetectorOptions& options, DetectorState* state) {
  if (state->missed_queries < options.temporal_score.max_missed_queries &&
      !state->previous_etas.empty()) {
    ++state->missed_queries;
  } else {
    state->previous_etas.clear();
    state->missed_queries = 0;
    state->previous_odometer = std::numeric_limits<double>::quiet_NaN();
  }
  state->consistency.miss(options.temporal_verification);
}

// The number of entries driven up to `odometer`: those whose odometer (an
// entry without one carries the one before it, Database::odometers) is at
// most it. One binary search over the non-decreasing odometers.
std::size_t entriesDrivenUpTo(const Database& database, double odometer) {
  const std::vector<double>& odometers = database.odometers();
  return static_cast<std::size_t>(
      std::upper_bound(odometers.begin(), odometers.end(), odometer) - odometers.begin());
}

// Entries with id < the returned limit may be candidates. In keyframes: all
// but the `recent_exclusion` newest. In metres (the query has an odometer and
// recent_exclusion_m > 0): the entries before the newest one driven at least
// recent_exclusion_m before the query; entries without an odometer there are
// treated as recent.
EntryId candidateLimit(const Database& database, const IslandOptions& options, double odometer) {
  const std::size_t n = database.size();
  if (std::isnan(odometer) || !(options.recent_exclusion_m > 0.0)) {
    const std::size_t excluded = static_cast<std::size_t>(options.recent_exclusion);
    return static_cast<EntryId>(n > excluded ? n - excluded : 0);
  }
  // The non-decreasing odometers find the entries driven far enough back;
  // those at the end of that range without an odometer of their own carry
  // the one before them and are dropped.
  std::size_t limit = entriesDrivenUpTo(database, odometer - options.recent_exclusion_m);
  while (limit > 0 && std::isnan(database.entries()[limit - 1].odometer)) --limit;
  return static_cast<EntryId>(limit);
}

// The normalisers' I_{t-1} (SimilarityOptions::normaliser_distance_m): the
// newest entry driven at least that far before the query, when both have
// odometers; else the previous keyframe (the paper).
EntryId normaliserEntry(const Database& database, const SimilarityOptions& options,
                        double odometer) {
  const EntryId previous = static_cast<EntryId>(database.size() - 1);
  if (std::isnan(odometer) || !(options.normaliser_distance_m > 0.0)) return previous;
  const std::size_t behind = entriesDrivenUpTo(database, odometer - options.normaliser_distance_m);
  if (behind == 0 || std::isnan(database.entries()[behind - 1].odometer)) return previous;
  return static_cast<EntryId>(behind - 1);
}

struct QueryContext {
  const Vocabulary& vocabulary;
  const LoopDetectorOptions& options;
  const Database& database;
  DetectorState& state;
  std::vector<CandidateScores>& candidates;
};

// Steps after the query's vectors are ready: normalisers, candidate scores,
// temporal score, islands, temporal and geometric verification. Fills `r`.
void runQuery(const QueryContext& ctx, const DatabaseQuery& q, const DatabaseEntry& query_entry,
              const CameraIntrinsics& intrinsics, bool with_groups, bool with_distribution,
              LoopResult* r) {
  const Database* database_ = &ctx.database;
  const LoopDetectorOptions& options_ = ctx.options;
  DetectorState* state_ = &ctx.state;
  std::vector<CandidateScores>& last_candidates_ = ctx.candidates;
  const Vocabulary* vocabulary_ = &ctx.vocabulary;
  const auto t_query = Clock::now();
  const std::size_t n = database_->size();
  auto finish = [&](LoopStatus status) {
    r->status = status;
    recordUnscoredQuery(options_, state_);
  };
  if (n == 0) {
    finish(LoopStatus::kDatabaseTooSmall);
    r->timings.query_ms = msBetween(t_query, Clock::now());
    return;
  }

  const SimilarityOptions& so = options_.similarity;
  // Normalisers (eqs. 2, 4): the same scores against I_{t-1}, the last entry
  // (or the one driven normaliser_distance_m back). They join the history
  // from the first keyframe on, so that the floor has its median ready when
  // the database is large enough to be queried.
  const EntryScores norm =
      database_->score(q, normaliserEntry(*database_, so, query_entry.odometer));
  const Normalisers previous{norm.s_w, norm.s_g, norm.s_d};
  const Normalisers expected = state_->normalisers.median();
  state_->normalisers.push(previous, static_cast<std::size_t>(so.normaliser_window));
  r->word_normaliser = norm.s_w;
  r->group_normaliser = with_groups ? norm.s_g : 0.0;
  r->distribution_normaliser = with_distribution ? norm.s_d : 0.0;
  const EntryId limit = candidateLimit(*database_, options_.islands, query_entry.odometer);
  if (limit == 0) {
    finish(LoopStatus::kDatabaseTooSmall);
    r->timings.query_ms = msBetween(t_query, Clock::now());
    return;
  }
  // What eqs. 2 and 4 divide by: s(I_t, I_t-1), raised to the normaliser
  // floor where it is unusually small.
  const Normalisers divisor = flooredNormalisers(previous, expected, so.normaliser_floor);
  // A normaliser of 0 (I_{t-1} shares no word / group / occupied fan bin with
  // I_t) cannot divide eqs. 2 and 4 even when the minimum is set to 0 (a valid
  // value): such a keyframe is always low_normaliser, never inf/NaN scores.
  // Without the floor (the paper) the test reads s(I_t, I_t-1) itself. With
  // it, the floored divisor: a previous keyframe that shares little with this
  // one (keyframes 10-20 cm apart, a jolt, a roll) no longer silences the
  // query while the recent keyframes scored normally; an image too poor to
  // score still gets scores too small for any island.
  const Normalisers& tested = so.normaliser_floor > 0.0 ? divisor : previous;
  const auto low = [](double normaliser, double minimum) {
    return !(normaliser > 0.0) || normaliser < minimum;
  };
  if (low(tested.word, so.min_word_normaliser) ||
      (with_groups && low(tested.group, so.min_group_normaliser)) ||
      (with_distribution && low(tested.distribution, so.min_distribution_normaliser))) {
    finish(LoopStatus::kLowNormaliser);
    r->timings.query_ms = msBetween(t_query, Clock::now());
    return;
  }
  r->word_divisor = divisor.word;
  r->group_divisor = with_groups ? divisor.group : 0.0;
  r->distribution_divisor = with_distribution ? divisor.distribution : 0.0;

  const std::vector<EntryScores> scores = database_->query(q, limit, with_groups);
  r->candidates_scored = scores.size();
  std::vector<std::pair<EntryId, double>> etas;
  etas.reserve(scores.size());
  // Eq. 7's predecessor in metres when odometry allows it (options.h,
  // alignment_window_m), else in keyframes.
  const TemporalScoreOptions& to = options_.temporal_score;
  const bool metric_alignment = to.alignment_window_m > 0.0 &&
                                !std::isnan(query_entry.odometer) &&
                                !std::isnan(state_->previous_odometer);
  const double driven = metric_alignment ? query_entry.odometer - state_->previous_odometer : 0.0;
  last_candidates_.reserve(scores.size());
  for (const EntryScores& s : scores) {
    CandidateScores c;
    c.entry = s.entry;
    c.eta_w = normaliseScore(s.s_w, divisor.word);
    c.eta_g = with_groups ? normaliseScore(s.s_g, divisor.group) : 0.0;
    c.eta_d = with_distribution ? normaliseScore(s.s_d, divisor.distribution) : 0.0;
    c.eta_sim = combineSimilarity(c.eta_w, c.eta_g, c.eta_d, options_.word_groups,
                                  options_.distribution, so);
    // Eqs. 6-7: eta(t-1, tj-1) is the previous query's final score of the
    // entry before this one (alignment_window 0), or the best-aligned one
    // near it (temporal_alignment.h); 0 when none was scored then.
    const double eta_prev =
        metric_alignment
            ? alignedPreviousScoreInMetres(state_->previous_etas, database_->odometers(), s.entry,
                                           driven, to.alignment_window_m)
            : alignedPreviousScore(state_->previous_etas, s.entry, state_->missed_queries, to);
    c.eta = temporalScore(c.eta_sim, eta_prev, options_.temporal_score);
    last_candidates_.push_back(c);
    etas.emplace_back(c.entry, c.eta);
  }
  state_->previous_etas = etas;  // sorted by entry id, as the scores are
  state_->missed_queries = 0;
  state_->previous_odometer = query_entry.odometer;
  const auto t_islands = Clock::now();
  r->timings.query_ms = msBetween(t_query, t_islands);

  if (scores.empty()) {
    finish(LoopStatus::kNoCandidates);
    return;
  }
  r->has_candidate = true;
  r->best = *std::max_element(
      last_candidates_.begin(), last_candidates_.end(),
      [](const CandidateScores& a, const CandidateScores& b) { return a.eta < b.eta; });

  // Islands (Sec. III-D, eq. 10) and temporal verification.
  std::vector<Island> islands = computeIslands(etas, options_.islands);
  for (Island& i : islands) {
    i.first_m = database_->entry(i.first).odometer;
    i.last_m = database_->entry(i.last).odometer;
  }
  if (islands.empty()) {
    r->status = LoopStatus::kNoScoreAboveThreshold;
    state_->consistency.miss(options_.temporal_verification);
    r->timings.islands_ms = msBetween(t_islands, Clock::now());
    return;
  }
  const GeometricVerificationOptions& go = options_.geometric;
  // The query's direct index is built on the first verification only: with
  // one verified candidate most queries stop at the temporal check before it.
  DirectIndex query_direct;
  bool query_direct_built = go.exhaustive;
  const auto queryView = [&]() {
    if (!query_direct_built) {
      query_direct = directIndexFromWords(*vocabulary_, query_entry.words, database_->directLevel());
      query_direct_built = true;
    }
    return VerificationView{&query_entry.keypoints, &query_entry.descriptors, &query_direct};
  };
  const auto matchView = [database_](EntryId id) {
    const DatabaseEntry& m = database_->entry(id);
    return VerificationView{&m.keypoints, &m.descriptors, &m.direct};
  };

  // Geometric re-ranking (options.h, GeometricVerificationOptions::candidates):
  // the query's island is the one of the top `candidates` whose best entry has
  // the most inliers (ties: the better-scored island). With 1 it is the best-
  // scored island, verified after the temporal verification (the paper).
  std::size_t chosen = 0;
  GeometricVerificationResult g;
  bool verified = false;
  const std::size_t reranked =
      go.enabled ? std::min(islands.size(), static_cast<std::size_t>(go.candidates)) : 1;
  double rerank_ms = 0;
  if (reranked > 1) {
    const auto t_rerank = Clock::now();
    const VerificationView qv = queryView();
    for (std::size_t i = 0; i < reranked; ++i) {
      const VerificationView mv = matchView(islands[i].best_entry);
      const auto pairs = findCorrespondences(qv, mv, go);
      // Inliers are a subset of the correspondences: a candidate with no
      // more correspondences than the best inlier count so far cannot win,
      // so its RANSAC is skipped (the choice is the same).
      if (i > 0 && static_cast<int>(pairs.size()) <= g.inliers) continue;
      GeometricVerificationResult gi = verifyCorrespondences(pairs, qv, mv, intrinsics, go);
      if (i == 0 || gi.inliers > g.inliers) {
        g = std::move(gi);
        chosen = i;
      }
    }
    verified = true;
    rerank_ms = msBetween(t_rerank, Clock::now());
  }
  const Island& island = islands[chosen];
  r->island_first = island.first;
  r->island_last = island.last;
  r->island_score = island.score;
  const auto it =
      std::lower_bound(last_candidates_.begin(), last_candidates_.end(), island.best_entry,
                       [](const CandidateScores& c, EntryId id) { return c.entry < id; });
  if (it != last_candidates_.end() && it->entry == island.best_entry) r->best = *it;
  // The followed hypotheses (TemporalVerificationOptions::hypotheses): the
  // chosen island first, then the best-scored others.
  std::vector<Island> followed{island};
  const std::size_t wanted = static_cast<std::size_t>(options_.temporal_verification.hypotheses);
  for (std::size_t i = 0; i < islands.size() && followed.size() < wanted; ++i) {
    if (i != chosen) followed.push_back(islands[i]);
  }
  const bool consistent = state_->consistency.update(followed, 0, options_.temporal_verification,
                                                     query_entry.odometer);
  const auto t_verify = Clock::now();
  r->timings.islands_ms = msBetween(t_islands, t_verify) - rerank_ms;
  r->timings.verification_ms = rerank_ms;
  if (!consistent) {
    r->status = LoopStatus::kNoTemporalConsistency;
    return;
  }

  // Geometric verification of the best entry of the chosen island.
  const DatabaseEntry& match = database_->entry(island.best_entry);
  r->match_id = match.id;
  r->match_stamp = match.stamp;
  if (!go.enabled) {
    r->status = LoopStatus::kLoopDetected;
    return;
  }
  if (!verified) g = verifyGeometry(queryView(), matchView(island.best_entry), intrinsics, go);
  r->timings.verification_ms = rerank_ms + msBetween(t_verify, Clock::now());
  r->status = g.status;
  r->correspondences = g.correspondences;
  r->inliers = g.inliers;
  if (g.status != LoopStatus::kLoopDetected) {
    r->match_id = 0;
    r->match_stamp = 0;
    return;
  }
  r->inlier_correspondences = std::move(g.inlier_correspondences);
  r->has_relative_pose = g.has_relative_pose;
  std::copy(g.rotation, g.rotation + 9, r->rotation);
  std::copy(g.translation_direction, g.translation_direction + 3, r->translation_direction);
}

}  // namespace

struct LoopDetector::State : DetectorState {};

LoopDetector::LoopDetector(std::shared_ptr<const Vocabulary> vocabulary,
                           const LoopDetectorOptions& options)
    : vocabulary_(std::move(vocabulary)), options_(options), state_(new State) {
  if (!vocabulary_ || vocabulary_->empty()) {
    throw InvalidParameter("LoopDetector: the vocabulary is null or empty");
  }
  options_.validate();
  database_.reset(new Database(vocabulary_, options_.scoring, options_.geometric.direct_index_level,
                               options_.distribution.fan_bins));
}

LoopDetector::~LoopDetector() = default;

void LoopDetector::setOptions(const LoopDetectorOptions& options) {
  options.validate();
  options_ = options;
  // Only what depends on a changed value is rebuilt (see Database).
  database_->setScoring(options_.scoring);
  database_->setDirectLevel(options_.geometric.direct_index_level);
  database_->setFanBins(options_.distribution.fan_bins);
}

void LoopDetector::save(const std::string& path) const {
  saveDetectorFile(path, *database_, *state_);
}

void LoopDetector::load(const std::string& path) {
  // Built aside; swapped in only when the whole file was read and checked.
  DetectorState loaded_state;
  std::unique_ptr<Database> loaded =
      loadDetectorFile(path, vocabulary_, options_.scoring, options_.geometric.direct_index_level,
                       options_.distribution.fan_bins, &loaded_state);
  std::unique_ptr<State> new_state(new State);
  static_cast<DetectorState&>(*new_state) = std::move(loaded_state);
  database_.swap(loaded);
  state_.swap(new_state);
  last_candidates_.clear();
}

void LoopDetector::reset() {
  database_->clear();
  state_.reset(new State);
  last_candidates_.clear();
}

LoopResult LoopDetector::process(const KeyframeInput& keyframe) {
  const auto t0 = Clock::now();
  const ImageFeatures& f = keyframe.features;
  if (f.keypoints.size() != f.descriptors.size()) {
    throw std::invalid_argument("LoopDetector::process: keyframe.features has " +
                                std::to_string(f.keypoints.size()) + " keypoints but " +
                                std::to_string(f.descriptors.size()) + " descriptors");
  }
  if (!std::isfinite(keyframe.stamp)) {
    throw std::invalid_argument("LoopDetector::process: keyframe.stamp is not finite");
  }
  if (!std::isnan(keyframe.odometer)) {
    if (!std::isfinite(keyframe.odometer) || keyframe.odometer < 0.0) {
      throw std::invalid_argument("LoopDetector::process: keyframe.odometer must be NaN "
                                  "(unknown) or finite >= 0");
    }
    const double last = database_->lastOdometer();
    if (keyframe.odometer < last) {
      throw std::invalid_argument("LoopDetector::process: keyframe.odometer " +
                                  std::to_string(keyframe.odometer) + " decreases (last " +
                                  std::to_string(last) + ")");
    }
  }
  if (!database_->empty() && !(keyframe.stamp > database_->entries().back().stamp)) {
    throw std::invalid_argument("LoopDetector::process: keyframe.stamp " +
                                std::to_string(keyframe.stamp) + " does not increase (last stamp " +
                                std::to_string(database_->entries().back().stamp) + ")");
  }

  LoopResult r;
  r.query_id = static_cast<EntryId>(database_->size());
  r.stamp = keyframe.stamp;
  last_candidates_.clear();

  DatabaseEntry entry;
  entry.stamp = keyframe.stamp;
  entry.keypoints = f.keypoints;
  entry.descriptors = f.descriptors;
  entry.intrinsics = keyframe.intrinsics;
  entry.odometer = keyframe.odometer;
  fanCentre(keyframe, &entry.centre_x, &entry.centre_y);

  if (f.empty()) {
    // Added anyway so that entry ids stay aligned with keyframe indices.
    database_->add(std::move(entry));
    recordUnscoredQuery(options_, state_.get());
    r.status = LoopStatus::kNoFeatures;
    r.timings.total_ms = msBetween(t0, Clock::now());
    return r;
  }

  // 1. Words (Sec. III-A "Word Vocabulary Tree").
  BowVector bow;
  vocabulary_->transform(f.descriptors, &bow, nullptr, 0, &entry.words);
  const auto t1 = Clock::now();
  r.timings.transform_ms = msBetween(t0, t1);

  // 2. Raw word groups, computed even when the ablation switch turns groups
  // off so that switching them on later finds every entry grouped; 3. they
  // join the table BEFORE eq. 1 is applied to the query (finite IDF for the
  // query's own groups); 4. refined weights.
  entry.raw_groups = buildWordGroups(f.keypoints, entry.words, options_.word_groups);
  database_->addToGroupTable(entry.raw_groups);
  const bool with_groups = options_.word_groups.enabled;
  const bool with_distribution = options_.distribution.enabled;
  const DatabaseQuery q = database_->makeQuery(bow, entry.raw_groups, f.keypoints, entry.centre_x,
                                               entry.centre_y, with_distribution);
  entry.bow = std::move(bow);
  const auto t2 = Clock::now();
  r.timings.word_groups_ms = msBetween(t1, t2);

  // 5. Query, then the entry joins the indexes (it never matches itself).
  const QueryContext ctx{*vocabulary_, options_, *database_, *state_, last_candidates_};
  try {
    runQuery(ctx, q, entry, keyframe.intrinsics, with_groups, with_distribution, &r);
  } catch (...) {
    // The raw groups are already in the table: add the entry anyway so that
    // the table, the indexes and the keyframe ids stay consistent.
    database_->add(std::move(entry));
    throw;
  }
  database_->add(std::move(entry));
  r.timings.total_ms = msBetween(t0, Clock::now());
  return r;
}

}  // namespace bowg
