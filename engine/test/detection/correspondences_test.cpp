// Geometric verification's correspondences (findCorrespondences): the rules
// (direct-index nodes, Hamming limit, ratio test, mutual matches) by hand,
// and the definition written out against the search through ties.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "bowg/detection/geometric_verification.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace {

// Hand-made descriptors: d(k) has the k lowest bits of block 0 set.
Descriptor bitsSet(int k) {
  Descriptor d;
  d.bits[0] = k >= 64 ? ~0ull : ((1ull << k) - 1);
  return d;
}

TEST(GeometricVerification, CorrespondenceRules) {
  std::vector<ImagePoint> qk(3), mk(3);
  GeometricVerificationOptions o;
  o.max_hamming = 10;
  o.max_neighbour_ratio = 0.8;
  // Query 0 = bits(0); match 0 = bits(2) (d=2), match 1 = bits(20) (d=20):
  // 2 < 0.8 * 20 -> kept. Query 1 = bits(40): nearest match 1 at 20 > 10 -> dropped.
  // Query 2 = bits(1): match 0 at 1, match 1 at 19: passes ratio but match 0's
  // closest query is query 2 (1 < 2), so query 0 loses its mutual match.
  std::vector<Descriptor> qd{bitsSet(0), bitsSet(40), bitsSet(1)};
  std::vector<Descriptor> md{bitsSet(2), bitsSet(20), bitsSet(63)};
  o.exhaustive = true;
  VerificationView q{&qk, &qd, nullptr}, m{&mk, &md, nullptr};
  auto pairs = findCorrespondences(q, m, o);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], std::make_pair(2u, 0u));
  // Without query 2, query 0 matches match 0.
  std::vector<Descriptor> qd2{bitsSet(0), bitsSet(40)};
  std::vector<ImagePoint> qk2(2);
  VerificationView q2{&qk2, &qd2, nullptr};
  pairs = findCorrespondences(q2, m, o);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], std::make_pair(0u, 0u));
  // Ratio test: a second match at the same distance makes it ambiguous.
  std::vector<Descriptor> md3{bitsSet(2), bitsSet(2), bitsSet(63)};
  VerificationView m3{&mk, &md3, nullptr};
  EXPECT_TRUE(findCorrespondences(q2, m3, o).empty());
  // Direct index: features in different nodes are never compared.
  o.exhaustive = false;
  const DirectIndex qdi{{5, 0}, {5, 1}}, mdi_other{{6, 0}, {6, 1}, {6, 2}},
      mdi_same{{5, 0}, {5, 1}, {5, 2}};
  q2.direct = &qdi;
  m.direct = &mdi_other;
  EXPECT_TRUE(findCorrespondences(q2, m, o).empty());
  m.direct = &mdi_same;
  EXPECT_EQ(findCorrespondences(q2, m, o).size(), 1u);
  // Incomplete views are rejected.
  m.direct = nullptr;
  EXPECT_THROW(findCorrespondences(q2, m, o), std::invalid_argument);
}

// The definition, written out: within each node, a query feature's nearest
// match feature (the first of equals) and the second smallest distance
// (a tie with the nearest counts); kept when near enough, unambiguous and
// mutual (the match feature's nearest query feature of the node, the first
// of equals, is this one).
std::vector<std::pair<std::uint32_t, std::uint32_t>> correspondencesByDefinition(
    const std::vector<Descriptor>& qd, const DirectIndex& qdi, const std::vector<Descriptor>& md,
    const DirectIndex& mdi, const GeometricVerificationOptions& o) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (const auto& q : qdi) {
    std::vector<std::uint32_t> ms;
    for (const auto& m : mdi) {
      if (m.first == q.first) ms.push_back(m.second);
    }
    if (ms.empty()) continue;
    std::vector<int> dists;
    std::uint32_t nearest = ms[0];
    int best = hammingDistance(qd[q.second], md[ms[0]]);
    for (const std::uint32_t m : ms) {
      const int d = hammingDistance(qd[q.second], md[m]);
      dists.push_back(d);
      if (d < best) best = d, nearest = m;
    }
    std::sort(dists.begin(), dists.end());
    if (best > o.max_hamming) continue;
    if (dists.size() > 1 && !(best < o.max_neighbour_ratio * dists[1])) continue;
    std::uint32_t back = 0;
    int back_best = std::numeric_limits<int>::max();
    for (const auto& other : qdi) {
      if (other.first != q.first) continue;
      const int d = hammingDistance(qd[other.second], md[nearest]);
      if (d < back_best) back_best = d, back = other.second;
    }
    if (back == q.second) out.emplace_back(q.second, nearest);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(GeometricVerification, CorrespondencesFollowTheDefinitionThroughTies) {
  // Descriptors a few bits from one of three prototypes: many equal
  // distances, so first-of-equals and second-counting-ties decide.
  std::mt19937_64 rng(21);
  const std::vector<Descriptor> prototypes = testing::randomDescriptors(3, 5);
  std::uniform_int_distribution<int> bit(0, 255), proto(0, 2), flips(0, 4), node(0, 5);
  auto near = [&]() {
    Descriptor d = prototypes[static_cast<std::size_t>(proto(rng))];
    for (int f = flips(rng); f > 0; --f) {
      const int i = bit(rng);
      d.bits[i / 64] ^= 1ull << (i % 64);
    }
    return d;
  };
  std::size_t kept = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t nq = 1 + trial % 23, nm = 1 + (trial * 7) % 19;
    std::vector<Descriptor> qd(nq), md(nm);
    for (auto& d : qd) d = near();
    for (auto& d : md) d = near();
    DirectIndex qdi, mdi;
    for (std::uint32_t i = 0; i < nq; ++i) qdi.emplace_back(static_cast<NodeId>(node(rng)), i);
    for (std::uint32_t i = 0; i < nm; ++i) mdi.emplace_back(static_cast<NodeId>(node(rng)), i);
    std::sort(qdi.begin(), qdi.end());
    std::sort(mdi.begin(), mdi.end());
    std::vector<ImagePoint> qk(nq), mk(nm);
    GeometricVerificationOptions o;
    o.max_hamming = 3 + trial % 5;
    o.max_neighbour_ratio = trial % 2 ? 0.8 : 1.0;
    o.exhaustive = trial % 3 == 0;
    const VerificationView q{&qk, &qd, &qdi}, m{&mk, &md, &mdi};
    DirectIndex qall, mall;
    for (std::uint32_t i = 0; i < nq; ++i) qall.emplace_back(0, i);
    for (std::uint32_t i = 0; i < nm; ++i) mall.emplace_back(0, i);
    const auto expected = o.exhaustive ? correspondencesByDefinition(qd, qall, md, mall, o)
                                       : correspondencesByDefinition(qd, qdi, md, mdi, o);
    ASSERT_EQ(findCorrespondences(q, m, o), expected) << "trial " << trial;
    kept += expected.size();
  }
  EXPECT_GT(kept, 100u);  // the rules were exercised, not only the rejections
}

}  // namespace
}  // namespace bowg
