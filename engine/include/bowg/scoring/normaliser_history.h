// The normalisers s(I_t, I_t-1) of the most recent keyframes, and the floor
// they put under the normaliser of the next query.
//
// Eqs. 2 and 4 normalise a query's scores "with the best score we expect to
// obtain in the sequence for I_t" (paper Sec. III-B, after DLoopDetector), and
// estimate it with ONE sample, the score against the previous keyframe. When
// that keyframe is unusually dissimilar (an exposure step, a jolt), every eta
// of the query is lifted by the same factor and the best of its hundreds of
// candidates - usually a look-alike - outscores every true revisit of the
// sequence (on a rendered pipe sequence the top-scored loops of every
// ablation row were false for that reason). The median of the last few normalisers is a robust
// estimate of the same expectation; the floor keeps the paper's normaliser
// whenever it is not unusually small (docs/method.md, "Normaliser floor").
#pragma once

#include <cstddef>
#include <deque>
#include <vector>

namespace bowg {

/// s_w, s_g, s_d of a query against its previous keyframe (eqs. 2, 4, Sec. III-C).
struct Normalisers {
  double word = 0.0;
  double group = 0.0;
  double distribution = 0.0;
};

class NormaliserHistory {
 public:
  /// Appends the normalisers of one keyframe, keeping only the last `window`
  /// (>= 1) keyframes.
  void push(const Normalisers& n, std::size_t window);
  /// Component-wise median of the stored values (mean of the two middle
  /// values for an even count); all zero when nothing is stored.
  Normalisers median() const;
  std::size_t size() const { return values_.size(); }
  /// Oldest first, as push() appended them (persistence).
  std::vector<Normalisers> values() const { return {values_.begin(), values_.end()}; }
  void restore(const std::vector<Normalisers>& values) {
    values_.assign(values.begin(), values.end());
  }
  void clear() { values_.clear(); }

 private:
  std::deque<Normalisers> values_;
};

/// The normalisers a query divides by: per component max(current,
/// floor * expected), `floor` >= 0. floor 0 returns `current` unchanged
/// (the paper's s(I_t, I_t-1)).
Normalisers flooredNormalisers(const Normalisers& current, const Normalisers& expected,
                               double floor);

}  // namespace bowg
