// The temporal verification over k previous queries (paper Sec. III-D,
// DLoopDetector's k) and this implementation's tolerances (missed queries,
// metres, several hypotheses), on hand-made islands.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "bowg/core/errors.h"
#include "bowg/detection/islands.h"
#include "detection/island_fixture.h"

namespace bowg {
namespace {

using testing::island;

TEST(IslandsConsistent, GapBetweenIntervals) {
  // [10, 15] and [17, 20]: gap 17 - 15 = 2.
  EXPECT_TRUE(islandsConsistent(island(10, 15), island(17, 20), 2));
  EXPECT_FALSE(islandsConsistent(island(10, 15), island(17, 20), 1));
  EXPECT_TRUE(islandsConsistent(island(17, 20), island(10, 15), 2));  // symmetric
  // Overlap: gap 12 - 14 = -2 <= 0.
  EXPECT_TRUE(islandsConsistent(island(10, 15), island(12, 14), 0));
  // Adjacent [10, 15], [16, 18]: gap 1, not an overlap.
  EXPECT_FALSE(islandsConsistent(island(10, 15), island(16, 18), 0));
  // Unsigned ids far apart: no wrap-around.
  EXPECT_FALSE(islandsConsistent(island(0, 0), island(4000000000u, 4000000000u), 3));
}

TemporalVerificationOptions verification(int k, int max_distance = 3) {
  TemporalVerificationOptions o;
  o.k = k;
  o.max_island_distance = max_distance;
  return o;
}

TEST(TemporalConsistency, ChainOfKPreviousConsistentIslands) {
  // k = 2: the current island and the islands of the 2 previous queries must
  // form a chain, so the third consistent query is the first to pass.
  TemporalConsistency tc;
  const TemporalVerificationOptions o = verification(2);
  EXPECT_FALSE(tc.update(island(10, 12), o));
  EXPECT_EQ(tc.chainLength(), 1);
  EXPECT_FALSE(tc.update(island(11, 13), o));  // overlaps
  EXPECT_EQ(tc.chainLength(), 2);
  EXPECT_TRUE(tc.update(island(15, 16), o));  // gap 15 - 13 = 2 <= 3
  EXPECT_EQ(tc.chainLength(), 3);
  EXPECT_TRUE(tc.update(island(17, 17), o));  // the chain goes on
  EXPECT_EQ(tc.chainLength(), 4);
  EXPECT_EQ(tc.lastIsland().first, 17u);
}

// chainTo: what update() would give an island, without changing anything.
TEST(TemporalConsistency, ChainToPredictsUpdate) {
  TemporalConsistency tc;
  TemporalVerificationOptions o = verification(2);
  o.hypotheses = 2;
  EXPECT_EQ(tc.chainTo(island(10, 12), o), 1);  // nothing followed yet
  // Two hypotheses per query; the chosen island jumps from lap 1 (near 10)
  // to lap 3 (near 210), lap 1 is followed as the second hypothesis.
  tc.update({island(10, 12), island(110, 112)}, 0, o);
  tc.update({island(211, 213), island(11, 13)}, 0, o);
  EXPECT_EQ(tc.chainLength(), 1);               // lap 3's chain starts
  EXPECT_EQ(tc.chainTo(island(12, 14), o), 3);  // lap 1's: 10 -> 11 -> 12
  EXPECT_EQ(tc.chainTo(island(212, 214), o), 2);
  EXPECT_EQ(tc.chainTo(island(112, 114), o), 1);  // lap 2 was not followed last query
  EXPECT_EQ(tc.chainLength(), 1);                 // unchanged
  EXPECT_TRUE(tc.update({island(12, 14)}, 0, o));
  EXPECT_EQ(tc.chainLength(), 3);
}

TEST(TemporalConsistency, InconsistentIslandRestartsTheChain) {
  TemporalConsistency tc;
  const TemporalVerificationOptions o = verification(2);
  tc.update(island(10, 12), o);
  tc.update(island(11, 13), o);
  // [100, 102] is 87 ids away: chain restarts at 1 with it.
  EXPECT_FALSE(tc.update(island(100, 102), o));
  EXPECT_EQ(tc.chainLength(), 1);
  EXPECT_FALSE(tc.update(island(101, 103), o));
  EXPECT_TRUE(tc.update(island(102, 104), o));
}

TEST(TemporalConsistency, ConsistencyIsJudgedAgainstTheLastIslandOnly) {
  // Each island is close to its predecessor although the first and the last
  // are 8 ids apart: a chain, as in DLoopDetector.
  TemporalConsistency tc;
  const TemporalVerificationOptions o = verification(2, 3);
  tc.update(island(10, 10), o);
  tc.update(island(13, 13), o);
  EXPECT_TRUE(tc.update(island(16, 16), o));
}

TEST(TemporalConsistency, BreakChainForgetsThePast) {
  TemporalConsistency tc;
  const TemporalVerificationOptions o = verification(2);
  tc.update(island(10, 12), o);
  tc.update(island(11, 13), o);
  tc.breakChain();  // a query without any island
  EXPECT_EQ(tc.chainLength(), 0);
  EXPECT_FALSE(tc.update(island(12, 14), o));  // would have been the third
  EXPECT_EQ(tc.chainLength(), 1);
  tc.update(island(12, 14), o);
  tc.reset();
  EXPECT_EQ(tc.chainLength(), 0);
}

TEST(TemporalConsistency, KZeroAlwaysPasses) {
  TemporalConsistency tc;
  const TemporalVerificationOptions o = verification(0);
  EXPECT_TRUE(tc.update(island(10, 12), o));
  EXPECT_TRUE(tc.update(island(500, 501), o));  // inconsistent, still passes
  tc.breakChain();
  EXPECT_TRUE(tc.update(island(7, 7), o));
}

TEST(TemporalConsistency, KOneNeedsOnePreviousConsistentQuery) {
  TemporalConsistency tc;
  const TemporalVerificationOptions o = verification(1, 0);
  EXPECT_FALSE(tc.update(island(10, 12), o));
  EXPECT_FALSE(tc.update(island(14, 15), o));  // gap 2 > 0
  EXPECT_TRUE(tc.update(island(15, 16), o));   // overlaps [14, 15]
}

TEST(TemporalConsistency, RestoreResumesTheChain) {
  TemporalConsistency tc;
  tc.restore(island(11, 13), 2);
  EXPECT_EQ(tc.chainLength(), 2);
  EXPECT_EQ(tc.lastIsland().last, 13u);
  EXPECT_TRUE(tc.update(island(14, 15), verification(2)));
  EXPECT_THROW(tc.restore(island(11, 13), -1), std::invalid_argument);
  EXPECT_THROW(tc.restore(island(13, 11), 1), std::invalid_argument);
  EXPECT_EQ(tc.chainLength(), 3);  // failed restores change nothing
}

TEST(TemporalConsistency, MissedQueriesWithinTheToleranceKeepTheChain) {
  // k = 2, up to one query without an island tolerated.
  TemporalConsistency tc;
  TemporalVerificationOptions o = verification(2, 3);
  o.max_missed_queries = 1;
  tc.update(island(10, 12), o);
  tc.update(island(11, 13), o);
  tc.miss(o);  // nothing above min_score for one query
  EXPECT_EQ(tc.chainLength(), 2);
  EXPECT_EQ(tc.missedQueries(), 1);
  // The place moved on during the miss: the distance allowed is 3 * (1 + 1)
  // = 6; [19, 20] is 19 - 13 = 6 from [11, 13].
  EXPECT_TRUE(tc.update(island(19, 20), o));
  EXPECT_EQ(tc.chainLength(), 3);
  EXPECT_EQ(tc.missedQueries(), 0);
  // Two misses in a row exceed the tolerance: the chain breaks.
  tc.miss(o);
  tc.miss(o);
  EXPECT_EQ(tc.chainLength(), 0);
  EXPECT_FALSE(tc.update(island(21, 22), o));
  EXPECT_EQ(tc.chainLength(), 1);
}

TEST(TemporalConsistency, WithoutToleranceAMissBreaksTheChainAsDLoopDetector) {
  TemporalConsistency tc;
  const TemporalVerificationOptions o = verification(2, 3);
  tc.update(island(10, 12), o);
  tc.update(island(11, 13), o);
  tc.miss(o);
  EXPECT_EQ(tc.chainLength(), 0);
  EXPECT_FALSE(tc.update(island(12, 14), o));
  // Without the miss the same island would have passed: 3 > k.
  TemporalConsistency other;
  other.update(island(10, 12), o);
  other.update(island(11, 13), o);
  EXPECT_TRUE(other.update(island(12, 14), o));
  // A distance of 6 after one tolerated miss is 6 > 3 without misses.
  TemporalVerificationOptions tolerant = o;
  tolerant.max_missed_queries = 1;
  TemporalConsistency no_miss;
  no_miss.update(island(10, 12), tolerant);
  no_miss.update(island(11, 13), tolerant);
  EXPECT_FALSE(no_miss.update(island(19, 20), tolerant));
  EXPECT_EQ(no_miss.chainLength(), 1);
}

Island placed(EntryId first, EntryId last, double first_m, double last_m) {
  Island i = island(first, last);
  i.first_m = first_m;
  i.last_m = last_m;
  return i;
}

TEST(TemporalConsistency, InMetresTheIslandMovesWithTheRobot) {
  TemporalConsistency tc;
  TemporalVerificationOptions o = verification(1, 3);
  o.max_island_distance_m = 0.1;
  // Query at 10.0 m matched the first pass at [2.0, 2.2] m (ids 20..22, a
  // 0.1 m spacing); the query then drove 0.6 m: the place is now expected
  // at [2.6, 2.8] m. An island at [2.75, 2.85] m (ids 80..82 of a denser
  // stretch) overlaps it: consistent although its ids are 58 away.
  EXPECT_FALSE(tc.update(placed(20, 22, 2.0, 2.2), o, 10.0));
  EXPECT_TRUE(tc.update(placed(80, 82, 2.75, 2.85), o, 10.6));
  // Driven 0.2 m more: expected [2.95, 3.05]; an island at [3.3, 3.4] m is
  // 0.25 m away: inconsistent although its ids (83..84) are adjacent.
  EXPECT_FALSE(tc.update(placed(83, 84, 3.3, 3.4), o, 10.8));
  EXPECT_EQ(tc.chainLength(), 1);
  // Without a query odometer the ids decide: 85 is 1 id from [83, 84].
  EXPECT_TRUE(tc.update(placed(85, 85, 9.0, 9.0), o));
  EXPECT_TRUE(std::isnan(tc.lastQueryOdometer()));
}

TEST(TemporalConsistency, RestoreKeepsTheMissedCount) {
  TemporalConsistency tc;
  tc.restore(island(11, 13), 2, 1);
  EXPECT_EQ(tc.missedQueries(), 1);
  EXPECT_THROW(tc.restore(island(11, 13), 0, 1), std::invalid_argument);
  EXPECT_THROW(tc.restore(island(11, 13), 2, -1), std::invalid_argument);
  EXPECT_EQ(tc.missedQueries(), 1);
}

// Several hypotheses per query (TemporalVerificationOptions::hypotheses).
TEST(TemporalConsistency, HypothesesKeepAChainWhoseIslandAlternates) {
  // Two equally true places (the same stretch on two earlier laps): the
  // chosen island alternates between the track at 10.. and the one at 110..
  const TemporalVerificationOptions o = verification(2, 1);
  TemporalConsistency one, two;
  // Query 1 chooses A, query 2 B, query 3 A again.
  EXPECT_FALSE(one.update(island(10, 10), o));
  EXPECT_FALSE(one.update(island(111, 111), o));  // 101 ids from [10, 10]
  EXPECT_EQ(one.chainLength(), 1);
  EXPECT_FALSE(one.update(island(12, 12), o));
  EXPECT_EQ(one.chainLength(), 1);
  // Followed as two hypotheses: B2 extends B1 (chain 2), A3 extends A2
  // (chain 3 > k = 2, passes), both having been followed all along.
  EXPECT_FALSE(two.update({island(10, 10), island(110, 110)}, 0, o));
  EXPECT_EQ(two.chainLength(), 1);
  ASSERT_EQ(two.otherHypotheses().size(), 1u);
  EXPECT_EQ(two.otherHypotheses()[0].chain_length, 1);
  EXPECT_FALSE(two.update({island(111, 111), island(11, 11)}, 0, o));
  EXPECT_EQ(two.chainLength(), 2);
  EXPECT_EQ(two.otherHypotheses()[0].chain_length, 2);
  EXPECT_TRUE(two.update({island(112, 112), island(12, 12)}, 1, o));
  EXPECT_EQ(two.chainLength(), 3);
  EXPECT_EQ(two.lastIsland().first, 12u);
  EXPECT_EQ(two.otherHypotheses()[0].island.first, 112u);
}

TEST(TemporalConsistency, ALookAlikeForOneQueryDoesNotRestartTheTruePlace) {
  const TemporalVerificationOptions o = verification(2, 1);
  TemporalConsistency tc;
  tc.update({island(10, 10)}, 0, o);
  tc.update({island(11, 11)}, 0, o);
  // A look-alike at 500 wins query 3; the true place (12) is followed too.
  EXPECT_FALSE(tc.update({island(500, 500), island(12, 12)}, 0, o));
  EXPECT_EQ(tc.chainLength(), 1);
  EXPECT_EQ(tc.otherHypotheses()[0].chain_length, 3);
  // Query 4 chooses the true place again: 1 + 3, passes at once. [16, 16]
  // is 4 ids from [12, 12]: a new chain.
  EXPECT_TRUE(tc.update({island(13, 13), island(16, 16)}, 0, o));
  EXPECT_EQ(tc.chainLength(), 4);
  EXPECT_EQ(tc.otherHypotheses()[0].chain_length, 1);
  // [14, 15] is consistent with both (gaps 1 and 1): the longer chain wins.
  EXPECT_TRUE(tc.update({island(14, 15)}, 0, o));
  EXPECT_EQ(tc.chainLength(), 5);
}

TEST(TemporalConsistency, OneHypothesisIsTheSingleChain) {
  // update({island}, 0) and update(island) are the same rule.
  const TemporalVerificationOptions o = verification(2, 3);
  TemporalConsistency a, b;
  const std::vector<Island> seq{island(10, 12), island(11, 13), island(40, 41), island(42, 42),
                                island(44, 45), island(46, 46)};
  for (const Island& i : seq) {
    EXPECT_EQ(a.update(i, o), b.update(std::vector<Island>{i}, 0, o));
    EXPECT_EQ(a.chainLength(), b.chainLength());
    EXPECT_TRUE(b.otherHypotheses().empty());
  }
}

TEST(TemporalConsistency, HypothesesAreForgottenWithTheChainAndRestored) {
  const TemporalVerificationOptions o = verification(2, 1);
  TemporalConsistency tc;
  EXPECT_THROW(tc.update(std::vector<Island>{island(1, 1)}, 1, o), std::invalid_argument);
  EXPECT_THROW(tc.update(std::vector<Island>{}, 0, o), std::invalid_argument);
  tc.update({island(10, 10), island(50, 50)}, 0, o);
  tc.breakChain();
  EXPECT_TRUE(tc.otherHypotheses().empty());
  // Restored: the other hypothesis [50, 51] with chain 2 carries on.
  tc.restore(island(11, 13), 1, 0, std::nan(""), {IslandHypothesis{island(50, 51), 2}});
  EXPECT_TRUE(tc.update({island(52, 52)}, 0, o));
  EXPECT_EQ(tc.chainLength(), 3);
  EXPECT_THROW(tc.restore(island(11, 13), 0, 0, std::nan(""), {IslandHypothesis{island(50, 51), 2}}),
               std::invalid_argument);
  EXPECT_THROW(tc.restore(island(11, 13), 1, 0, std::nan(""), {IslandHypothesis{island(50, 51), 0}}),
               std::invalid_argument);
  EXPECT_EQ(tc.chainLength(), 3);  // failed restores change nothing
}

TEST(TemporalConsistency, AStandingRobotsRepeatsCountOnce) {
  // k = 2, min_step_m 0.05: queries at 0, 0.10 count (chain 2); 0.11 and
  // 0.14 are the same view again (0.01 and 0.04 m after 0.10): they pass only
  // if the chain passed, and change nothing; 0.20 counts (chain 3, passes);
  // 0.22 repeats it (passes, chain stays 3). The same queries without the
  // rule pass from the third one on.
  TemporalVerificationOptions o = verification(2, 1);
  o.min_step_m = 0.05;
  TemporalConsistency tc, every;
  const TemporalVerificationOptions plain = verification(2, 1);
  const double at[] = {0.0, 0.10, 0.11, 0.14, 0.20, 0.22};
  const bool expected[] = {false, false, false, false, true, true};
  const int chain[] = {1, 2, 2, 2, 3, 3};
  const bool expected_every[] = {false, false, true, true, true, true};
  const EntryId place[] = {10, 11, 11, 11, 12, 12};  // the island stays while it stands
  for (int i = 0; i < 6; ++i) {
    SCOPED_TRACE(at[i]);
    EXPECT_EQ(tc.update({island(place[i], place[i])}, 0, o, at[i]), expected[i]);
    EXPECT_EQ(tc.chainLength(), chain[i]);
    EXPECT_EQ(every.update({island(place[i], place[i])}, 0, plain, at[i]), expected_every[i]);
  }
  // The repeats left the last counted query in place.
  EXPECT_EQ(tc.lastQueryOdometer(), 0.20);
  EXPECT_EQ(tc.lastIsland().first, 12u);
  // Without odometers every query counts; k = 0 passes whatever.
  TemporalConsistency no_odometry;
  for (int i = 0; i < 3; ++i) no_odometry.update({island(10, 10)}, 0, o);
  EXPECT_EQ(no_odometry.chainLength(), 3);
  TemporalVerificationOptions k0 = o;
  k0.k = 0;
  TemporalConsistency zero;
  EXPECT_TRUE(zero.update({island(10, 10)}, 0, k0, 0.0));
  EXPECT_TRUE(zero.update({island(500, 500)}, 0, k0, 0.01));
}

TEST(TemporalConsistency, InvalidOptionsThrow) {
  TemporalConsistency tc;
  EXPECT_THROW(tc.update(island(1, 1), verification(-1)), InvalidParameter);
  EXPECT_THROW(tc.update(island(1, 1), verification(1, -2)), InvalidParameter);
  TemporalVerificationOptions o = verification(1);
  o.max_missed_queries = -1;
  EXPECT_THROW(tc.miss(o), InvalidParameter);
  o = verification(1);
  o.hypotheses = 0;
  EXPECT_THROW(tc.update(island(1, 1), o), InvalidParameter);
  o = verification(1);
  o.min_step_m = -0.5;
  EXPECT_THROW(tc.update(island(1, 1), o), InvalidParameter);
}

}  // namespace
}  // namespace bowg
