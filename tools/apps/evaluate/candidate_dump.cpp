// --dump-candidates (candidate_dump.h).
#include "candidate_dump.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>

#include "bowg/core/atomic_file.h"
#include "bowg/detection/loop_detector.h"
#include "console_output.h"

namespace bowg {
namespace evaluate_app {

using namespace bowg::eval;

// --dump-candidates: where the true revisit ranks among the candidates under
// each score of the method (paper eqs. 2, 4, 5/9, 7 and the distribution
// score), so that one sees which score separates revisits from look-alikes.
// Rank 1 = the best true match has the highest score of all candidates; 0 =
// no true match among the candidates (outside the database or sharing nothing).
namespace {

const char* const kScoreNames[] = {"eta_w", "eta_g", "eta_d", "eta_sim", "eta"};

// Where the best true match of query `query` ranks under each score: rank 1 =
// it has the highest score of all candidates; 0 = no true match among the
// candidates. Also the best true and the best false final score eta.
struct QueryRanks {
  int rank[5] = {0, 0, 0, 0, 0};
  double best_true = -1, best_false = -1;
};

QueryRanks rankTrueMatch(const std::vector<CandidateScores>& c, const GroundTruth& gt, int query) {
  QueryRanks q;
  for (int s = 0; s < 5; ++s) {
    auto value = [s](const CandidateScores& x) {
      return s == 0 ? x.eta_w : s == 1 ? x.eta_g : s == 2 ? x.eta_d : s == 3 ? x.eta_sim : x.eta;
    };
    double true_best = -std::numeric_limits<double>::infinity();
    bool found = false;
    for (const CandidateScores& x : c) {
      if (gt.contains(query, static_cast<int>(x.entry))) {
        true_best = std::max(true_best, value(x));
        found = true;
      }
    }
    if (!found) continue;
    int better = 0;
    for (const CandidateScores& x : c) {
      if (!gt.contains(query, static_cast<int>(x.entry)) && value(x) > true_best) ++better;
    }
    q.rank[s] = better + 1;
    if (s == 4) {
      q.best_true = true_best;
      for (const CandidateScores& x : c) {
        if (!gt.contains(query, static_cast<int>(x.entry)))
          q.best_false = std::max(q.best_false, x.eta);
      }
    }
  }
  return q;
}

// Quantiles of the features and normalisers, then top-1/5/20 per score.
void printRankTable(const std::vector<double>& feature_counts, const std::vector<double>& word_norm,
                    const std::vector<double>& group_norm, const std::vector<double>& dist_norm,
                    const std::vector<std::vector<int>>& ranks) {
  const char* const* names = kScoreNames;
  auto quantiles = [](std::vector<double> v) {
    if (v.empty()) return std::string("-");
    std::sort(v.begin(), v.end());
    auto q = [&v](double f) { return v[static_cast<std::size_t>(f * (v.size() - 1))]; };
    return fmt("%.4g / %.4g / %.4g / %.4g", q(0.05), q(0.25), q(0.5), q(0.95));
  };
  std::printf("features per frame (p5 / p25 / median / p95): %s\n",
              quantiles(feature_counts).c_str());
  std::printf("word normaliser s_w(t, t-1):  %s\n", quantiles(word_norm).c_str());
  std::printf("group normaliser s_g(t, t-1): %s\n", quantiles(group_norm).c_str());
  std::printf("distribution normaliser:      %s\n", quantiles(dist_norm).c_str());
  std::printf("%zu queries with a revisit; rank of the best true match among the candidates:\n",
              ranks[0].size());
  std::printf("score     top-1   top-5  top-20  absent  median rank (when present)\n");
  for (int s = 0; s < 5; ++s) {
    int top1 = 0, top5 = 0, top20 = 0, absent = 0;
    std::vector<double> present;
    for (int x : ranks[s]) {
      if (x == 0) {
        ++absent;
        continue;
      }
      top1 += x == 1;
      top5 += x <= 5;
      top20 += x <= 20;
      present.push_back(x);
    }
    std::sort(present.begin(), present.end());
    const double n = std::max<std::size_t>(1, ranks[s].size());
    std::printf("%-8s %6.3f  %6.3f  %6.3f  %6.3f  %g\n", names[s], top1 / n, top5 / n, top20 / n,
                absent / n, present.empty() ? 0.0 : present[present.size() / 2]);
  }
}

}  // namespace

int dumpCandidates(const Args& a, std::shared_ptr<const Vocabulary> vocabulary,
                   LoopDetectorOptions options, const std::vector<FrameInput>& frames,
                   const GroundTruth& gt) {
  options.word_groups.enabled = true;
  options.distribution.enabled = true;
  options.similarity.min_word_normaliser = 0;
  options.similarity.min_group_normaliser = 0;
  options.similarity.min_distribution_normaliser = 0;
  LoopDetector detector(vocabulary, options);
  std::ostringstream csv;
  csv << "frame,features,word_normaliser,group_normaliser,distribution_normaliser,candidates,"
         "rank_w,rank_g,rank_d,rank_sim,rank_eta,best_true_eta,best_false_eta\n";
  std::vector<std::vector<int>> ranks(5);
  std::vector<double> word_norm, group_norm, dist_norm, feature_counts;
  ProgressBar bar("dump-candidates", a.quiet);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const KeyframeInput input = toKeyframeInput(frames[i]);
    const LoopResult r = detector.process(input);
    bar(i + 1, frames.size());
    feature_counts.push_back(static_cast<double>(frames[i].features.size()));
    if (r.status != LoopStatus::kDatabaseTooSmall && r.status != LoopStatus::kNoFeatures) {
      word_norm.push_back(r.word_normaliser);
      group_norm.push_back(r.group_normaliser);
      dist_norm.push_back(r.distribution_normaliser);
    }
    const auto it = gt.loops.find(static_cast<int>(i));
    if (it == gt.loops.end() || it->second.empty()) continue;
    const QueryRanks q = rankTrueMatch(detector.lastCandidates(), gt, static_cast<int>(i));
    const int* rank = q.rank;
    const double best_true = q.best_true, best_false = q.best_false;
    for (int s = 0; s < 5; ++s) ranks[s].push_back(rank[s]);
    csv << i << "," << frames[i].features.size() << "," << r.word_normaliser << ","
        << r.group_normaliser << "," << r.distribution_normaliser << ","
        << detector.lastCandidates().size();
    for (int s = 0; s < 5; ++s) csv << "," << rank[s];
    csv << "," << best_true << "," << best_false << "\n";
  }
  writeFileAtomically(a.dump_candidates, csv.str());
  printRankTable(feature_counts, word_norm, group_norm, dist_norm, ranks);
  std::printf("per-query CSV: %s\n", a.dump_candidates.c_str());
  return 0;
}

}  // namespace evaluate_app
}  // namespace bowg
