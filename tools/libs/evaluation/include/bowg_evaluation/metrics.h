// Precision, recall, F1, the precision-recall curve and recall at 100 %
// precision of a list of loop detections against a GroundTruth.
//
// Definitions (docs/evaluation.md):
//  - At threshold tau a detection (q, m, score) is accepted when
//    score >= tau. Each query counts at most once: where a query has several
//    accepted detections, only its highest-scoring one counts (ties: the
//    first in the list).
//  - True positive: the query's counted detection has m in gt[q].
//    False positive: any other counted detection (wrong place, or a query
//    whose gt set is empty).
//  - precision = TP / (TP + FP), defined as 1 when nothing is accepted;
//    recall = TP / P, P = number of queries with a non-empty gt set,
//    defined as 0 when P = 0; F1 = 2PR / (P + R), 0 when P + R = 0.
//  - Recall at 100 % precision: the largest recall over all thresholds at
//    which FP = 0 (0 when even the highest score is a false positive).
#pragma once

#include <string>
#include <vector>

#include "bowg_evaluation/ground_truth.h"

namespace bowg {
namespace eval {

struct Detection {
  int query = 0;
  int match = 0;
  double score = 0;
};

struct PrPoint {
  double threshold = 0;
  int true_positives = 0;
  int false_positives = 0;
  int positives = 0;  ///< queries with a non-empty gt set
  double precision = 1;
  double recall = 0;
  double f1 = 0;
};

/// The counts at one threshold.
PrPoint evaluateAt(const std::vector<Detection>& detections, const GroundTruth& gt,
                   double threshold);

/// One point per distinct detection score, thresholds descending (the exact
/// curve: between two scores nothing changes).
std::vector<PrPoint> precisionRecallCurve(const std::vector<Detection>& detections,
                                          const GroundTruth& gt);

/// One point per given threshold, in the given order.
std::vector<PrPoint> precisionRecallCurve(const std::vector<Detection>& detections,
                                          const GroundTruth& gt,
                                          const std::vector<double>& thresholds);

/// The point with the largest recall among those with FP = 0 (on ties the
/// highest threshold). When no such point has TP > 0, recall is 0 and the
/// threshold is +infinity.
PrPoint recallAtFullPrecision(const std::vector<PrPoint>& curve);

/// Reads/writes detections as CSV "query,match,score" with that header line.
/// Read errors throw bowg::FormatError("<path>:<line>: ...").
std::vector<Detection> parseDetectionsCsv(const std::string& text, const std::string& source);
std::string detectionsToCsv(const std::vector<Detection>& detections);

}  // namespace eval
}  // namespace bowg
