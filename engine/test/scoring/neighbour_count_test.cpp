// The neighbour count of the word groups' grid: hand-worked distances at
// and around both bounds, and the AVX2 count against the portable one on
// random runs of 0-40 points from any start (and NaN coordinates).
#include "scoring/neighbour_count.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <vector>

#include "core/cpu_features.h"

namespace bowg {
namespace {

using neighbour_count::CountWithin;
using neighbour_count::Counts;

std::vector<CountWithin> counts() {
  std::vector<CountWithin> c{neighbour_count::countWithinPortable};
  if (cpuHasAvx2()) c.push_back(neighbour_count::countWithinAvx2);
  return c;
}

TEST(NeighbourCount, DistancesAtTheBoundsByHand) {
  // Around (10, 20): squared distances 0, 1, 4, 4, 9, 16, 25, 2, 5, 8, 4
  // (eleven points: the AVX2 count's eight and a rest of three).
  const std::vector<float> xs{10, 11, 12, 10, 13, 10, 15, 11, 12, 12, 8};
  const std::vector<float> ys{20, 20, 20, 22, 20, 24, 20, 21, 21, 22, 20};
  for (const CountWithin count : counts()) {
    // below 4 (strict): 0, 1, 2 -> 3; above 4 (inclusive): and the three 4s -> 6.
    Counts c = count(xs.data(), ys.data(), 0, 11, 10, 20, 4, 4);
    EXPECT_EQ(c.sure, 3);
    EXPECT_EQ(c.maybe, 6);
    // below 5, above 9: 0, 1, 4, 4, 2, 4 -> 6; and 5, 8, 9 -> 9.
    c = count(xs.data(), ys.data(), 0, 11, 10, 20, 5, 9);
    EXPECT_EQ(c.sure, 6);
    EXPECT_EQ(c.maybe, 9);
    // A sub-run [3, 7): 4, 9, 16, 25.
    c = count(xs.data(), ys.data(), 3, 7, 10, 20, 10, 16);
    EXPECT_EQ(c.sure, 2);
    EXPECT_EQ(c.maybe, 3);
    c = count(xs.data(), ys.data(), 5, 5, 10, 20, 10, 16);
    EXPECT_EQ(c.sure, 0);
    EXPECT_EQ(c.maybe, 0);
  }
}

TEST(NeighbourCount, TheAvx2CountIsThePortableOne) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2: only the portable count runs here";
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> u(0.f, 64.f);
  std::vector<float> xs(64), ys(64);
  for (int trial = 0; trial < 3000; ++trial) {
    for (std::size_t i = 0; i < xs.size(); ++i) {
      // Whole coordinates make exact ties with the bounds common.
      xs[i] = trial % 2 ? u(rng) : static_cast<float>(static_cast<int>(u(rng)) % 9);
      ys[i] = trial % 2 ? u(rng) : static_cast<float>(static_cast<int>(u(rng)) % 9);
    }
    if (trial % 7 == 0) xs[rng() % xs.size()] = std::numeric_limits<float>::quiet_NaN();
    const std::uint32_t begin = rng() % 24, end = begin + rng() % 41;
    const float x = static_cast<float>(rng() % 9), y = static_cast<float>(rng() % 9);
    const float below = static_cast<float>(rng() % 40), above = below + static_cast<float>(rng() % 3);
    const Counts p = neighbour_count::countWithinPortable(xs.data(), ys.data(), begin, end, x, y,
                                                          below, above);
    const Counts a =
        neighbour_count::countWithinAvx2(xs.data(), ys.data(), begin, end, x, y, below, above);
    ASSERT_EQ(a.sure, p.sure) << "trial " << trial;
    ASSERT_EQ(a.maybe, p.maybe) << "trial " << trial;
  }
}

TEST(NeighbourCount, TheBestCountIsTheFastestTheCpuRuns) {
  EXPECT_EQ(neighbour_count::bestCountWithin(), cpuHasAvx2()
                                                    ? neighbour_count::countWithinAvx2
                                                    : neighbour_count::countWithinPortable);
}

}  // namespace
}  // namespace bowg
