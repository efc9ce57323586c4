// The verified chain (verified_chain.h) on hand-worked queries and matches.
#include "bowg/detection/verified_chain.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace bowg {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// A query with its matches (entry, unique inliers), best first.
ChainQuery query(EntryId id, double odometer, std::vector<ChainMatch> matches,
                 bool published = false) {
  ChainQuery q;
  q.query = id;
  q.odometer = odometer;
  for (const ChainMatch& m : matches) q.add(m);
  q.published = published;
  return q;
}

ChainMatch match(EntryId entry, int unique = 30) {
  ChainMatch m;
  m.entry = entry;
  m.unique_inliers = unique;
  return m;
}

// Everything a step needs: entries without odometers unless set, no links.
struct Fixture {
  std::vector<double> odometers = std::vector<double>(300, kNaN);
  PlaceLinks links;
  TemporalVerificationOptions temporal;
  double drift = 0.25;
  ChainContext context() const { return ChainContext{odometers, links, temporal, drift}; }
};

TEST(VerifiedChain, StepInMetresAllowsTheToleranceAndTheDrift) {
  Fixture f;
  f.temporal.max_island_distance_m = 0.25;
  // The query drove 1 m (10 -> 11): the match must move 1 m within
  // 0.25 + 0.25 * 1 = 0.5 m. No entry has a neighbour with an odometer, so
  // nothing is added for the spacing.
  f.odometers[30] = 2.0;
  f.odometers[50] = 3.5;   // moved 1.5: on the bound, follows
  f.odometers[60] = 3.75;  // moved 1.75: does not
  f.odometers[70] = 2.5;   // moved 0.5: on the bound, follows
  f.odometers[80] = 2.25;  // moved 0.25: does not
  const ChainContext c = f.context();
  EXPECT_TRUE(chainStep(40, 10.0, 30, 41, 11.0, 50, c));
  EXPECT_FALSE(chainStep(40, 10.0, 30, 41, 11.0, 60, c));
  EXPECT_TRUE(chainStep(40, 10.0, 30, 41, 11.0, 70, c));
  EXPECT_FALSE(chainStep(40, 10.0, 30, 41, 11.0, 80, c));
}

TEST(VerifiedChain, StepInMetresAllowsForTheSpacingOfThePass) {
  Fixture f;
  f.drift = 0.0;
  f.temporal.max_island_distance_m = 0.1;
  // A pass with keyframes 15 cm apart: each match stands for a place within
  // 0.15 / 2 = 0.075 m of it, so a step allows 0.1 + 0.075 + 0.075 = 0.25.
  f.odometers[10] = 1.00;
  f.odometers[11] = 1.15;
  f.odometers[12] = 1.30;
  f.odometers[13] = 1.45;
  const ChainContext c = f.context();
  // The query drove 0.15 m (5.00 -> 5.15).
  EXPECT_TRUE(chainStep(40, 5.0, 11, 41, 5.15, 11, c));   // stayed: |0 - 0.15| = 0.15
  EXPECT_TRUE(chainStep(40, 5.0, 11, 41, 5.15, 13, c));   // two on: |0.30 - 0.15| = 0.15
  EXPECT_FALSE(chainStep(40, 5.0, 10, 41, 5.15, 13, c));  // three on: |0.45 - 0.15| = 0.30
  EXPECT_FALSE(chainStep(40, 5.0, 12, 41, 5.15, 11, c));  // back: |-0.15 - 0.15| = 0.30
  // A gap of 1 m (a lost stretch) adds at most max_island_distance_m per
  // match: 0.1 + 0.1 + 0.1 = 0.3 for a match that stayed.
  f.odometers[20] = 2.0;
  f.odometers[21] = 3.0;
  EXPECT_TRUE(chainStep(40, 5.0, 20, 41, 5.3, 20, f.context()));
  EXPECT_FALSE(chainStep(40, 5.0, 20, 41, 5.31, 20, f.context()));
}

TEST(VerifiedChain, StepInKeyframesAllowsASpeedRatioOfTwoAndOneKeyframe) {
  Fixture f;  // no odometers: ids
  const ChainContext c = f.context();
  // Two queries on (10 -> 12): the match may advance from 2 / 2 - 1 = 0 to
  // 2 * 2 + 1 = 5 keyframes.
  EXPECT_FALSE(chainStep(10, kNaN, 20, 12, kNaN, 19, c));
  EXPECT_TRUE(chainStep(10, kNaN, 20, 12, kNaN, 20, c));
  EXPECT_TRUE(chainStep(10, kNaN, 20, 12, kNaN, 25, c));
  EXPECT_FALSE(chainStep(10, kNaN, 20, 12, kNaN, 26, c));
  // One query on: from -0.5 to 3.
  EXPECT_TRUE(chainStep(10, kNaN, 20, 11, kNaN, 20, c));
  EXPECT_TRUE(chainStep(10, kNaN, 20, 11, kNaN, 23, c));
  EXPECT_FALSE(chainStep(10, kNaN, 20, 11, kNaN, 24, c));
  // Metres need every odometer: one missing falls back to ids.
  f.temporal.max_island_distance_m = 0.1;
  f.odometers[20] = 1.0;
  EXPECT_TRUE(chainStep(10, 5.0, 20, 11, 5.04, 23, f.context()));
}

TEST(VerifiedChain, LinkedPlacesFollowAcrossLaps) {
  Fixture f;
  // Lap 2's entry 105 closed a loop to lap 1's entry 6: one place, whose
  // first entry is 6. The match jumps from lap 1 (5) to lap 2 (105) as the
  // query moves one keyframe on: 6 - 5 = 1 keyframe, a step.
  f.links.link(105, 6);
  EXPECT_FALSE(chainStep(210, kNaN, 5, 211, kNaN, 105, f.context()));
  f.temporal.linked_places = true;
  EXPECT_TRUE(chainStep(210, kNaN, 5, 211, kNaN, 105, f.context()));
  // Back from lap 2 to lap 1 as well; an unlinked lap-2 entry does not.
  EXPECT_TRUE(chainStep(211, kNaN, 105, 212, kNaN, 7, f.context()));
  EXPECT_FALSE(chainStep(210, kNaN, 5, 211, kNaN, 104, f.context()));
  // In metres the places' first entries' odometers are compared.
  f.temporal.max_island_distance_m = 0.1;
  f.drift = 0.0;
  f.odometers[5] = 1.0;
  f.odometers[6] = 1.2;
  f.odometers[105] = 15.0;
  EXPECT_TRUE(chainStep(210, 30.0, 5, 211, 30.2, 105, f.context()));
  EXPECT_FALSE(chainStep(210, 30.0, 5, 211, 30.5, 105, f.context()));
}

// Queries 10-13 before the current 14, ids one keyframe apart, every match
// one entry on: a chain of 3 with K = 3.
VerifiedChainOptions options(int length, int min_unique, int max_missed = 1) {
  VerifiedChainOptions o;
  o.length = length;
  o.min_unique_inliers = min_unique;
  o.max_missed = max_missed;
  return o;
}

TEST(VerifiedChain, PassesWhenEnoughUniqueMatchesLeadToTheMatch) {
  Fixture f;
  VerifiedChain chain;
  chain.push(query(10, kNaN, {match(3)}));
  chain.push(query(11, kNaN, {match(4)}));
  chain.push(query(12, kNaN, {}));  // no verified match: stepped over
  chain.push(query(13, kNaN, {match(6)}));
  const ChainQuery current = query(14, kNaN, {match(7)});
  EXPECT_TRUE(chain.passes(current, options(3, 25), f.context()));
  EXPECT_FALSE(chain.passes(current, options(4, 25), f.context()));  // only 3 before
  // The current match needs its unique inliers too.
  EXPECT_FALSE(chain.passes(query(14, kNaN, {match(7, 24)}), options(3, 25), f.context()));
  EXPECT_TRUE(chain.passes(query(14, kNaN, {match(7, 24)}), options(3, 24), f.context()));
  // A query without any match fails.
  EXPECT_FALSE(chain.passes(query(14, kNaN, {}), options(0, 0), f.context()));
  EXPECT_TRUE(chain.passes(query(14, kNaN, {match(7)}), options(0, 0), f.context()));
}

// Where the odometry gate judged the loop's match, the chain's unique
// inliers count on average (25 here: 125 over five matches), each at least
// 25 / 2 = 12.
TEST(VerifiedChain, WhereTheGateJudgedTheMatchUniqueInliersCountOnAverage) {
  Fixture f;
  const auto chainOf = [](int a, int b, int c, int d) {
    VerifiedChain chain;
    chain.push(query(10, kNaN, {match(3, a)}));
    chain.push(query(11, kNaN, {match(4, b)}));
    chain.push(query(12, kNaN, {match(5, c)}));
    chain.push(query(13, kNaN, {match(6, d)}));
    return chain;
  };
  ChainContext gated = f.context();
  gated.position_gated = true;
  const VerifiedChainOptions o = options(4, 25);
  // 20 + 30 + 13 + 25 + 37 = 125.
  EXPECT_TRUE(chainOf(20, 30, 13, 25).passes(query(14, kNaN, {match(7, 37)}), o, gated));
  EXPECT_FALSE(chainOf(20, 30, 13, 25).passes(query(14, kNaN, {match(7, 37)}), o, f.context()));
  // 124: one short.
  EXPECT_FALSE(chainOf(20, 30, 13, 25).passes(query(14, kNaN, {match(7, 36)}), o, gated));
  // 125 with one match at 12 passes, with one at 11 does not.
  EXPECT_TRUE(chainOf(20, 30, 12, 25).passes(query(14, kNaN, {match(7, 38)}), o, gated));
  EXPECT_FALSE(chainOf(20, 30, 11, 25).passes(query(14, kNaN, {match(7, 39)}), o, gated));
  // Every match at 25 passes either way.
  EXPECT_TRUE(chainOf(25, 25, 25, 25).passes(query(14, kNaN, {match(7, 25)}), o, f.context()));
}

TEST(VerifiedChain, MissesALookAlikeOrTooFewUniqueInliersEndIt) {
  Fixture f;
  {
    VerifiedChain chain;  // two queries in a row without a match, one allowed
    chain.push(query(10, kNaN, {match(3)}));
    chain.push(query(11, kNaN, {match(4)}));
    chain.push(query(12, kNaN, {}));
    chain.push(query(13, kNaN, {}));
    chain.push(query(14, kNaN, {match(7)}));
    EXPECT_FALSE(chain.passes(query(15, kNaN, {match(8)}), options(3, 25), f.context()));
    EXPECT_TRUE(chain.passes(query(15, kNaN, {match(8)}), options(3, 25, 2), f.context()));
  }
  {
    VerifiedChain chain;  // a look-alike 12 sections away won query 12
    chain.push(query(10, kNaN, {match(3)}));
    chain.push(query(11, kNaN, {match(4)}));
    chain.push(query(12, kNaN, {match(40)}));
    chain.push(query(13, kNaN, {match(6)}));
    EXPECT_FALSE(chain.passes(query(14, kNaN, {match(7)}), options(3, 25), f.context()));
    EXPECT_TRUE(chain.passes(query(14, kNaN, {match(7)}), options(1, 25), f.context()));
  }
  {
    VerifiedChain chain;  // ... unless its runner-up continues the chain
    chain.push(query(10, kNaN, {match(3)}));
    chain.push(query(11, kNaN, {match(4)}));
    chain.push(query(12, kNaN, {match(40), match(5)}));
    chain.push(query(13, kNaN, {match(6)}));
    EXPECT_TRUE(chain.passes(query(14, kNaN, {match(7)}), options(3, 25), f.context()));
  }
  {
    VerifiedChain chain;  // a match of the chain with too few unique inliers
    chain.push(query(10, kNaN, {match(3)}));
    chain.push(query(11, kNaN, {match(4, 10)}));
    chain.push(query(12, kNaN, {match(5)}));
    EXPECT_FALSE(chain.passes(query(13, kNaN, {match(6)}), options(3, 25), f.context()));
    EXPECT_TRUE(chain.passes(query(13, kNaN, {match(6)}), options(3, 10), f.context()));
    EXPECT_TRUE(chain.passes(query(13, kNaN, {match(6)}), options(1, 25), f.context()));
  }
  {
    VerifiedChain chain;  // of two that follow, the one with unique inliers
    chain.push(query(10, kNaN, {match(3)}));
    chain.push(query(11, kNaN, {match(5, 0), match(4, 30)}));
    chain.push(query(12, kNaN, {match(5)}));
    EXPECT_TRUE(chain.passes(query(13, kNaN, {match(6)}), options(3, 25), f.context()));
  }
}

// A look-alike that won a query is stepped over with strays allowed: it
// counts against both the strays and the queries missed in a row. Only
// where the steps are in metres (the current query has an odometer).
TEST(VerifiedChain, StraysAllowedStepOverALookAlike) {
  Fixture f;
  // Entries 10 cm apart, queries too; a step allows 0.1 m plus half a gap
  // (0.05 m) for each match: 0.2 m.
  f.drift = 0.0;
  f.temporal.max_island_distance_m = 0.1;
  for (EntryId e = 0; e < 60; ++e) f.odometers[e] = 0.1 * e;
  const auto at = [](EntryId id, std::vector<ChainMatch> matches) {
    return query(id, 0.1 * id, matches);
  };
  const auto withStrays = [](int strays, int max_missed) {
    VerifiedChainOptions o = options(3, 25, max_missed);
    o.max_strays = strays;
    return o;
  };
  VerifiedChain chain;
  chain.push(at(10, {match(3)}));
  chain.push(at(11, {match(4)}));
  chain.push(at(12, {match(40)}));  // the look-alike, 3.4 m off
  chain.push(at(13, {match(6)}));
  const ChainQuery current = at(14, {match(7)});
  EXPECT_FALSE(chain.passes(current, withStrays(0, 1), f.context()));
  // 13 -> 14 follows; 12 stepped over; 11 -> 13: driven 0.2 m, moved
  // 0.2 m; 10 -> 11 follows: three taken.
  EXPECT_TRUE(chain.passes(current, withStrays(1, 1), f.context()));
  // A stray is a missed query too: none allowed in a row, it ends the walk.
  EXPECT_FALSE(chain.passes(current, withStrays(1, 0), f.context()));
  // Without odometers on the queries the steps are in ids, and a stray
  // needs the rate of two queries or more behind it
  // (StraysInIdsFollowTheChainsRate): here one.
  VerifiedChain images_only;
  for (const ChainQuery& q :
       {at(10, {match(3)}), at(11, {match(4)}), at(12, {match(40)}), at(13, {match(6)})}) {
    images_only.push(query(q.query, kNaN, {q.match[0]}));
  }
  EXPECT_FALSE(images_only.passes(query(14, kNaN, {match(7)}), withStrays(1, 1), f.context()));
  // Nor without a distance tolerance, odometers or not.
  f.temporal.max_island_distance_m = 0.0;
  EXPECT_FALSE(chain.passes(current, withStrays(1, 1), f.context()));
  f.temporal.max_island_distance_m = 0.1;
  // Nor where the match after the stray has no odometer.
  f.odometers[4] = kNaN;
  EXPECT_FALSE(chain.passes(current, withStrays(1, 1), f.context()));
  f.odometers[4] = 0.4;
  EXPECT_TRUE(chain.passes(current, withStrays(1, 1), f.context()));
  // Two look-alikes, one stray allowed: the second ends the walk.
  chain.push(at(15, {match(50)}));
  chain.push(at(16, {match(9)}));
  const ChainQuery later = at(17, {match(10)});
  EXPECT_FALSE(chain.passes(later, withStrays(1, 1), f.context()));
  // 16 -> 17; 15 stepped over; 13 -> 16 (0.3 m both); 12 stepped over;
  // 11 -> 13 (0.2 m both): three taken with two strays.
  EXPECT_TRUE(chain.passes(later, withStrays(2, 1), f.context()));
  // A stray next to a query without a match: two missed in a row.
  VerifiedChain gap;
  gap.push(at(10, {match(3)}));
  gap.push(at(11, {match(4)}));
  gap.push(at(12, {}));
  gap.push(at(13, {match(40)}));
  gap.push(at(14, {match(7)}));
  EXPECT_FALSE(gap.passes(at(15, {match(8)}), withStrays(1, 1), f.context()));
  EXPECT_TRUE(gap.passes(at(15, {match(8)}), withStrays(1, 2), f.context()));
}

TEST(VerifiedChain, StraysInIdsFollowTheChainsRate) {
  Fixture f;  // no odometers: every step in keyframe ids
  VerifiedChainOptions o = options(3, 25, 1);
  o.max_strays = 1;
  // Queries 10-14 with the matches given, query 11's a look-alike's.
  const auto walk = [&](EntryId m10, EntryId m12 = 15, EntryId m13 = 16, EntryId m14 = 17) {
    VerifiedChain chain;
    chain.push(query(10, kNaN, {match(m10)}));
    chain.push(query(11, kNaN, {match(40)}));
    chain.push(query(12, kNaN, {match(m12)}));
    chain.push(query(13, kNaN, {match(m13)}));
    return chain.passes(query(14, kNaN, {match(m14)}), o, f.context());
  };
  // 13 -> 14 and 12 -> 13 follow; 11 stepped over. The matches advanced
  // (17 - 15) / (14 - 12) = 1 keyframe a query, so across 12 -> 10 (two
  // queries) entry 15 - 2 = 13 is expected, within 1.5 keyframes.
  EXPECT_TRUE(walk(13));
  EXPECT_TRUE(walk(12));  // advanced 3: off by 1
  // Advanced 4: off by 2, though chainStep's band (0-5 keyframes across
  // two queries) allows it.
  EXPECT_FALSE(walk(11));
  EXPECT_TRUE(chainStep(10, kNaN, 11, 12, kNaN, 15, f.context()));
  EXPECT_FALSE(walk(10));  // advanced 5
  // The rate of a robot standing still: nothing may advance across.
  EXPECT_TRUE(walk(17, 17, 17, 17));
  EXPECT_FALSE(walk(15, 17, 17, 17));
}

TEST(VerifiedChain, APublishedLoopCarriesTheChain) {
  Fixture f;
  VerifiedChain chain;
  chain.push(query(10, kNaN, {match(3, 0)}, true));  // published, no unique inliers
  chain.push(query(11, kNaN, {match(4, 0)}));
  // Its match leads to the published loop: passes whatever the length and
  // the unique inliers.
  EXPECT_TRUE(chain.passes(query(12, kNaN, {match(5, 0)}), options(5, 25), f.context()));
  // A match that does not lead to it does not.
  EXPECT_FALSE(chain.passes(query(12, kNaN, {match(30, 40)}), options(5, 25), f.context()));
  // A published loop reached through a runner-up does not count: only what
  // was published carries.
  VerifiedChain other;
  other.push(query(10, kNaN, {match(60), match(3)}, true));
  EXPECT_FALSE(other.passes(query(11, kNaN, {match(4)}), options(2, 25), f.context()));
}

TEST(VerifiedChain, AStandingRobotCountsOnce) {
  Fixture f;
  f.temporal.max_island_distance_m = 0.1;
  f.temporal.min_step_m = 0.02;
  for (EntryId e = 0; e < 20; ++e) f.odometers[e] = 0.1 * e;
  VerifiedChain chain;
  // Queries 40-43 stand at 10.0 m, matching entry 5 (0.5 m) again and again.
  for (EntryId q = 40; q < 44; ++q) chain.push(query(q, 10.0, {match(5)}));
  const ChainQuery moved = query(44, 10.1, {match(6)});
  EXPECT_TRUE(chain.passes(moved, options(1, 25), f.context()));
  EXPECT_FALSE(chain.passes(moved, options(2, 25), f.context()));
  // Without the step every repeat counts.
  f.temporal.min_step_m = 0.0;
  EXPECT_TRUE(chain.passes(moved, options(4, 25), f.context()));
}

TEST(VerifiedChain, RemembersTheLast64Queries) {
  Fixture f;
  VerifiedChain chain;
  for (EntryId q = 0; q < 100; ++q) chain.push(query(q, kNaN, {match(0)}));
  EXPECT_EQ(chain.size(), 64u);
  chain.clear();
  EXPECT_EQ(chain.size(), 0u);
}

}  // namespace
}  // namespace bowg
