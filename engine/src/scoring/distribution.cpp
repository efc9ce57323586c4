// Feature-distribution score (paper Sec. III-C). The paper's formula takes the
// largest *distance* over cyclic shifts; docs/method.md (step 5) fixes the reading
// to the best *alignment* (largest inner product), which is what makes the
// score roll invariant.
#include "bowg/scoring/distribution.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace bowg {
namespace {

const double kTwoPi = 6.283185307179586476925286766559;

void checkBins(const char* function, int m) {
  if (m < 1) {
    throw std::invalid_argument(std::string(function) +
                                ": the number of fan bins m must be >= 1 (got " +
                                std::to_string(m) + ")");
  }
}

const double kHalfPi = 1.5707963267948966192313216916398;
const double kPi = 3.1415926535897932384626433832795;
// The approximate angle's error bound (its polynomial's, 1.7e-6 rad, with a
// factor 6 to spare): a point farther than this from a bin's edge lies in
// the bin its approximate angle says.
const double kApproximateAngleMargin = 1e-5;

// atan(a) for a in [0, 1], within 1.7e-6 rad: an odd polynomial of degree
// 11 fitted for the least largest error.
double atanUnit(double a) {
  const double a2 = a * a;
  return a * (0.99997722229731367 +
              a2 * (-0.33262290599594413 +
                    a2 * (0.19354088966718644 +
                          a2 * (-0.1164278279216006 +
                                a2 * (0.052648867684518097 + a2 * -0.011719748445724903)))));
}

// The angle of (dx, dy) != 0 in [0, 2 pi], within 1.7e-6 rad (plus
// rounding): the octant by comparisons, atanUnit within it.
double approximateAngle(double dx, double dy) {
  const double ax = std::fabs(dx), ay = std::fabs(dy);
  double t = ay > ax ? kHalfPi - atanUnit(ax / ay) : atanUnit(ay / ax);
  if (dx < 0.0) t = kPi - t;
  if (dy < 0.0) t = kTwoPi - t;
  return t;
}

// Bin k covers [2*pi*k/m, 2*pi*(k+1)/m) of atan2's angle.
int exactFanBin(double dx, double dy, int m) {
  double angle = std::atan2(dy, dx);
  if (angle < 0.0) angle += kTwoPi;
  // Rounding can put an angle a hair below 2*pi at exactly m: that point
  // belongs to the last bin.
  const int k = static_cast<int>(std::floor(angle / (kTwoPi / m)));
  return k >= m ? m - 1 : k;
}

}  // namespace

int fanBin(float x, float y, double cx, double cy, int m) {
  checkBins("fanBin", m);
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(cx) || !std::isfinite(cy)) {
    throw std::invalid_argument("fanBin: point and centre must be finite");
  }
  const double dx = static_cast<double>(x) - cx;
  const double dy = static_cast<double>(y) - cy;
  if (dx == 0.0 && dy == 0.0) return 0;
  // Image coordinates (y down): the angle grows clockwise on screen. atan2
  // was most of the distribution vector's cost: its bin comes from the
  // approximate angle unless that lies within the margin of a bin's edge,
  // where atan2 decides. Either way the bin is atan2's.
  const double width = kTwoPi / m;
  const double u = approximateAngle(dx, dy) / width;  // >= 0
  const int k = static_cast<int>(u);                  // floor
  const double below = u - k, above = k + 1.0 - u;
  if ((below < above ? below : above) * width > kApproximateAngleMargin && k < m) return k;
  return exactFanBin(dx, dy, m);
}

std::vector<double> distributionVector(const std::vector<ImagePoint>& points, double cx, double cy,
                                       int m) {
  checkBins("distributionVector", m);
  std::vector<double> v(static_cast<std::size_t>(m), 0.0);
  for (const ImagePoint& p : points) v[fanBin(p.x, p.y, cx, cy, m)] += 1.0;
  // L2 normalisation (v-hat in the paper).
  double norm = 0.0;
  for (const double n : v) norm += n * n;
  if (norm > 0.0) {
    norm = std::sqrt(norm);
    for (double& n : v) n /= norm;
  }
  return v;
}

DistributionScorer::DistributionScorer(const std::vector<double>& query, std::size_t db_bins,
                                       const char* caller)
    : twice_(2 * query.size()), dots_(query.size()) {
  if (query.size() != db_bins) {
    throw std::invalid_argument(std::string(caller) + ": the query's distribution vector has " +
                                std::to_string(query.size()) + " bins, the scored one " +
                                std::to_string(db_bins) +
                                "; were they built with the same number of fan bins?");
  }
  const std::size_t m = query.size();
  for (std::size_t i = 0; i < m; ++i) twice_[i] = twice_[i + m] = query[i];
}

namespace {

// The best of the m shifts' dot products of `twice` (the query twice over)
// with db. A roll of the camera by 2*pi*i/m shifts the bins cyclically by i:
// the score is the best alignment over the m columns M_i of the
// distribution matrix, m_ij = v_((i+j) mod m). All m dot products at once,
// term j added to each in turn (the order of each sum is j = 0..m-1, as one
// dot product at a time would add them): the inner loop runs over the
// alignments, contiguous in the query read twice over, and vectorises.
template <typename Size>
double bestShift(const double* twice, const double* db, Size m, double* dot) {
  for (std::size_t i = 0; i < m; ++i) dot[i] = 0.0;
  for (std::size_t j = 0; j < m; ++j) {
    const double d = db[j];
    const double* q = twice + j;
    for (std::size_t i = 0; i < m; ++i) dot[i] += q[i] * d;
  }
  double best = 0.0;
  for (std::size_t i = 0; i < m; ++i)
    if (dot[i] > best) best = dot[i];
  // Rounding can exceed 1 by an ulp for identical unit vectors.
  return best > 1.0 ? 1.0 : best;
}

// The presets' fan_bins (a large map's query scores ~10^5 entries): with m
// known and the sums in a local array, the compiler keeps them in registers
// and unrolls the loops into whole vector operations; the same sums in the
// same order.
const std::size_t kPresetBins = 8;
double bestShiftOfEight(const double* twice, const double* db) {
  double dot[kPresetBins];
  return bestShift(twice, db, std::integral_constant<std::size_t, kPresetBins>(), dot);
}

}  // namespace

double DistributionScorer::score(const double* db) {
  const std::size_t m = dots_.size();
  if (m == kPresetBins) return bestShiftOfEight(twice_.data(), db);
  return bestShift(twice_.data(), db, m, dots_.data());
}

double distributionScore(const std::vector<double>& query, const std::vector<double>& db) {
  return DistributionScorer(query, db.size(), "distributionScore").score(db.data());
}

}  // namespace bowg
