// One query of the loop detector (query_steps.h), in steps: scores, islands
// with geometric re-ranking, temporal verification, geometric verification.
#include "detection/query_steps.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "bowg/detection/geometric_verification.h"
#include "bowg/detection/islands.h"
#include "bowg/detection/odometry_gate.h"
#include "bowg/scoring/similarity.h"
#include "bowg/scoring/temporal_alignment.h"

namespace bowg {
namespace query_steps {
namespace {

// The number of entries driven up to `odometer`: those whose odometer (an
// entry without one carries the one before it, Database::odometers) is at
// most it. One binary search over the non-decreasing odometers.
std::size_t entriesDrivenUpTo(const Database& database, double odometer) {
  const std::vector<double>& odometers = database.odometers();
  return static_cast<std::size_t>(std::upper_bound(odometers.begin(), odometers.end(), odometer) -
                                  odometers.begin());
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

// True when a normaliser of an enabled component is 0 or below its minimum.
bool lowNormaliser(const Normalisers& tested, const SimilarityOptions& so, bool with_groups,
                   bool with_distribution) {
  const auto low = [](double normaliser, double minimum) {
    return !(normaliser > 0.0) || normaliser < minimum;
  };
  return low(tested.word, so.min_word_normaliser) ||
         (with_groups && low(tested.group, so.min_group_normaliser)) ||
         (with_distribution && low(tested.distribution, so.min_distribution_normaliser));
}

// The query's final scores of every candidate (and the step's outcome): false
// when the query stops before its candidates are scored (database too small,
// low normaliser); `r` then has its status. Updates the temporal memory.
bool scoreCandidates(const QueryContext& ctx, const DatabaseQuery& q,
                     const DatabaseEntry& query_entry, bool with_groups, bool with_distribution,
                     LoopResult* r, std::vector<std::pair<EntryId, double>>* etas) {
  const Database& database = ctx.database;
  const LoopDetectorOptions& options = ctx.options;
  DetectorState& state = ctx.state;
  const auto finish = [&](LoopStatus status) {
    r->status = status;
    recordUnscoredQuery(options, &state);
    return false;
  };
  if (database.size() == 0) return finish(LoopStatus::kDatabaseTooSmall);

  const SimilarityOptions& so = options.similarity;
  // Normalisers (eqs. 2, 4): the same scores against I_{t-1}, the last entry
  // (or the one driven normaliser_distance_m back). They join the history
  // from the first keyframe on, so that the floor has its median ready when
  // the database is large enough to be queried.
  const EntryScores norm = database.score(q, normaliserEntry(database, so, query_entry.odometer));
  const Normalisers previous{norm.s_w, norm.s_g, norm.s_d};
  const Normalisers expected = state.normalisers.median();
  state.normalisers.push(previous, static_cast<std::size_t>(so.normaliser_window));
  r->word_normaliser = norm.s_w;
  r->group_normaliser = with_groups ? norm.s_g : 0.0;
  r->distribution_normaliser = with_distribution ? norm.s_d : 0.0;
  const EntryId limit = candidateLimit(database, options.islands, query_entry.odometer);
  if (limit == 0) return finish(LoopStatus::kDatabaseTooSmall);
  // What eqs. 2 and 4 divide by: s(I_t, I_t-1), raised to the normaliser
  // floor where it is unusually small.
  const Normalisers divisor = flooredNormalisers(previous, expected, so.normaliser_floor);
  // A normaliser of 0 (I_{t-1} shares no word / group / occupied fan bin with
  // I_t) cannot divide eqs. 2 and 4 even when the minimum is set to 0 (a valid
  // value): such a keyframe is always low_normaliser, never inf/NaN scores.
  // Without the floor (the paper) the test reads s(I_t, I_t-1) itself. With
  // it, the floored divisor: a previous keyframe that shares little with this
  // one (keyframes 10-20 cm apart, a jolt, a roll) does not silence the
  // query while the recent keyframes scored normally; an image too poor to
  // score still gets scores too small for any island.
  const Normalisers& tested = so.normaliser_floor > 0.0 ? divisor : previous;
  if (lowNormaliser(tested, so, with_groups, with_distribution)) {
    return finish(LoopStatus::kLowNormaliser);
  }
  r->word_divisor = divisor.word;
  r->group_divisor = with_groups ? divisor.group : 0.0;
  r->distribution_divisor = with_distribution ? divisor.distribution : 0.0;

  const std::vector<EntryScores> scores = database.query(q, limit, with_groups);
  r->candidates_scored = scores.size();
  etas->reserve(scores.size());
  // Eq. 7's predecessor in metres when odometry allows it
  // (TemporalScoreOptions::alignment_window_m), else in keyframes.
  const TemporalScoreOptions& to = options.temporal_score;
  const bool metric_alignment = to.alignment_window_m > 0.0 && !std::isnan(query_entry.odometer) &&
                                !std::isnan(state.previous_odometer);
  const double driven = metric_alignment ? query_entry.odometer - state.previous_odometer : 0.0;
  ctx.candidates.reserve(scores.size());
  // The scores come in ascending entry order: one forward walk of the
  // temporal memory for all of them.
  AlignedPreviousScores aligned =
      metric_alignment ? AlignedPreviousScores(state.previous_etas, database.odometers(), driven,
                                               to.alignment_window_m)
                       : AlignedPreviousScores(state.previous_etas, state.missed_queries, to);
  for (const EntryScores& s : scores) {
    CandidateScores c;
    c.entry = s.entry;
    c.eta_w = normaliseScore(s.s_w, divisor.word);
    c.eta_g = with_groups ? normaliseScore(s.s_g, divisor.group) : 0.0;
    c.eta_d = with_distribution ? normaliseScore(s.s_d, divisor.distribution) : 0.0;
    c.eta_sim =
        combineSimilarity(c.eta_w, c.eta_g, c.eta_d, options.word_groups, options.distribution, so);
    // Eqs. 6-7: eta(t-1, tj-1) is the previous query's final score of the
    // entry before this one (alignment_window 0), or the best-aligned one
    // near it (temporal_alignment.h); 0 when none was scored then.
    c.eta = temporalScore(c.eta_sim, aligned(s.entry), options.temporal_score);
    ctx.candidates.push_back(c);
    etas->emplace_back(c.entry, c.eta);
  }
  state.previous_etas = *etas;  // sorted by entry id, as the scores are
  state.missed_queries = 0;
  state.previous_odometer = query_entry.odometer;
  return true;
}

// What a verification view of a database entry points into: its positions
// unpacked (the database packs them, PackedPoints) and its direct index,
// made from its words.
struct EntryViewStorage {
  std::vector<ImagePoint> points;
  std::vector<WordId> words;
  DirectIndex direct;
};

// The two sides of a geometric verification. The query's direct index is
// built on the first verification only (with one verified candidate most
// queries stop at the temporal check before it), a database entry's for each
// correspondence search with it: the database keeps words, not direct
// indexes. RANSAC on correspondences already found needs none (features()).
class Verifier {
 public:
  Verifier(const QueryContext& ctx, const DatabaseEntry& query, const CameraIntrinsics& k)
      : ctx_(ctx),
        query_(query),
        intrinsics_(k),
        exhaustive_(ctx.options.geometric.exhaustive),
        built_(false) {}

  VerificationView query() {
    if (!built_) {
      unpack(query_, &query_storage_);
      built_ = true;
    }
    return VerificationView{&query_storage_.points, &query_.descriptors, &query_storage_.direct};
  }

  /// Valid until the next call.
  VerificationView match(EntryId id) { return entry(id, &match_storage_); }

  /// Entry `id`'s keypoints and descriptors without a direct index: enough
  /// for RANSAC on correspondences already found (verifyCorrespondences).
  /// Valid until the next call.
  VerificationView features(EntryId id) {
    const DatabaseEntry& m = ctx_.database.entry(id);
    m.points.unpack(&features_points_);
    return VerificationView{&features_points_, &m.descriptors, nullptr};
  }

  /// Entry `id`'s view, its positions and direct index in `storage`.
  VerificationView entry(EntryId id, EntryViewStorage* storage) const {
    const DatabaseEntry& m = ctx_.database.entry(id);
    unpack(m, storage);
    return VerificationView{&storage->points, &m.descriptors, &storage->direct};
  }

  const CameraIntrinsics& intrinsics() const { return intrinsics_; }
  const DatabaseEntry& queryEntry() const { return query_; }

 private:
  void unpack(const DatabaseEntry& e, EntryViewStorage* storage) const {
    e.points.unpack(&storage->points);
    if (!exhaustive_) {
      e.words.unpack(&storage->words);
      storage->direct =
          directIndexFromWords(ctx_.vocabulary, storage->words, ctx_.database.directLevel());
    }
  }

  const QueryContext& ctx_;
  const DatabaseEntry& query_;
  const CameraIntrinsics& intrinsics_;
  EntryViewStorage query_storage_, match_storage_;
  std::vector<ImagePoint> features_points_;
  bool exhaustive_;
  bool built_;
};

// TemporalVerificationOptions::linked_places: whether the chosen island
// (followed[0]) is one place, by accepted loops, with another followed
// island whose chain passes (the chains as they stand before this query's
// update). Then the robot is where that chain says, seen on another lap.
bool continuesLinkedChain(const QueryContext& ctx, const std::vector<Island>& followed,
                          double query_m) {
  const TemporalVerificationOptions& tv = ctx.options.temporal_verification;
  for (std::size_t i = 1; i < followed.size(); ++i) {
    if (ctx.state.consistency.chainTo(followed[i], tv, query_m) > tv.k &&
        ctx.state.place_links.linked(followed[0], followed[i])) {
      return true;
    }
  }
  return false;
}

struct IslandChoice {
  std::size_t chosen = 0;         ///< index into the islands
  GeometricVerificationResult g;  ///< of its best entry, when verified
  bool verified = false;
  /// Its best entry's correspondences when the re-ranking chose it by them
  /// without RANSAC (GeometricVerificationOptions::rerank_ransacs 0); empty
  /// otherwise (a choice by correspondences has at least min_inliers >= 8).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  double rerank_ms = 0;
};

// Geometric re-ranking (GeometricVerificationOptions::candidates): the
// query's island is the one of the top `candidates` whose best entry has the
// most inliers (ties: the better-scored island), among those with at least
// min_inliers correspondences: only they can be loops. When none has that
// many, or with 1 candidate, it is the best-scored island, verified after the
// temporal verification (the paper). The correspondences are cheap; RANSAC
// is the cost, and in an aliased pipe most queries have no candidate that
// could pass: RANSAC runs on at most `rerank_ransacs` candidates, those with
// the most correspondences (0: the one with the most correspondences is
// chosen, and verified only if it passes the temporal verification).
IslandChoice chooseIsland(const std::vector<Island>& islands,
                          const GeometricVerificationOptions& go, Verifier* verifier) {
  IslandChoice c;
  const std::size_t reranked =
      go.enabled ? std::min(islands.size(), static_cast<std::size_t>(go.candidates)) : 1;
  if (reranked <= 1) return c;
  const auto t_rerank = Clock::now();
  const VerificationView qv = verifier->query();
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> pairs(reranked);
  std::vector<std::size_t> order(reranked);
  for (std::size_t i = 0; i < reranked; ++i) {
    pairs[i] = findCorrespondences(qv, verifier->match(islands[i].best_entry), go);
    order[i] = i;
  }
  // RANSAC (the cost) in decreasing number of correspondences. Inliers are a
  // subset of the correspondences, so once a candidate has fewer
  // correspondences than min_inliers (it cannot be a loop) or than the best
  // inlier count so far (or as many, and a worse score: ties go to the
  // better-scored island), neither it nor any later one can win: the choice
  // is the one of trying every candidate that could be a loop.
  std::stable_sort(order.begin(), order.end(), [&pairs](std::size_t a, std::size_t b) {
    return pairs[a].size() > pairs[b].size();
  });
  if (go.rerank_ransacs == 0) {
    if (static_cast<int>(pairs[order[0]].size()) >= go.min_inliers) {
      c.chosen = order[0];
      c.pairs = std::move(pairs[order[0]]);
    }
    c.rerank_ms = msBetween(t_rerank, Clock::now());
    return c;
  }
  bool have = false;
  int ransacs = 0;
  for (const std::size_t i : order) {
    const int n = static_cast<int>(pairs[i].size());
    if (n < go.min_inliers || (have && n < c.g.inliers)) break;
    if (have && n == c.g.inliers && i > c.chosen) continue;
    if (ransacs == go.rerank_ransacs) break;
    ++ransacs;
    // After a loop, only a model with more inliers (as many, for a
    // better-scored island) changes the choice: RANSAC's samples are
    // bounded for that count (GeometricVerificationOptions::
    // ransac_bound_confidence).
    const int decisive =
        have && c.g.inliers >= go.min_inliers ? c.g.inliers + (i < c.chosen ? 0 : 1) : 0;
    // No intrinsics: the relative pose (an essential matrix) is only worth
    // its cost for the loop, once it is accepted (verifyMatch).
    GeometricVerificationResult gi = verifyCorrespondences(
        pairs[i], qv, verifier->features(islands[i].best_entry), CameraIntrinsics(), go, decisive);
    if (!have || gi.inliers > c.g.inliers || (gi.inliers == c.g.inliers && i < c.chosen)) {
      c.g = std::move(gi);
      c.chosen = i;
      have = true;
    }
  }
  c.verified = have;
  c.rerank_ms = msBetween(t_rerank, Clock::now());
  return c;
}

// The loop's translation in metres from the odometer between the match and
// a neighbour of it (metric_translation.h); the PnP pose replaces the
// essential matrix's so that rotation and translation belong together. An
// estimate longer than the odometry allows between the two keyframes (by
// the gates' own assumptions: odometryDistanceBound, `anchors` as the
// loop-anchored gate read them) is not published.
void estimateScale(const QueryContext& ctx, const Verifier& verifier,
                   const std::vector<AnchorEntries>& anchors, LoopResult* r) {
  const MetricTranslationOptions& mo = ctx.options.metric;
  if (!r->has_relative_pose) return;
  if (!mo.enabled) {
    r->metric_status = MetricTranslationStatus::kDisabled;
    return;
  }
  const auto& entries = ctx.database.entries();
  if (!std::isfinite(entries[r->match_id].odometer)) {
    r->metric_status = MetricTranslationStatus::kNoOdometry;
    return;
  }
  const std::vector<EntryId> ids = chooseScaleNeighbours(entries, r->match_id, mo);
  if (ids.empty()) {
    r->metric_status = MetricTranslationStatus::kNoNeighbour;
    return;
  }
  const DatabaseEntry& m = entries[r->match_id];
  EntryViewStorage match_storage;
  std::vector<EntryViewStorage> storage(ids.size());
  std::vector<ScaleNeighbour> neighbours(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    neighbours[i].view = verifier.entry(ids[i], &storage[i]);
    neighbours[i].baseline_m = std::fabs(entries[ids[i]].odometer - m.odometer);
  }
  const MetricTranslation t = estimateMetricTranslation(
      r->inlier_correspondences, verifier.intrinsics(), verifier.entry(r->match_id, &match_storage),
      neighbours, m.intrinsics, ctx.options.geometric, mo);
  r->metric_status = t.status;
  if (t.status != MetricTranslationStatus::kEstimated) return;
  const double norm =
      std::sqrt(t.translation[0] * t.translation[0] + t.translation[1] * t.translation[1] +
                t.translation[2] * t.translation[2]);
  if (!(norm <= odometryDistanceBound(verifier.queryEntry(), m, anchors, ctx.options.islands))) {
    r->metric_status = MetricTranslationStatus::kOutsideOdometry;
    return;
  }
  r->translation_scale_known = true;
  std::copy(t.translation, t.translation + 3, r->translation_m);
  std::copy(t.covariance, t.covariance + 9, r->translation_covariance);
  std::copy(t.rotation, t.rotation + 9, r->rotation);
  if (norm > 0) {
    for (int i = 0; i < 3; ++i) r->translation_direction[i] = t.translation[i] / norm;
  }
}

// Geometric verification of the best entry of the chosen island (done
// already when re-ranking); the loop, its relative pose and its scale.
void verifyMatch(const QueryContext& ctx, const Island& island, IslandChoice* choice,
                 Verifier* verifier, const std::vector<AnchorEntries>& anchors,
                 Clock::time_point t_verify, LoopResult* r) {
  const GeometricVerificationOptions& go = ctx.options.geometric;
  const DatabaseEntry& match = ctx.database.entry(island.best_entry);
  r->match_id = match.id;
  r->match_stamp = match.stamp;
  if (!go.enabled) {
    r->status = LoopStatus::kLoopDetected;
    return;
  }
  GeometricVerificationResult& g = choice->g;
  if (!choice->pairs.empty()) {
    g = verifyCorrespondences(choice->pairs, verifier->query(),
                              verifier->features(island.best_entry), verifier->intrinsics(), go);
  } else if (!choice->verified) {
    g = verifyGeometry(verifier->query(), verifier->match(island.best_entry),
                       verifier->intrinsics(), go);
  }
  r->timings.verification_ms = choice->rerank_ms + msBetween(t_verify, Clock::now());
  r->status = g.status;
  r->correspondences = g.correspondences;
  r->inliers = g.inliers;
  if (g.status != LoopStatus::kLoopDetected) {
    r->match_id = 0;
    r->match_stamp = 0;
    return;
  }
  if (!g.has_relative_pose && verifier->intrinsics().valid) {
    g.has_relative_pose = relativePoseFromCorrespondences(
        g.inlier_correspondences, verifier->intrinsics(), go.ransac_threshold_px,
        go.ransac_confidence, g.rotation, g.translation_direction);
  }
  r->inlier_correspondences = std::move(g.inlier_correspondences);
  r->has_relative_pose = g.has_relative_pose;
  std::copy(g.rotation, g.rotation + 9, r->rotation);
  std::copy(g.translation_direction, g.translation_direction + 3, r->translation_direction);
  estimateScale(ctx, *verifier, anchors, r);
  r->timings.verification_ms = choice->rerank_ms + msBetween(t_verify, Clock::now());
}

}  // namespace

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

void runQuery(const QueryContext& ctx, const DatabaseQuery& q, const DatabaseEntry& query_entry,
              const CameraIntrinsics& intrinsics, bool with_groups, bool with_distribution,
              LoopResult* r) {
  const LoopDetectorOptions& options = ctx.options;
  const auto t_query = Clock::now();
  std::vector<std::pair<EntryId, double>> etas;
  const bool scored =
      scoreCandidates(ctx, q, query_entry, with_groups, with_distribution, r, &etas);
  const auto t_islands = Clock::now();
  r->timings.query_ms = msBetween(t_query, t_islands);
  if (!scored) return;
  if (etas.empty()) {
    r->status = LoopStatus::kNoCandidates;
    recordUnscoredQuery(options, &ctx.state);
    return;
  }
  r->has_candidate = true;
  r->best = *std::max_element(
      ctx.candidates.begin(), ctx.candidates.end(),
      [](const CandidateScores& a, const CandidateScores& b) { return a.eta < b.eta; });

  // The odometry gates: candidates above the threshold where the odometry
  // says the robot cannot be are not candidates (the temporal memory above
  // keeps their scores: the gates judge places, not the score's history).
  const IslandOptions& io = options.islands;
  std::vector<AnchorEntries> anchors;
  if (io.odometry_anchor_m > 0.0) {
    for (const LoopAnchor& a : ctx.state.recent_loops) {
      if (a.query < ctx.database.size() && a.match < ctx.database.size()) {
        anchors.push_back(
            AnchorEntries{&ctx.database.entry(a.query), &ctx.database.entry(a.match)});
      }
    }
  }
  const bool anchored = !anchors.empty();
  if (io.odometry_gate_m > 0.0 || anchored) {
    const auto outside = [&](const std::pair<EntryId, double>& c) {
      if (c.second < io.min_score) return false;
      const DatabaseEntry& e = ctx.database.entry(c.first);
      return !withinOdometryGate(query_entry, e, io) ||
             (anchored && !withinLoopAnchors(query_entry, e, anchors, io));
    };
    const auto end = std::remove_if(etas.begin(), etas.end(), outside);
    r->candidates_gated = static_cast<std::size_t>(etas.end() - end);
    etas.erase(end, etas.end());
  }
  // Islands (Sec. III-D, eq. 10) and temporal verification.
  std::vector<Island> islands = computeIslands(std::move(etas), options.islands);
  for (Island& i : islands) {
    i.first_m = ctx.database.entry(i.first).odometer;
    i.last_m = ctx.database.entry(i.last).odometer;
  }
  if (islands.empty()) {
    r->status = LoopStatus::kNoScoreAboveThreshold;
    ctx.state.consistency.miss(options.temporal_verification);
    r->timings.islands_ms = msBetween(t_islands, Clock::now());
    return;
  }
  Verifier verifier(ctx, query_entry, intrinsics);
  IslandChoice choice = chooseIsland(islands, options.geometric, &verifier);
  const Island& island = islands[choice.chosen];
  r->island_first = island.first;
  r->island_last = island.last;
  r->island_score = island.score;
  const auto it =
      std::lower_bound(ctx.candidates.begin(), ctx.candidates.end(), island.best_entry,
                       [](const CandidateScores& c, EntryId id) { return c.entry < id; });
  if (it != ctx.candidates.end() && it->entry == island.best_entry) r->best = *it;
  // The followed hypotheses (TemporalVerificationOptions::hypotheses): the
  // chosen island first, then the best-scored others.
  std::vector<Island> followed{island};
  const std::size_t wanted = static_cast<std::size_t>(options.temporal_verification.hypotheses);
  for (std::size_t i = 0; i < islands.size() && followed.size() < wanted; ++i) {
    if (i != choice.chosen) followed.push_back(islands[i]);
  }
  const TemporalVerificationOptions& tv = options.temporal_verification;
  const bool linked = tv.linked_places && continuesLinkedChain(ctx, followed, query_entry.odometer);
  const bool anchored_chain =
      tv.anchored_chain && anchored &&
      anchoredByRecentLoop(query_entry, ctx.database.entry(island.best_entry), anchors, io);
  const bool consistent = ctx.state.consistency.update(followed, 0, tv, query_entry.odometer) ||
                          linked || anchored_chain;
  const auto t_verify = Clock::now();
  r->timings.islands_ms = msBetween(t_islands, t_verify) - choice.rerank_ms;
  r->timings.verification_ms = choice.rerank_ms;
  if (!consistent) {
    r->status = LoopStatus::kNoTemporalConsistency;
    return;
  }
  verifyMatch(ctx, island, &choice, &verifier, anchors, t_verify, r);
  if (r->status == LoopStatus::kLoopDetected) {
    ctx.state.place_links.link(r->query_id, r->match_id);
    std::vector<LoopAnchor>& recent = ctx.state.recent_loops;
    if (recent.size() == kLoopAnchors) recent.erase(recent.begin());
    recent.push_back(LoopAnchor{r->query_id, r->match_id});
  }
}

}  // namespace query_steps
}  // namespace bowg
