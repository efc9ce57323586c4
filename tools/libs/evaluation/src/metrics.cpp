#include "bowg_evaluation/metrics.h"

#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

#include "bowg/core/errors.h"

namespace bowg {
namespace eval {
namespace {

void finish(PrPoint& p) {
  const int accepted = p.true_positives + p.false_positives;
  p.precision = accepted > 0 ? static_cast<double>(p.true_positives) / accepted : 1.0;
  p.recall = p.positives > 0 ? static_cast<double>(p.true_positives) / p.positives : 0.0;
  p.f1 = p.precision + p.recall > 0 ? 2 * p.precision * p.recall / (p.precision + p.recall) : 0.0;
}

}  // namespace

PrPoint evaluateAt(const std::vector<Detection>& detections, const GroundTruth& gt,
                   double threshold) {
  // The counted detection per query: highest score >= threshold, first wins ties.
  std::map<int, const Detection*> best;
  for (const Detection& d : detections) {
    if (!(d.score >= threshold)) continue;
    auto it = best.find(d.query);
    if (it == best.end()) {
      best[d.query] = &d;
    } else if (d.score > it->second->score) {
      it->second = &d;
    }
  }
  PrPoint p;
  p.threshold = threshold;
  p.positives = gt.positives();
  for (const auto& kv : best) {
    if (gt.contains(kv.first, kv.second->match)) {
      ++p.true_positives;
    } else {
      ++p.false_positives;
    }
  }
  finish(p);
  return p;
}

std::vector<PrPoint> precisionRecallCurve(const std::vector<Detection>& detections,
                                          const GroundTruth& gt) {
  std::vector<double> scores;
  for (const Detection& d : detections) scores.push_back(d.score);
  std::sort(scores.begin(), scores.end(), std::greater<double>());
  scores.erase(std::unique(scores.begin(), scores.end()), scores.end());
  return precisionRecallCurve(detections, gt, scores);
}

std::vector<PrPoint> precisionRecallCurve(const std::vector<Detection>& detections,
                                          const GroundTruth& gt,
                                          const std::vector<double>& thresholds) {
  std::vector<PrPoint> curve;
  curve.reserve(thresholds.size());
  for (double t : thresholds) curve.push_back(evaluateAt(detections, gt, t));
  return curve;
}

PrPoint recallAtFullPrecision(const std::vector<PrPoint>& curve) {
  PrPoint best;
  best.threshold = std::numeric_limits<double>::infinity();
  if (!curve.empty()) best.positives = curve.front().positives;
  for (const PrPoint& p : curve) {
    if (p.false_positives != 0 || p.true_positives == 0) continue;
    if (p.true_positives > best.true_positives ||
        (p.true_positives == best.true_positives && p.threshold > best.threshold)) {
      best = p;
    }
  }
  finish(best);
  return best;
}

std::vector<Detection> parseDetectionsCsv(const std::string& text, const std::string& source) {
  std::vector<Detection> out;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    if (number == 1 && line.find("query") != std::string::npos) continue;  // header
    std::istringstream fields(line);
    std::string a, b, c, extra;
    if (!std::getline(fields, a, ',') || !std::getline(fields, b, ',') ||
        !std::getline(fields, c, ',') || std::getline(fields, extra, ',')) {
      throw FormatError(source + ":" + std::to_string(number) +
                        ": expected 'query,match,score', got '" + line + "'");
    }
    char* end = nullptr;
    Detection d;
    const long q = std::strtol(a.c_str(), &end, 10);
    const bool q_ok = end != a.c_str() && *end == '\0' && q >= 0;
    const long m = std::strtol(b.c_str(), &end, 10);
    const bool m_ok = end != b.c_str() && *end == '\0' && m >= 0;
    d.score = std::strtod(c.c_str(), &end);
    const bool s_ok = end != c.c_str() && *end == '\0';
    if (!q_ok || !m_ok || !s_ok) {
      throw FormatError(source + ":" + std::to_string(number) +
                        ": query and match must be non-negative integers and score a number: '" +
                        line + "'");
    }
    d.query = static_cast<int>(q);
    d.match = static_cast<int>(m);
    out.push_back(d);
  }
  return out;
}

std::string detectionsToCsv(const std::vector<Detection>& detections) {
  std::ostringstream out;
  out << "query,match,score\n" << std::setprecision(9);
  for (const Detection& d : detections) out << d.query << "," << d.match << "," << d.score << "\n";
  return out.str();
}

}  // namespace eval
}  // namespace bowg
