// Database queries: the inverse-index scores equal the direct formulas (word
// score = scoreBowVectors() for every ScoringType; group score = eq. 3 on
// eq. 1 weights with the table's current IDF), hand-worked group scores,
// group counts beyond a posting's byte, the recent-exclusion limit, entries
// out of the index, the caller's scratch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <set>
#include <stdexcept>

#include "bowg/database/database.h"
#include "bowg/scoring/distribution.h"
#include "bowg/scoring/word_groups.h"
#include "bowg/vocabulary/vocabulary.h"
#include "database_fixture.h"
#include "synthetic_corridor.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace {

using namespace database_fixture;

// The inverse index keeps BoW weights as floats (24 bits): scores through it
// agree with the double-precision vectors to ~1e-7 of their weights.
const double kFloatWeightTolerance = 1e-6;

class DatabaseScoring : public ::testing::TestWithParam<ScoringType> {};

TEST_P(DatabaseScoring, InverseIndexWordScoreEqualsScoreBowVectors) {
  const ScoringType s = GetParam();
  Database db(vocabulary(), s, 2, 8);
  BowVector qbow;
  const CountedEntry qe = fill(&db, &qbow);
  const DatabaseQuery q = db.makeQuery(qbow, qe.counted, qe.entry.points.unpack(), 320, 240, false);
  const EntryId limit = 25;
  const std::vector<EntryScores> scores = db.query(q, limit, /*with_groups=*/false);
  // Exactly the entries < limit that share a word with the query.
  std::set<EntryId> expected;
  for (EntryId id = 0; id < limit; ++id) {
    for (const auto& w : db.bow(id)) {
      if (std::binary_search(
              q.bow.begin(), q.bow.end(), BowEntry(w.first, 0.0),
              [](const BowEntry& a, const BowEntry& b) { return a.first < b.first; })) {
        expected.insert(id);
      }
    }
  }
  ASSERT_EQ(scores.size(), expected.size());
  ASSERT_GT(scores.size(), 5u);
  // In ascending entry order (read off the touched flags: a large share of
  // the 25 entries is touched).
  for (std::size_t i = 1; i < scores.size(); ++i) EXPECT_LT(scores[i - 1].entry, scores[i].entry);
  for (const EntryScores& e : scores) {
    EXPECT_TRUE(expected.count(e.entry));
    EXPECT_NEAR(e.s_w, scoreBowVectors(s, q.bow, db.bow(e.entry)), kFloatWeightTolerance)
        << toString(s) << " entry " << e.entry;
    EXPECT_NEAR(e.s_w, db.score(q, e.entry).s_w, kFloatWeightTolerance);
  }
}

INSTANTIATE_TEST_SUITE_P(AllScoringTypes, DatabaseScoring,
                         ::testing::Values(ScoringType::kL1, ScoringType::kL2,
                                           ScoringType::kChiSquare, ScoringType::kKl,
                                           ScoringType::kBhattacharyya, ScoringType::kDotProduct));

TEST(Database, InverseIndexGroupScoreEqualsDirectEq3WithCurrentIdf) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  BowVector qbow;
  std::vector<GroupVector> added;
  const CountedEntry qe = fill(&db, &qbow, &added);
  const DatabaseQuery q = db.makeQuery(qbow, qe.counted, qe.entry.points.unpack(), 320, 240, false);
  const std::vector<EntryScores> scores = db.query(q, 30, true);
  int with_groups = 0;
  for (const EntryScores& e : scores) {
    const GroupVector refined = refineGroupWeights(added[e.entry], db.groupTable());
    EXPECT_NEAR(e.s_g, groupScore(q.refined_groups, refined), 1e-12);
    EXPECT_NEAR(e.s_g, db.score(q, e.entry).s_g, 1e-12);
    if (e.s_g > 0) ++with_groups;
  }
  EXPECT_GT(with_groups, 3);
}

// makeQuery keeps the IDFs it read; query() and score() reuse them while
// the table stands, bit for bit what the table gives, and read the table
// again once it has changed (the query then scores with the CURRENT IDF).
TEST(Database, QueryIdfsAreReusedOnlyWhileTheTableStands) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  BowVector qbow;
  std::vector<GroupVector> added;
  const CountedEntry qe = fill(&db, &qbow, &added);
  DatabaseQuery q = db.makeQuery(qbow, qe.counted, qe.entry.points.unpack(), 320, 240, false);
  ASSERT_EQ(q.group_idf.size(), q.refined_groups.size());
  ASSERT_FALSE(q.group_idf.empty());
  for (std::size_t i = 0; i < q.group_idf.size(); ++i)
    EXPECT_EQ(q.group_idf[i], db.groupTable().idf(q.refined_groups[i].first));
  DatabaseQuery unread = q;  // no IDFs: the table is read for each group
  unread.group_idf.clear();
  const auto expectSameScores = [&](const char* when) {
    const std::vector<EntryScores> a = db.query(q, 30, true), b = db.query(unread, 30, true);
    ASSERT_EQ(a.size(), b.size()) << when;
    int with_groups = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].entry, b[i].entry) << when;
      EXPECT_EQ(a[i].s_g, b[i].s_g) << when << " entry " << a[i].entry;
      EXPECT_EQ(db.score(q, a[i].entry).s_g, db.score(unread, a[i].entry).s_g) << when;
      EXPECT_EQ(
          db.score(q, a[i].entry).s_g,
          groupScore(q.refined_groups, refineGroupWeights(added[a[i].entry], db.groupTable())))
          << when;
      if (a[i].s_g > 0) ++with_groups;
    }
    EXPECT_GT(with_groups, 3) << when;
  };
  expectSameScores("table unchanged");
  // The table moves on (another keyframe's groups): q's IDFs are stale and
  // must not be used. Every query group's IDF changes, so reusing them
  // would change the scores.
  db.addToGroupTable(added[0]);
  expectSameScores("table changed");
}

// Hand-worked eq. 1 and eq. 3 through the database (groups only, no words).
//   A raw {0:2, 1:2}, B raw {1:1, 2:3}, query raw {1:2, 2:2}, all in the table:
//   cumulative: g0 = 2, g1 = 2+1+2 = 5, g2 = 3+2 = 5; total = 4+4+4 = 12.
//   IDF: g0 log(12/2) = log 6, g1 = g2 = log(12/5) = log 2.4 (= 0.87547).
//   TF:  A {0:.5, 1:.5}, B {1:.25, 2:.75}, Q {1:.5, 2:.5}.
//   dot(Q, A) = (.5 log2.4)(.5 log2.4)                   = .25 log(2.4)^2 = 0.19161
//   dot(Q, B) = (.5)(.25) log(2.4)^2 + (.5)(.75) log(2.4)^2 = .5 log(2.4)^2 = 0.38322
//   eq. 3: s_g = 1 - sqrt(1 - dot): A 0.10090, B 0.21465.
// Then C raw {0:4} joins: cumulative g0 = 6, total = 16; the scores use the
// new IDF log(16/5) (= 1.16315): dot(Q, A) = .25 log(3.2)^2 = 0.33823.
TEST(Database, HandWorkedGroupScores) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  EXPECT_EQ(addGroups(&db, 1, {{0, 2}, {1, 2}}), 0u);
  EXPECT_EQ(addGroups(&db, 2, {{1, 1}, {2, 3}}), 1u);
  const GroupVector q_raw{{1, 2}, {2, 2}};
  const CountedGroups q_counted = db.addToGroupTable(q_raw);
  DatabaseQuery q = db.makeQuery({}, q_counted, {}, 0, 0, false);
  const double l24 = std::log(2.4);
  std::vector<EntryScores> s = db.query(q, 2, true);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_NEAR(s[0].s_g, 1 - std::sqrt(1 - 0.25 * l24 * l24), 1e-12);
  EXPECT_NEAR(s[0].s_g, 0.10090, 1e-5);
  EXPECT_NEAR(s[1].s_g, 1 - std::sqrt(1 - 0.5 * l24 * l24), 1e-12);
  EXPECT_NEAR(s[1].s_g, 0.21465, 1e-5);
  EXPECT_EQ(s[0].s_w, 0.0);  // no shared word
  // The limit excludes entry 1.
  s = db.query(q, 1, true);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].entry, 0u);
  // Without groups nothing is shared.
  EXPECT_TRUE(db.query(q, 2, false).empty());

  addGroups(&db, 3, {{0, 4}});
  q = db.makeQuery({}, q_counted, {}, 0, 0, false);
  const double l32 = std::log(3.2);
  s = db.query(q, 3, true);
  ASSERT_EQ(s.size(), 2u);  // C shares no group with the query
  EXPECT_NEAR(s[0].s_g, 1 - std::sqrt(1 - 0.25 * l32 * l32), 1e-12);
  EXPECT_NEAR(s[0].s_g, db.score(q, 0).s_g, 1e-12);
}

// A posting keeps a group count in 8 bits and counts from 255 up in the
// database's overflow table. The hand-worked case above with every count
// times 300 (A {0:600, 1:600}, B {1:300, 2:900}, query {1:600, 2:600}): TF
// and the IDF ratios are unchanged, so are the scores; counts read back
// exactly on both sides of the byte's limit.
TEST(Database, GroupCountsBeyondAPostingsByteScoreAsSmallOnes) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  const GroupVector a{{0, 600}, {1, 600}}, b{{1, 300}, {2, 900}};
  addGroups(&db, 1, a);
  addGroups(&db, 2, b);
  const GroupVector q_raw{{1, 600}, {2, 600}};
  const DatabaseQuery q = db.makeQuery({}, db.addToGroupTable(q_raw), {}, 0, 0, false);
  const double l24 = std::log(2.4);
  const std::vector<EntryScores> s = db.query(q, 2, true);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_NEAR(s[0].s_g, 1 - std::sqrt(1 - 0.25 * l24 * l24), 1e-12);
  EXPECT_NEAR(s[1].s_g, 1 - std::sqrt(1 - 0.5 * l24 * l24), 1e-12);
  EXPECT_EQ(db.rawGroups(0), a);
  EXPECT_EQ(db.rawGroups(1), b);
  // 254 fits the byte; 255 and 256 go to the table; 16,777,215 = 2^24 - 1
  // is the largest count add() takes.
  const GroupVector c{{3, 254}, {4, 255}, {5, 256}, {6, 16777215}};
  addGroups(&db, 3, c);
  EXPECT_EQ(db.rawGroups(2), c);
  EXPECT_EQ(db.rawGroups(1), b);
  // Each entry reads its own records, also with an entry without any
  // between two that have some, and the same words overflowing again.
  const GroupVector d{{1, 3}, {4, 7}}, e{{4, 400}, {6, 1000}};
  addGroups(&db, 4, d);
  addGroups(&db, 5, e);
  EXPECT_EQ(db.rawGroups(3), d);
  EXPECT_EQ(db.rawGroups(4), e);
  EXPECT_EQ(db.rawGroups(2), c);
  EXPECT_EQ(db.rawGroups(0), a);
}

// The same corridor keyframes in two databases, every third one out of the
// index in the second: each entry scores the same in both, and a query
// there returns exactly the first one's candidates that are indexed.
TEST(Database, QueriesSkipEntriesOutOfTheIndexAndNothingElse) {
  Database all(vocabulary(), ScoringType::kL1, 2, 8), some(vocabulary(), ScoringType::kL1, 2, 8);
  const testing::Corridor c = testing::makeCorridor(30, 50, 21);
  std::mt19937_64 rng(4);
  for (int i = 0; i < 30; ++i) {
    BowVector bow;
    BuiltEntry b = entryFromKeyframe(all.vocabulary(),
                                     testing::observeCorridor(c, 0.5 * i, 1.0 + i, rng, 2), &bow);
    CountedGroups in_all = all.addToGroupTable(b.raw_groups);
    CountedGroups in_some = some.addToGroupTable(b.raw_groups);
    all.add(b.entry, std::move(in_all));
    b.entry.searchable = i % 3 != 1;
    some.add(std::move(b.entry), std::move(in_some));
  }
  EXPECT_EQ(some.searchableCount(), 20u);
  BowVector qbow;
  const BuiltEntry qe =
      entryFromKeyframe(all.vocabulary(), testing::observeCorridor(c, 3.2, 100.0, rng, 2), &qbow);
  const CountedGroups in_all = all.addToGroupTable(qe.raw_groups);
  const CountedGroups in_some = some.addToGroupTable(qe.raw_groups);
  const std::vector<ImagePoint> points = qe.entry.points.unpack();
  const DatabaseQuery qa = all.makeQuery(qbow, in_all, points, 320, 240, true);
  const DatabaseQuery qs = some.makeQuery(qbow, in_some, points, 320, 240, true);
  std::vector<EntryScores> expected;
  for (const EntryScores& e : all.query(qa, 30, true)) {
    if (e.entry % 3 != 1) expected.push_back(e);
  }
  const std::vector<EntryScores> got = some.query(qs, 30, true);
  ASSERT_EQ(got.size(), expected.size());
  ASSERT_GT(got.size(), 5u);
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].entry, expected[i].entry);
    EXPECT_EQ(got[i].s_w, expected[i].s_w);
    EXPECT_EQ(got[i].s_g, expected[i].s_g);
    EXPECT_EQ(got[i].s_d, expected[i].s_d);
  }
  for (EntryId id = 0; id < 30; ++id) {
    const EntryScores x = all.score(qa, id), y = some.score(qs, id);
    EXPECT_EQ(x.s_w, y.s_w) << id;
    EXPECT_EQ(x.s_g, y.s_g) << id;
    EXPECT_EQ(x.s_d, y.s_d) << id;
    EXPECT_EQ(all.rawGroups(id), some.rawGroups(id)) << id;
  }
}

TEST(Database, PostingsPackTheEntryAndTheGroupCodeInOneWord) {
  EXPECT_EQ(sizeof(Posting), 8u);
  EXPECT_EQ(kMaxEntries, 16777216u);
  const Posting p{0xABCDEFu | 17u << Posting::kEntryBits, 0.5f};
  EXPECT_EQ(p.entry(), 0xABCDEFu);
  EXPECT_EQ(p.groupCode(), 17u);
}

// A query touching few of many entries: the touched ids are sorted. Entry i
// holds the one word w_i; the query holds the words of entries 30 and 5, the
// lower word first, so the entries are touched in the order 30, 5.
TEST(Database, FewTouchedEntriesComeOutInAscendingOrder) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  const Vocabulary& voc = *vocabulary();
  std::vector<WordId> words;
  for (WordId w = 0; words.size() < 40; ++w) {
    if (voc.wordWeight(w) > 0) words.push_back(w);
  }
  for (std::size_t i = 0; i < 40; ++i) {
    DatabaseEntry e;
    e.stamp = 1.0 + static_cast<double>(i);
    // Entry 30 gets the lowest word, entry 5 a higher one.
    e.words = PackedWords({words[i == 30 ? 0 : i == 0 ? 30 : i]});
    e.points = PackedPoints(std::vector<ImagePoint>(1), 0.f);
    e.descriptors.resize(1);
    db.add(e, db.addToGroupTable({}));
  }
  const BowVector qbow = voc.bowFromWords({words[0], words[5]});
  const DatabaseQuery q = db.makeQuery(qbow, db.addToGroupTable({}), {}, 0, 0, false);
  const std::vector<EntryScores> s = db.query(q, 40, false);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].entry, 5u);
  EXPECT_EQ(s[1].entry, 30u);
}

TEST(Database, ScoringChangeRenormalisesAndReindexes) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  BowVector qbow;
  const CountedEntry qe = fill(&db, &qbow);
  db.setScoring(ScoringType::kL2);
  const DatabaseQuery q = db.makeQuery(qbow, qe.counted, qe.entry.points.unpack(), 320, 240, false);
  std::size_t scored = 0;
  for (const EntryScores& e : db.query(q, 30, false)) {
    BowVector a = qbow, b = db.bow(e.entry);
    normaliseBowVector(ScoringType::kL2, &a);
    normaliseBowVector(ScoringType::kL2, &b);
    EXPECT_NEAR(e.s_w, scoreBowVectors(ScoringType::kL2, a, b), kFloatWeightTolerance);
    ++scored;
  }
  EXPECT_GT(scored, 5u);
}

// The caller's scratch: one reused across queries of two databases of other
// sizes and limits scores exactly as a fresh one (a query leaves every
// accumulator and flag at 0 again).
TEST(Database, AReusedQueryScratchScoresAsAFreshOne) {
  Database big(vocabulary(), ScoringType::kL1, 2, 8), small(vocabulary(), ScoringType::kL2, 2, 8);
  const testing::Corridor c = testing::makeCorridor(30, 50, 21);
  std::mt19937_64 rng(9);
  for (int i = 0; i < 30; ++i) {
    BowVector bow;
    BuiltEntry b = entryFromKeyframe(big.vocabulary(),
                                     testing::observeCorridor(c, 0.5 * i, 1.0 + i, rng, 2), &bow);
    CountedGroups in_big = big.addToGroupTable(b.raw_groups);
    if (i < 12) small.add(b.entry, small.addToGroupTable(b.raw_groups));
    big.add(std::move(b.entry), std::move(in_big));
  }
  BowVector qbow;
  const BuiltEntry qe =
      entryFromKeyframe(big.vocabulary(), testing::observeCorridor(c, 3.2, 100.0, rng, 2), &qbow);
  const CountedGroups in_big = big.addToGroupTable(qe.raw_groups);
  const CountedGroups in_small = small.addToGroupTable(qe.raw_groups);
  const std::vector<ImagePoint> points = qe.entry.points.unpack();
  const DatabaseQuery qb = big.makeQuery(qbow, in_big, points, 320, 240, true);
  const DatabaseQuery qs = small.makeQuery(qbow, in_small, points, 320, 240, true);
  QueryScratch scratch;
  const auto same = [](const std::vector<EntryScores>& a, const std::vector<EntryScores>& b) {
    if (a.size() != b.size() || a.empty()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].entry != b[i].entry || a[i].s_w != b[i].s_w || a[i].s_g != b[i].s_g ||
          a[i].s_d != b[i].s_d) {
        return false;
      }
    }
    return true;
  };
  for (int round = 0; round < 2; ++round) {
    EXPECT_TRUE(same(big.query(qb, 30, true, &scratch), big.query(qb, 30, true)));
    EXPECT_TRUE(same(big.query(qb, 17, false, &scratch), big.query(qb, 17, false)));
    EXPECT_TRUE(same(small.query(qs, 12, true, &scratch), small.query(qs, 12, true)));
  }
  for (const QueryScratch::Sums& v : scratch.sums) {
    EXPECT_EQ(v.word, 0.0);
    EXPECT_EQ(v.group, 0.0);
  }
  for (std::uint8_t f : scratch.touched_flag) EXPECT_EQ(f, 0u);
}

}  // namespace
}  // namespace bowg
