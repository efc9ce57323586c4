// bowg_evaluate's outputs (summary_report.h).
#include "summary_report.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <sstream>

#include "bowg/core/atomic_file.h"
#include "bowg_evaluation/mission_file.h"
#include "bowg_evaluation/pr_report.h"
#include "bowg_evaluation/timing_stats.h"
#include "console_output.h"

namespace bowg {
namespace evaluate_app {

using namespace bowg::eval;

namespace {

// The loops from one mission into another, at the operating point: what a
// robot re-inspecting a network gets from the earlier surveys.
void crossMissionTable(const std::vector<RowResult>& results, const GroundTruth& gt,
                       std::ostream& s) {
  s << "\nacross missions (loops into another mission than the query's; "
    << "positives: queries with a true match there)\n"
    << "row            precision  recall   TP   FP  positives\n";
  for (const RowResult& r : results) {
    const PrPoint p = crossMissionPoint(r.run, gt);
    char line[160];
    std::snprintf(line, sizeof(line), "%-14s %9.3f %7.3f %4d %4d  %9d\n", r.run.name.c_str(),
                  p.precision, p.recall, p.true_positives, p.false_positives, p.positives);
    s << line;
  }
}

// Precision, recall, F1 and recall at 100 % precision per row.
void accuracyTable(const Args& a, const std::vector<RowResult>& results, const GroundTruth& gt,
                   const std::vector<double>& thresholds, double threshold, std::ostream& s) {
  s << "ground truth: " << a.gt << " (" << gt.positives() << " queries with a revisit)\n"
    << "PR sweep: "
    << (a.sweep == "rerun" ? "detector re-run per min_score"
                           : "final score of one run at the lowest min_score")
    << ", " << thresholds.size() << " thresholds " << thresholds.back() << ".."
    << thresholds.front() << "\n\n";
  s << "at min_score " << threshold << "; R@100%P = recall at 100 % precision (its threshold)\n"
    << "row            precision  recall      F1   TP   FP  R@100%P (threshold)  loops\n";
  for (const RowResult& r : results) {
    char line[256];
    std::snprintf(
        line, sizeof(line), "%-14s %9.3f %7.3f %7.3f %4d %4d  %7.3f (%9s)  %5zu\n",
        r.run.name.c_str(), r.at_threshold.precision, r.at_threshold.recall, r.at_threshold.f1,
        r.at_threshold.true_positives, r.at_threshold.false_positives, r.full_precision.recall,
        std::isinf(r.full_precision.threshold) ? "none"
                                               : fmt("%.3f", r.full_precision.threshold).c_str(),
        detectionsOf(r.run).size());
    s << line;
  }
  if (!a.missions.empty() || !a.maps.empty()) crossMissionTable(results, gt, s);
  if (a.ablation && results.front().run.name == "bow" &&
      results.back().run.name == "distribution") {
    // The comparison the paper's ablation is for, in one line (bow first,
    // the full method last); other row lists have no such pair.
    const PrPoint& bow = results.front().full_precision;
    const PrPoint& full = results.back().full_precision;
    s << "\nrecall at 100 % precision: full BoWG " << fmt("%.3f", full.recall)
      << ", pure bag of words " << fmt("%.3f", bow.recall);
    if (bow.recall > 0) s << " (" << fmt("%.1f", full.recall / bow.recall) << "x)";
    s << "\n";
  }
}

// Without a ground truth: keyframes per status and every loop.
void countsTable(const std::vector<RowResult>& results, std::size_t map_entries, std::ostream& s) {
  s << "\nno ground truth: counts only\n";
  for (const RowResult& r : results) {
    std::map<std::string, int> counts;
    int into_maps = 0;
    for (const KeyframeRecord& k : r.run.keyframes) {
      ++counts[toString(k.status)];
      if (k.match >= 0 && static_cast<std::size_t>(k.match) < map_entries) ++into_maps;
    }
    s << r.run.name << ":";
    for (const auto& kv : counts) s << " " << kv.first << "=" << kv.second;
    if (map_entries > 0) s << "  (" << into_maps << " into the reference maps)";
    s << "\n";
    for (const KeyframeRecord& k : r.run.keyframes) {
      if (k.match < 0) continue;
      s << "  loop " << k.frame << " -> " << k.match << "  score " << fmt("%.3f", k.candidate_score)
        << "  inliers " << k.inliers << "\n";
    }
  }
}

void timingTable(const std::vector<RowResult>& results, std::ostream& s) {
  s << "\nper-keyframe timing (ms): mean / median / p95 / max\n";
  for (const RowResult& r : results) {
    s << r.run.name << " (" << fmt("%.1f", r.run.wall_seconds) << " s for the run):\n";
    for (const auto& kv : stageTimingStats(r.run)) {
      char line[160];
      std::snprintf(line, sizeof(line), "  %-15s %7.2f %7.2f %7.2f %7.2f\n", kv.first.c_str(),
                    kv.second.mean, kv.second.median, kv.second.p95, kv.second.max);
      s << line;
    }
  }
}

// Five bins in the summary, twenty in time_vs_database_size.csv.
void timeVersusSize(const Args& a, const std::vector<RowResult>& results, std::ostream& s) {
  s << "\ndetector time vs database size (ms, mean / max):\n";
  std::ostringstream size_csv;
  size_csv << "method,first_size,last_size,mean_ms,median_ms,p95_ms,max_ms\n";
  for (const RowResult& r : results) {
    s << r.run.name << ":";
    for (const TimeVsSize& t : timeVersusDatabaseSize(r.run, 5)) {
      s << "  [" << t.first << "-" << t.last << "] "
        << fmt("%.2f/%.2f", t.total_ms.mean, t.total_ms.max);
    }
    s << "\n";
    for (const TimeVsSize& t : timeVersusDatabaseSize(r.run, 20)) {
      size_csv << r.run.name << "," << t.first << "," << t.last << "," << t.total_ms.mean << ","
               << t.total_ms.median << "," << t.total_ms.p95 << "," << t.total_ms.max << "\n";
    }
  }
  writeFileAtomically(a.output + "/time_vs_database_size.csv", size_csv.str());
}

// Resident set and the engine's estimate as the database grows (the first
// row is alone on a fresh heap; later rows reuse what earlier ones freed).
void memoryVersusSize(const Args& a, const std::vector<RowResult>& results, std::ostream& s) {
  std::ostringstream csv;
  csv << "method,keyframes,resident_mb,estimate_mb\n";
  s << "\nmemory growth per keyframe (resident set / Database::memoryBytes(), kB):\n";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const DetectorRun& run = results[i].run;
    for (const MemorySample& m : run.memory) {
      csv << run.name << "," << m.keyframes << "," << fmt("%.3f", m.resident_bytes / 1048576.0)
          << "," << fmt("%.3f", m.estimate_bytes / 1048576.0) << "\n";
    }
    const MemoryGrowth g = memoryGrowth(run);
    s << run.name << ": " << fmt("%.1f", g.resident_per_keyframe / 1024.0) << " / "
      << fmt("%.1f", g.estimate_per_keyframe / 1024.0) << " over " << g.keyframes << " keyframes"
      << (i == 0 ? "" : " (heap reused from the rows before)") << "\n";
  }
  writeFileAtomically(a.output + "/memory_vs_database_size.csv", csv.str());
}

}  // namespace

void writeReport(const Args& a, const std::vector<RowResult>& results, const RunInputs& inputs,
                 const GroundTruth* gt, const std::vector<double>& thresholds, double threshold) {
  const std::size_t frames = inputs.frames;
  for (const RowResult& r : results) {
    writeFileAtomically(a.output + "/keyframes_" + r.run.name + ".csv", keyframesCsv(r.run, gt));
    writeFileAtomically(a.output + "/detections_" + r.run.name + ".csv",
                        detectionsToCsv(detectionsOf(r.run)));
    writeFileAtomically(a.output + "/loop_poses_" + r.run.name + ".csv",
                        loopPosesToCsv(loopPosesOf(r.run)));
  }
  std::ostringstream s;
  s << "input: " << (a.bag.empty() ? a.images : a.bag) << " (" << frames << " frames)\n"
    << "vocabulary: " << a.vocabulary
    << "  config: " << (a.config.empty() ? "(defaults)" : a.config) << "  min_score: " << threshold
    << "\n"
    << inputs.odometry << "\n";
  if (!inputs.maps.empty()) s << inputs.maps << "\n";
  if (gt) {
    accuracyTable(a, results, *gt, thresholds, threshold, s);
  } else {
    countsTable(results, inputs.map_entries, s);
  }
  timingTable(results, s);
  timeVersusSize(a, results, s);
  memoryVersusSize(a, results, s);
  if (gt) {
    std::vector<NamedCurve> curves;
    for (const RowResult& r : results) curves.push_back({r.run.name, r.curve});
    writePrCurvesCsv(a.output + "/pr_curves.csv", curves);
    writePrPlot(a.output + "/pr_curve.png", curves,
                "BoWG precision-recall (" + std::to_string(frames) + " frames)");
  }
  s << "\noutputs in " << a.output << ": summary.txt, keyframes_<row>.csv, detections_<row>.csv, "
    << "loop_poses_<row>.csv, "
    << "time_vs_database_size.csv, memory_vs_database_size.csv"
    << (gt ? ", pr_curves.csv, pr_curve.png" : "") << "\n";
  writeFileAtomically(a.output + "/summary.txt", s.str());
  std::cout << s.str();
}

}  // namespace evaluate_app
}  // namespace bowg
