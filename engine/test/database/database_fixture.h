// What the database tests share: the synthetic vocabulary, entries built
// from corridor keyframes the way LoopDetector builds them, a filled
// database, entries of groups only.
#pragma once

#include <memory>
#include <random>
#include <vector>

#include "bowg/database/database.h"
#include "bowg/scoring/word_groups.h"
#include "bowg/vocabulary/vocabulary.h"
#include "synthetic_corridor.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace database_fixture {

inline std::shared_ptr<const Vocabulary> vocabulary() {
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

inline BuiltEntry entryFromKeyframe(const Vocabulary& voc, const KeyframeInput& kf,
                                    BowVector* bow) {
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

// A query keyframe's entry and its raw groups, counted into the table.
struct CountedEntry {
  DatabaseEntry entry;
  CountedGroups counted;
};

// Fills `db` with 30 corridor keyframes 0.5 m apart (overlapping views share
// words) and returns a query keyframe's entry over the first ones, its raw
// groups counted into the table (the entry not added). The raw groups each
// entry was added with go to `added` when given.
inline CountedEntry fill(Database* db, BowVector* query_bow,
                         std::vector<GroupVector>* added = nullptr) {
  const testing::Corridor c = testing::makeCorridor(30, 50, 21);
  std::mt19937_64 rng(4);
  for (int i = 0; i < 30; ++i) {
    BowVector bow;
    BuiltEntry b = entryFromKeyframe(db->vocabulary(),
                                     testing::observeCorridor(c, 0.5 * i, 1.0 + i, rng, 2), &bow);
    CountedGroups counted = db->addToGroupTable(b.raw_groups);
    if (added) added->push_back(b.raw_groups);
    db->add(std::move(b.entry), std::move(counted));
  }
  BuiltEntry q = entryFromKeyframe(db->vocabulary(),
                                   testing::observeCorridor(c, 3.2, 100.0, rng, 2), query_bow);
  CountedGroups counted = db->addToGroupTable(std::move(q.raw_groups));
  return CountedEntry{std::move(q.entry), std::move(counted)};
}

// An entry of groups only: one feature per group, with the group's word (an
// image's groups are among its words).
inline DatabaseEntry entryOfGroups(const GroupVector& raw, double stamp) {
  DatabaseEntry e;
  e.stamp = stamp;
  std::vector<WordId> words;
  for (const auto& g : raw) words.push_back(g.first);
  e.words = PackedWords(words);
  e.points = PackedPoints(std::vector<ImagePoint>(raw.size()), 0.f);
  e.descriptors.resize(raw.size());
  return e;
}

// entryOfGroups(), added to the table and then the database. Returns its id.
inline EntryId addGroups(Database* db, double stamp, const GroupVector& raw) {
  return db->add(entryOfGroups(raw, stamp), db->addToGroupTable(raw));
}

}  // namespace database_fixture
}  // namespace bowg
