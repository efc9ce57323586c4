// Running median of the previous-keyframe normalisers (normaliser_history.h).
#include "bowg/scoring/normaliser_history.h"

#include <algorithm>
#include <stdexcept>

namespace bowg {
namespace {

double medianOf(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  const double upper = v[mid];
  if (v.size() % 2 == 1) return upper;
  // Even count: the largest of the lower half is the other middle value.
  const double lower = *std::max_element(v.begin(), v.begin() + mid);
  return 0.5 * (lower + upper);
}

}  // namespace

void NormaliserHistory::push(const Normalisers& n, std::size_t window) {
  if (window == 0) throw std::invalid_argument("NormaliserHistory::push: window must be >= 1");
  values_.push_back(n);
  while (values_.size() > window) values_.pop_front();
}

Normalisers NormaliserHistory::median() const {
  std::vector<double> w, g, d;
  w.reserve(values_.size());
  g.reserve(values_.size());
  d.reserve(values_.size());
  for (const Normalisers& n : values_) {
    w.push_back(n.word);
    g.push_back(n.group);
    d.push_back(n.distribution);
  }
  return {medianOf(std::move(w)), medianOf(std::move(g)), medianOf(std::move(d))};
}

Normalisers flooredNormalisers(const Normalisers& current, const Normalisers& expected,
                               double floor) {
  if (!(floor >= 0.0)) {
    throw std::invalid_argument("flooredNormalisers: floor must be >= 0");
  }
  return {std::max(current.word, floor * expected.word),
          std::max(current.group, floor * expected.group),
          std::max(current.distribution, floor * expected.distribution)};
}

}  // namespace bowg
