// Database: the inverse-index queries equal the direct formulas (word score
// = scoreBowVectors() for every ScoringType; group score = eq. 3 on eq. 1
// weights with the table's current IDF), hand-worked group scores, the
// recent-exclusion limit, and the rebuilds on m / level / scoring changes.
#include "bowg/database/database.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <set>
#include <stdexcept>

#include "bowg/scoring/distribution.h"
#include "bowg/scoring/word_groups.h"
#include "bowg/vocabulary/vocabulary.h"
#include "synthetic_corridor.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace {

std::shared_ptr<const Vocabulary> vocabulary() {
  static std::shared_ptr<const Vocabulary> v =
      std::make_shared<Vocabulary>(testing::makeSyntheticVocabulary(10, 4, 5));
  return v;
}

// An entry and its raw groups built from a keyframe the way LoopDetector
// builds them (minus the query): words, BoW, raw groups into the table, then
// add().
struct BuiltEntry {
  DatabaseEntry entry;
  GroupVector raw_groups;
};

BuiltEntry entryFromKeyframe(const Vocabulary& voc, const KeyframeInput& kf, BowVector* bow) {
  BuiltEntry b;
  DatabaseEntry& e = b.entry;
  e.stamp = kf.stamp;
  e.points = PackedPoints::fromKeypoints(kf.features.keypoints, kf.features.pyramid_scale_factor);
  e.descriptors = kf.features.descriptors;
  e.centre_x = 320;
  e.centre_y = 240;
  std::vector<WordId> words;
  voc.transform(e.descriptors, bow, nullptr, 0, &words);
  e.words = PackedWords(words);
  b.raw_groups = buildWordGroups(kf.features.keypoints, words, WordGroupOptions());
  return b;
}

// Fills `db` with 30 corridor keyframes 0.5 m apart (overlapping views share
// words) and returns a query keyframe's entry over the first ones. The raw
// groups each entry was added with go to `added` when given.
BuiltEntry fill(Database* db, BowVector* query_bow, std::vector<GroupVector>* added = nullptr) {
  const testing::Corridor c = testing::makeCorridor(30, 50, 21);
  std::mt19937_64 rng(4);
  for (int i = 0; i < 30; ++i) {
    BowVector bow;
    BuiltEntry b = entryFromKeyframe(db->vocabulary(),
                                     testing::observeCorridor(c, 0.5 * i, 1.0 + i, rng, 2), &bow);
    db->addToGroupTable(b.raw_groups);
    if (added) added->push_back(b.raw_groups);
    db->add(std::move(b.entry), b.raw_groups);
  }
  BuiltEntry q = entryFromKeyframe(db->vocabulary(),
                                   testing::observeCorridor(c, 3.2, 100.0, rng, 2), query_bow);
  db->addToGroupTable(q.raw_groups);
  return q;
}

// The inverse index keeps BoW weights as floats (24 bits): scores through it
// agree with the double-precision vectors to ~1e-7 of their weights.
const double kFloatWeightTolerance = 1e-6;

class DatabaseScoring : public ::testing::TestWithParam<ScoringType> {};

TEST_P(DatabaseScoring, InverseIndexWordScoreEqualsScoreBowVectors) {
  const ScoringType s = GetParam();
  Database db(vocabulary(), s, 2, 8);
  BowVector qbow;
  const BuiltEntry qe = fill(&db, &qbow);
  const DatabaseQuery q =
      db.makeQuery(qbow, qe.raw_groups, qe.entry.points.unpack(), 320, 240, false);
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
  const BuiltEntry qe = fill(&db, &qbow, &added);
  const DatabaseQuery q =
      db.makeQuery(qbow, qe.raw_groups, qe.entry.points.unpack(), 320, 240, false);
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
  const BuiltEntry qe = fill(&db, &qbow, &added);
  DatabaseQuery q = db.makeQuery(qbow, qe.raw_groups, qe.entry.points.unpack(), 320, 240, false);
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

// The keyframe just queried joins with the query's BoW and distribution
// vectors: the same entry, postings and scores as one built from its words,
// for every scoring, searchable or not.
TEST(Database, AddingTheQueriedKeyframeTakesItsVectorsAsBuiltFromTheWords) {
  for (const ScoringType s :
       {ScoringType::kL1, ScoringType::kL2, ScoringType::kChiSquare, ScoringType::kKl,
        ScoringType::kBhattacharyya, ScoringType::kDotProduct}) {
    for (const bool searchable : {true, false}) {
      Database a(vocabulary(), s, 2, 8), b(vocabulary(), s, 2, 8);
      BowVector qbow;
      const BuiltEntry qe = fill(&a, &qbow);
      BowVector unused;
      fill(&b, &unused);
      const DatabaseQuery q =
          a.makeQuery(qbow, qe.raw_groups, qe.entry.points.unpack(), 320, 240, true);
      DatabaseEntry ea = qe.entry, eb = qe.entry;
      ea.searchable = eb.searchable = searchable;
      const EntryId ia = a.add(std::move(ea), qe.raw_groups, q);
      const EntryId ib = b.add(std::move(eb), qe.raw_groups);
      ASSERT_EQ(ia, ib);
      EXPECT_EQ(a.bow(ia), b.bow(ib)) << toString(s);
      EXPECT_EQ(a.bow(ia), q.bow) << toString(s);
      EXPECT_EQ(a.rawGroups(ia), b.rawGroups(ib));
      EXPECT_LE(a.memoryBytes(), b.memoryBytes());  // the copy kept is no larger
      // A later query scores the new entry the same in both.
      const DatabaseQuery later =
          a.makeQuery(qbow, qe.raw_groups, qe.entry.points.unpack(), 320, 240, true);
      const std::vector<EntryScores> sa = a.query(later, ia + 1, true);
      const std::vector<EntryScores> sb = b.query(later, ib + 1, true);
      ASSERT_EQ(sa.size(), sb.size());
      for (std::size_t i = 0; i < sa.size(); ++i) {
        EXPECT_EQ(sa[i].entry, sb[i].entry);
        EXPECT_EQ(sa[i].s_w, sb[i].s_w) << toString(s);
        EXPECT_EQ(sa[i].s_g, sb[i].s_g);
        EXPECT_EQ(sa[i].s_d, sb[i].s_d);
      }
      EXPECT_EQ(searchable, !sa.empty() && sa.back().entry == ia);
    }
  }
}

TEST(Database, AddingTheQueriedKeyframeRefusesAForeignQuery) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  BowVector qbow;
  const BuiltEntry qe = fill(&db, &qbow);
  const DatabaseQuery q =
      db.makeQuery(qbow, qe.raw_groups, qe.entry.points.unpack(), 320, 240, true);
  DatabaseQuery other_scoring = q;
  other_scoring.scoring = ScoringType::kL2;
  EXPECT_THROW(db.add(qe.entry, qe.raw_groups, other_scoring), std::invalid_argument);
  DatabaseQuery foreign_word = q;
  const std::vector<WordId> words = qe.entry.words.unpack();
  WordId absent = 0;
  while (std::find(words.begin(), words.end(), absent) != words.end()) ++absent;
  foreign_word.bow.insert(
      std::lower_bound(foreign_word.bow.begin(), foreign_word.bow.end(), BowEntry{absent, 0.0}),
      BowEntry{absent, 0.1});
  EXPECT_THROW(db.add(qe.entry, qe.raw_groups, foreign_word), std::invalid_argument);
  DatabaseQuery wrong_bins = q;
  wrong_bins.distribution.pop_back();
  EXPECT_THROW(db.add(qe.entry, qe.raw_groups, wrong_bins), std::invalid_argument);
  EXPECT_EQ(db.size(), 30u);  // nothing half-added
  EXPECT_EQ(db.add(qe.entry, qe.raw_groups, q), 30u);
}

// The entries keep no raw groups: the database reads them back from its
// inverse index, exactly as add() received them.
TEST(Database, RawGroupsAreReadBackAsAdded) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  BowVector qbow;
  std::vector<GroupVector> added;
  fill(&db, &qbow, &added);
  ASSERT_EQ(added.size(), db.size());
  std::size_t groups = 0;
  for (EntryId id = 0; id < db.size(); ++id) {
    EXPECT_EQ(db.rawGroups(id), added[id]) << "entry " << id;
    groups += added[id].size();
  }
  EXPECT_GT(groups, 100u);
}

// An entry of groups only: one feature per group, with the group's word (an
// image's groups are among its words), added to the table and then the
// database. Returns its id.
EntryId addGroups(Database* db, double stamp, const GroupVector& raw) {
  DatabaseEntry e;
  e.stamp = stamp;
  std::vector<WordId> words;
  for (const auto& g : raw) words.push_back(g.first);
  e.words = PackedWords(words);
  e.points = PackedPoints(std::vector<ImagePoint>(raw.size()), 0.f);
  e.descriptors.resize(raw.size());
  db->addToGroupTable(raw);
  return db->add(e, raw);
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
  db.addToGroupTable(q_raw);
  DatabaseQuery q = db.makeQuery({}, q_raw, {}, 0, 0, false);
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
  q = db.makeQuery({}, q_raw, {}, 0, 0, false);
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
  db.addToGroupTable(q_raw);
  const DatabaseQuery q = db.makeQuery({}, q_raw, {}, 0, 0, false);
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

// An entry out of the inverse index (DatabaseEntry::searchable false) is
// never a query's candidate, yet scores as it would in it. The hand-worked
// case above with B out of the index and its counts past a posting's byte
// (B {1:300, 2:900} weighs as {1:1, 2:3} in the TF, but its counts enter
// the table: cumulative g1 = 2+300+2 = 304, g2 = 900+2 = 902, total = 4 +
// 1200 + 4 = 1208; log(1208/304) = 1.37969, log(1208/902) = 0.29211).
// dot(Q, A) = (.5 1.37969)^2 = 0.47589, s_g = 1 - sqrt(1 - 0.47589) =
// 0.27604; dot(Q, B) = .5 .25 1.37969^2 + .5 .75 0.29211^2 = 0.23794 +
// 0.03200 = 0.26994, s_g = 1 - sqrt(1 - 0.26994) = 0.14557.
TEST(Database, EntriesOutOfTheIndexScoreButAreNeverCandidates) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  const GroupVector a{{0, 2}, {1, 2}}, b{{1, 300}, {2, 900}};
  addGroups(&db, 1, a);
  DatabaseEntry e;
  e.stamp = 2;
  e.words = PackedWords(std::vector<WordId>{1, 2});
  e.points = PackedPoints(std::vector<ImagePoint>(2), 0.f);
  e.descriptors.resize(2);
  e.searchable = false;
  db.addToGroupTable(b);
  EXPECT_EQ(db.add(e, b), 1u);
  EXPECT_EQ(db.size(), 2u);
  EXPECT_EQ(db.searchableCount(), 1u);
  EXPECT_FALSE(db.entry(1).searchable);
  EXPECT_EQ(db.rawGroups(1), b);
  EXPECT_EQ(db.rawGroups(0), a);
  const GroupVector q_raw{{1, 2}, {2, 2}};
  db.addToGroupTable(q_raw);
  // The query's words are B's: A shares word 1 with it.
  const DatabaseQuery q = db.makeQuery(db.bow(1), q_raw, {}, 0, 0, false);
  const double l1 = std::log(1208.0 / 304.0), l2 = std::log(1208.0 / 902.0);
  std::vector<EntryScores> s = db.query(q, 2, true);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].entry, 0u);
  EXPECT_NEAR(s[0].s_g, 1 - std::sqrt(1 - 0.25 * l1 * l1), 1e-12);
  EXPECT_NEAR(s[0].s_g, 0.27604, 1e-5);
  const EntryScores sb = db.score(q, 1);
  EXPECT_NEAR(sb.s_g, 1 - std::sqrt(1 - (0.125 * l1 * l1 + 0.375 * l2 * l2)), 1e-12);
  EXPECT_NEAR(sb.s_g, 0.14557, 1e-5);
  EXPECT_NEAR(sb.s_w, 1.0, 1e-12);  // the query's BoW is B's own
  // A scoring change rewrites the postings of the indexed entries only.
  db.setScoring(ScoringType::kL2);
  s = db.query(db.makeQuery(db.bow(1), q_raw, {}, 0, 0, false), 2, true);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].entry, 0u);
  EXPECT_EQ(db.rawGroups(1), b);
  // Later entries read their own groups, indexed or not.
  const GroupVector c{{3, 5}};
  addGroups(&db, 3, c);
  EXPECT_EQ(db.rawGroups(2), c);
  EXPECT_EQ(db.rawGroups(1), b);
  EXPECT_EQ(db.searchableCount(), 2u);
  db.clear();
  EXPECT_EQ(db.searchableCount(), 0u);
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
    all.addToGroupTable(b.raw_groups);
    some.addToGroupTable(b.raw_groups);
    all.add(b.entry, b.raw_groups);
    b.entry.searchable = i % 3 != 1;
    some.add(std::move(b.entry), b.raw_groups);
  }
  EXPECT_EQ(some.searchableCount(), 20u);
  BowVector qbow;
  const BuiltEntry qe =
      entryFromKeyframe(all.vocabulary(), testing::observeCorridor(c, 3.2, 100.0, rng, 2), &qbow);
  all.addToGroupTable(qe.raw_groups);
  some.addToGroupTable(qe.raw_groups);
  const std::vector<ImagePoint> points = qe.entry.points.unpack();
  const DatabaseQuery qa = all.makeQuery(qbow, qe.raw_groups, points, 320, 240, true);
  const DatabaseQuery qs = some.makeQuery(qbow, qe.raw_groups, points, 320, 240, true);
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
    db.add(e, {});
  }
  const BowVector qbow = voc.bowFromWords({words[0], words[5]});
  const DatabaseQuery q = db.makeQuery(qbow, {}, {}, 0, 0, false);
  const std::vector<EntryScores> s = db.query(q, 40, false);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].entry, 5u);
  EXPECT_EQ(s[1].entry, 30u);
}

TEST(Database, FanBinChangeRebuildsDistributionVectors) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  BowVector qbow;
  const BuiltEntry qe = fill(&db, &qbow);
  db.setFanBins(5);
  const DatabaseQuery q =
      db.makeQuery(qbow, qe.raw_groups, qe.entry.points.unpack(), 320, 240, true);
  ASSERT_EQ(q.distribution.size(), 5u);
  const std::vector<double> fresh_q = distributionVector(qe.entry.points.unpack(), 320, 240, 5);
  for (const EntryScores& e : db.query(q, 30, true)) {
    const DatabaseEntry& d = db.entry(e.entry);
    const std::vector<double> fresh = distributionVector(d.points.unpack(), 320, 240, 5);
    EXPECT_EQ(db.distribution(e.entry), fresh);
    EXPECT_NEAR(e.s_d, distributionScore(fresh_q, fresh), 1e-12);
  }
  EXPECT_THROW(db.setFanBins(0), std::invalid_argument);
}

// add() takes the query's distribution vector instead of computing it from
// the positions again; a vector of another size than the fan is refused.
TEST(Database, AddKeepsAGivenDistributionVector) {
  Database db(vocabulary(), ScoringType::kL1, 2, 4);
  DatabaseEntry e;
  e.stamp = 1;
  // Hand-worked with the fan centre (0, 0) and m = 4: angles 45, 135 and 225
  // degrees fall into bins 0, 1 and 2: counts (1, 1, 1, 0), L2-normalised
  // to 1/sqrt(3) each.
  e.points = PackedPoints({{1, 1}, {-1, 1}, {-1, -1}}, 0.f);
  e.descriptors.resize(3);
  e.words = PackedWords({0, 1, 2});
  e.centre_x = 0;
  e.centre_y = 0;
  db.add(e, {});
  const std::vector<double> computed = db.distribution(0);
  ASSERT_EQ(computed.size(), 4u);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(computed[k], 1.0 / std::sqrt(3.0), 1e-15);
  EXPECT_EQ(computed[3], 0.0);
  const std::vector<double> given{0.5, 0.25, 0.25, 0.0};
  e.stamp = 2;
  db.add(e, {}, given);
  EXPECT_EQ(db.distribution(1), given);
  e.stamp = 3;
  EXPECT_THROW(db.add(e, {}, std::vector<double>(5, 0.2)), std::invalid_argument);
  EXPECT_EQ(db.size(), 2u);
}

TEST(Database, DirectIndexMatchesTheVocabularyAtEveryLevel) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  BowVector qbow;
  fill(&db, &qbow);
  for (int level : {1, 3, 4, 2}) {
    db.setDirectLevel(level);
    for (EntryId id : {0u, 7u, 29u}) {
      const DatabaseEntry& e = db.entry(id);
      BowVector bow;
      DirectIndex direct;
      vocabulary()->transform(e.descriptors, &bow, &direct, level);
      EXPECT_EQ(directIndexFromWords(*vocabulary(), e.words.unpack(), db.directLevel()), direct)
          << "level " << level;
    }
  }
}

TEST(Database, ScoringChangeRenormalisesAndReindexes) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  BowVector qbow;
  const BuiltEntry qe = fill(&db, &qbow);
  db.setScoring(ScoringType::kL2);
  const DatabaseQuery q =
      db.makeQuery(qbow, qe.raw_groups, qe.entry.points.unpack(), 320, 240, false);
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

// The entry keeps its words, not its vector: the vector the database rebuilds
// is, bit for bit, the transform's of the keyframe normalised for the
// database's scoring (what the word inverse index holds).
TEST(Database, BowIsRebuiltFromTheWordsBitForBit) {
  for (ScoringType s : {ScoringType::kL1, ScoringType::kL2, ScoringType::kChiSquare}) {
    Database db(vocabulary(), s, 2, 8);
    const testing::Corridor c = testing::makeCorridor(5, 50, 3);
    std::mt19937_64 rng(7);
    BowVector bow;
    BuiltEntry e =
        entryFromKeyframe(db.vocabulary(), testing::observeCorridor(c, 0.5, 1.0, rng, 2), &bow);
    db.addToGroupTable(e.raw_groups);
    const EntryId id = db.add(std::move(e.entry), e.raw_groups);
    normaliseBowVector(s, &bow);
    ASSERT_FALSE(bow.empty());
    EXPECT_EQ(db.bow(id), bow) << toString(s);
  }
  // Hand-worked: TF-IDF over words {w, w, v} of the synthetic vocabulary,
  // L1: w has 2/3 * idf_w, v 1/3 * idf_v, each divided by their sum.
  const Vocabulary& voc = *vocabulary();
  WordId w = 0, v = 1;
  while (!(voc.wordWeight(w) > 0)) ++w;
  v = w + 1;
  while (!(voc.wordWeight(v) > 0)) ++v;
  const BowVector b = voc.bowFromWords({w, v, w});
  const double bw = 2.0 / 3.0 * voc.wordWeight(w), bv = 1.0 / 3.0 * voc.wordWeight(v);
  ASSERT_EQ(b.size(), 2u);
  EXPECT_EQ(b[0].first, w);
  EXPECT_EQ(b[1].first, v);
  EXPECT_NEAR(b[0].second, bw / (bw + bv), 1e-15);
  EXPECT_NEAR(b[1].second, bv / (bw + bv), 1e-15);
  EXPECT_THROW(voc.bowFromWords({static_cast<WordId>(voc.wordCount())}), std::out_of_range);
}

// The newest entries' vectors are kept, the older ones rebuilt from the
// words and the postings: both give the same vectors bit for bit, under the
// scoring the database has now (a scoring change drops the kept ones).
TEST(Database, KeptAndRebuiltVectorsAreTheSame) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  BowVector qbow;
  std::vector<GroupVector> added;
  fill(&db, &qbow, &added);
  for (ScoringType s : {ScoringType::kL1, ScoringType::kL2}) {
    db.setScoring(s);
    for (EntryId id = 0; id < db.size(); ++id) {
      BowVector expected = db.vocabulary().bowFromWords(db.entry(id).words.unpack());
      normaliseBowVector(s, &expected);
      EXPECT_EQ(db.bow(id), expected) << toString(s) << " entry " << id;
      EXPECT_EQ(db.rawGroups(id), added[id]) << "entry " << id;
    }
  }
  // The last entry's vectors, read again once eight more entries have made
  // it old: now rebuilt, still the same.
  const EntryId last = static_cast<EntryId>(db.size() - 1);
  const BowVector kept = db.bow(last);
  const GroupVector kept_groups = db.rawGroups(last);
  for (int i = 0; i < 8; ++i) addGroups(&db, 1000.0 + i, GroupVector{{3, 1}});
  EXPECT_EQ(db.bow(last), kept);
  EXPECT_EQ(db.rawGroups(last), kept_groups);
}

TEST(Database, AddRejectsInconsistentEntries) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  DatabaseEntry e;
  e.stamp = 1;
  e.points = PackedPoints(std::vector<ImagePoint>(2), 0.f);
  e.descriptors.resize(2);
  e.words = PackedWords({0});
  EXPECT_THROW(db.add(e, {}), std::invalid_argument);
  e.words = PackedWords({0, static_cast<WordId>(vocabulary()->wordCount())});
  EXPECT_THROW(db.add(e, {}), std::invalid_argument);
  e.words = PackedWords({0, 1});
  // Raw groups: among the entry's words, sorted without repeats, whole counts.
  EXPECT_THROW(db.add(e, {{2, 1.0}}), std::invalid_argument);
  EXPECT_THROW(db.add(e, {{1, 1.0}, {0, 1.0}}), std::invalid_argument);
  EXPECT_THROW(db.add(e, {{0, 1.0}, {0, 2.0}}), std::invalid_argument);
  EXPECT_THROW(db.add(e, {{0, 1.5}}), std::invalid_argument);
  EXPECT_THROW(db.add(e, {{0, 0.0}}), std::invalid_argument);
  EXPECT_THROW(db.add(e, {{0, 16777216.0}}), std::invalid_argument);
  EXPECT_EQ(db.size(), 0u);
  EXPECT_EQ(db.add(e, {{0, 2.0}, {1, 16777215.0}}), 0u);
  EXPECT_EQ(db.rawGroups(0), (GroupVector{{0, 2.0}, {1, 16777215.0}}));
  EXPECT_THROW(db.add(e, {}), std::invalid_argument);  // same stamp
  EXPECT_EQ(db.size(), 1u);
  EXPECT_GT(db.memoryBytes(), 0u);
  db.clear();
  EXPECT_TRUE(db.empty());
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
    big.addToGroupTable(b.raw_groups);
    if (i < 12) {
      small.addToGroupTable(b.raw_groups);
      small.add(b.entry, b.raw_groups);
    }
    big.add(std::move(b.entry), b.raw_groups);
  }
  BowVector qbow;
  const BuiltEntry qe =
      entryFromKeyframe(big.vocabulary(), testing::observeCorridor(c, 3.2, 100.0, rng, 2), &qbow);
  big.addToGroupTable(qe.raw_groups);
  small.addToGroupTable(qe.raw_groups);
  const std::vector<ImagePoint> points = qe.entry.points.unpack();
  const DatabaseQuery qb = big.makeQuery(qbow, qe.raw_groups, points, 320, 240, true);
  const DatabaseQuery qs = small.makeQuery(qbow, qe.raw_groups, points, 320, 240, true);
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
  for (double v : scratch.word_acc) EXPECT_EQ(v, 0.0);
  for (std::uint8_t f : scratch.touched_flag) EXPECT_EQ(f, 0u);
}

}  // namespace
}  // namespace bowg
