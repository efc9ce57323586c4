// Database: adding entries (the queried keyframe's vectors, raw groups read
// back, entries out of the index, refusals) and the rebuilds on m / level /
// scoring changes. The queries' scores are in database_query_test.cpp.
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
#include "database_fixture.h"
#include "synthetic_corridor.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace {

using namespace database_fixture;

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
      CountedEntry qe = fill(&a, &qbow);
      BowVector unused;
      CountedEntry qe_b = fill(&b, &unused);
      const DatabaseQuery q =
          a.makeQuery(qbow, qe.counted, qe.entry.points.unpack(), 320, 240, true);
      DatabaseEntry ea = qe.entry, eb = qe.entry;
      ea.searchable = eb.searchable = searchable;
      const EntryId ia = a.add(std::move(ea), std::move(qe.counted), q);
      const EntryId ib = b.add(std::move(eb), std::move(qe_b.counted));
      ASSERT_EQ(ia, ib);
      EXPECT_EQ(a.bow(ia), b.bow(ib)) << toString(s);
      EXPECT_EQ(a.bow(ia), q.bow) << toString(s);
      EXPECT_EQ(a.rawGroups(ia), b.rawGroups(ib));
      EXPECT_LE(a.memoryBytes(), b.memoryBytes());  // the copy kept is no larger
      // A later query scores the new entry the same in both.
      const DatabaseQuery later =
          a.makeQuery(qbow, qe.counted, qe.entry.points.unpack(), 320, 240, true);
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
  CountedEntry qe = fill(&db, &qbow);
  const DatabaseQuery q = db.makeQuery(qbow, qe.counted, qe.entry.points.unpack(), 320, 240, true);
  DatabaseQuery other_scoring = q;
  other_scoring.scoring = ScoringType::kL2;
  EXPECT_THROW(db.add(qe.entry, std::move(qe.counted), other_scoring), std::invalid_argument);
  DatabaseQuery foreign_word = q;
  const std::vector<WordId> words = qe.entry.words.unpack();
  WordId absent = 0;
  while (std::find(words.begin(), words.end(), absent) != words.end()) ++absent;
  foreign_word.bow.insert(
      std::lower_bound(foreign_word.bow.begin(), foreign_word.bow.end(), BowEntry{absent, 0.0}),
      BowEntry{absent, 0.1});
  EXPECT_THROW(db.add(qe.entry, std::move(qe.counted), foreign_word), std::invalid_argument);
  DatabaseQuery wrong_bins = q;
  wrong_bins.distribution.pop_back();
  EXPECT_THROW(db.add(qe.entry, std::move(qe.counted), wrong_bins), std::invalid_argument);
  EXPECT_EQ(db.size(), 30u);  // nothing half-added
  EXPECT_EQ(db.add(qe.entry, std::move(qe.counted), q), 30u);
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
  EXPECT_EQ(db.add(e, db.addToGroupTable(b)), 1u);
  EXPECT_EQ(db.size(), 2u);
  EXPECT_EQ(db.searchableCount(), 1u);
  EXPECT_FALSE(db.entry(1).searchable);
  EXPECT_EQ(db.rawGroups(1), b);
  EXPECT_EQ(db.rawGroups(0), a);
  const GroupVector q_raw{{1, 2}, {2, 2}};
  const CountedGroups q_counted = db.addToGroupTable(q_raw);
  // The query's words are B's: A shares word 1 with it.
  const DatabaseQuery q = db.makeQuery(db.bow(1), q_counted, {}, 0, 0, false);
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
  s = db.query(db.makeQuery(db.bow(1), q_counted, {}, 0, 0, false), 2, true);
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

TEST(Database, FanBinChangeRebuildsDistributionVectors) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  BowVector qbow;
  const CountedEntry qe = fill(&db, &qbow);
  db.setFanBins(5);
  const DatabaseQuery q = db.makeQuery(qbow, qe.counted, qe.entry.points.unpack(), 320, 240, true);
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
  db.add(e, db.addToGroupTable({}));
  const std::vector<double> computed = db.distribution(0);
  ASSERT_EQ(computed.size(), 4u);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(computed[k], 1.0 / std::sqrt(3.0), 1e-15);
  EXPECT_EQ(computed[3], 0.0);
  const std::vector<double> given{0.5, 0.25, 0.25, 0.0};
  e.stamp = 2;
  db.add(e, db.addToGroupTable({}), given);
  EXPECT_EQ(db.distribution(1), given);
  e.stamp = 3;
  EXPECT_THROW(db.add(e, db.addToGroupTable({}), std::vector<double>(5, 0.2)),
               std::invalid_argument);
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
    const EntryId id = db.add(std::move(e.entry), db.addToGroupTable(e.raw_groups));
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
  EXPECT_THROW(db.add(e, db.addToGroupTable({})), std::invalid_argument);
  e.words = PackedWords({0, static_cast<WordId>(vocabulary()->wordCount())});
  EXPECT_THROW(db.add(e, db.addToGroupTable({})), std::invalid_argument);
  e.words = PackedWords({0, 1});
  // Raw groups: among the entry's words, sorted without repeats, whole counts.
  EXPECT_THROW(db.add(e, db.addToGroupTable({{2, 1.0}})), std::invalid_argument);
  EXPECT_THROW(db.add(e, db.addToGroupTable({{1, 1.0}, {0, 1.0}})), std::invalid_argument);
  EXPECT_THROW(db.add(e, db.addToGroupTable({{0, 1.0}, {0, 2.0}})), std::invalid_argument);
  EXPECT_THROW(db.add(e, db.addToGroupTable({{0, 1.5}})), std::invalid_argument);
  EXPECT_THROW(db.add(e, db.addToGroupTable({{0, 0.0}})), std::invalid_argument);
  EXPECT_THROW(db.add(e, db.addToGroupTable({{0, 16777216.0}})), std::invalid_argument);
  EXPECT_EQ(db.size(), 0u);
  EXPECT_EQ(db.add(e, db.addToGroupTable({{0, 2.0}, {1, 16777215.0}})), 0u);
  EXPECT_EQ(db.rawGroups(0), (GroupVector{{0, 2.0}, {1, 16777215.0}}));
  EXPECT_THROW(db.add(e, db.addToGroupTable({})), std::invalid_argument);  // same stamp
  EXPECT_EQ(db.size(), 1u);
  EXPECT_GT(db.memoryBytes(), 0u);
  db.clear();
  EXPECT_TRUE(db.empty());
}

}  // namespace
}  // namespace bowg
