// The recent past that models a pipe's repeated texture (repeated_texture.h):
// which keyframes stand for it, which query features it repeats, and the
// inliers left, on hand-worked entries and descriptors.
#include "bowg/detection/repeated_texture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "synthetic_vocabulary.h"

namespace bowg {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// A database of featureless entries with these odometers (NaN = none).
std::unique_ptr<Database> databaseWith(const std::vector<double>& odometers) {
  static std::shared_ptr<const Vocabulary> vocabulary =
      std::make_shared<Vocabulary>(testing::makeSyntheticVocabulary(10, 2, 3));
  std::unique_ptr<Database> db(new Database(vocabulary, ScoringType::kL1, 1, 8));
  for (std::size_t i = 0; i < odometers.size(); ++i) {
    DatabaseEntry e;
    e.stamp = static_cast<double>(i);
    e.odometer = odometers[i];
    db->add(std::move(e), db->addToGroupTable(GroupVector()));
  }
  return db;
}

// Entries every 0.25 m from 0 to 10 m (41).
std::vector<double> everyQuarterMetre() {
  std::vector<double> odometers;
  for (int i = 0; i <= 40; ++i) odometers.push_back(0.25 * i);
  return odometers;
}

// Four keyframes from 0.5 m to 3.5 m back.
VerifiedChainOptions fourFromHalfAMetre() {
  VerifiedChainOptions chain;
  chain.repeated_texture_keyframes = 4;
  chain.repeated_texture_min_m = 0.5;
  return chain;
}

TEST(RepeatedTexture, EntriesSpreadOverTheMetresBehindTheQuery) {
  // Entries every 0.25 m from 0 to 10 m; the query at 10 m. Four keyframes
  // from 0.5 to 3.5 m back: 0.5, 1.5, 2.5, 3.5 m, the newest entries at or
  // before 9.5, 8.5, 7.5, 6.5 m: ids 38, 34, 30, 26.
  const std::unique_ptr<Database> db = databaseWith(everyQuarterMetre());
  VerifiedChainOptions chain = fourFromHalfAMetre();
  IslandOptions islands;
  islands.recent_exclusion_m = 3.5;
  EXPECT_EQ(repeatedTextureEntries(*db, 10.0, chain, islands),
            (std::vector<EntryId>{38, 34, 30, 26}));
  // One keyframe: the nearest end of the range.
  chain.repeated_texture_keyframes = 1;
  EXPECT_EQ(repeatedTextureEntries(*db, 10.0, chain, islands), (std::vector<EntryId>{38}));
  // Near the start of the run the range reaches before the first entry:
  // only the entries it finds (2 m: 1.5 and 0.5 m, ids 6 and 2).
  chain.repeated_texture_keyframes = 4;
  EXPECT_EQ(repeatedTextureEntries(*db, 2.0, chain, islands), (std::vector<EntryId>{6, 2}));
}

TEST(RepeatedTexture, EntriesWithoutAnOdometerAreLeftOut) {
  // Entry 30 (7.5 m) has no odometer: it carries 7.25 m in Database::
  // odometers, so the search for 7.5 m lands on it and leaves it out.
  std::vector<double> odometers = everyQuarterMetre();
  odometers[30] = kNaN;
  const std::unique_ptr<Database> db = databaseWith(odometers);
  IslandOptions islands;
  islands.recent_exclusion_m = 3.5;
  EXPECT_EQ(repeatedTextureEntries(*db, 10.0, fourFromHalfAMetre(), islands),
            (std::vector<EntryId>{38, 34, 26}));
}

TEST(RepeatedTexture, WithoutAnOdometerTheRecentExclusionKeyframes) {
  // 41 entries, a window of 20 keyframes, four of them: 5, 10, 15 and 20
  // keyframes back: ids 36, 31, 26, 21.
  const std::unique_ptr<Database> db = databaseWith(std::vector<double>(41, kNaN));
  VerifiedChainOptions chain;
  chain.repeated_texture_keyframes = 4;
  IslandOptions islands;
  islands.recent_exclusion = 20;
  EXPECT_EQ(repeatedTextureEntries(*db, kNaN, chain, islands),
            (std::vector<EntryId>{36, 31, 26, 21}));
  // A database shorter than the window: what it holds.
  const std::unique_ptr<Database> small = databaseWith(std::vector<double>(12, kNaN));
  EXPECT_EQ(repeatedTextureEntries(*small, kNaN, chain, islands), (std::vector<EntryId>{7, 2}));
  // More keyframes than the window has: each once.
  chain.repeated_texture_keyframes = 8;
  islands.recent_exclusion = 2;
  EXPECT_EQ(repeatedTextureEntries(*db, kNaN, chain, islands), (std::vector<EntryId>{40, 39}));
}

TEST(RepeatedTexture, FeaturesWithACorrespondenceAreRepeated) {
  // Query features 0 and 2 reappear exactly in the entry (as its 1 and 0),
  // feature 1 does not: features 0 and 2 are repeated.
  const std::vector<Descriptor> random = testing::randomDescriptors(5, 11);
  const std::vector<Descriptor> query_d{random[0], random[1], random[2]};
  const std::vector<Descriptor> entry_d{random[2], random[0], random[3], random[4]};
  const std::vector<ImagePoint> query_p(3), entry_p(4);
  GeometricVerificationOptions options;
  options.exhaustive = true;
  std::vector<char> repeated(3, 0);
  markRepeated(VerificationView{&query_p, &query_d, nullptr},
               VerificationView{&entry_p, &entry_d, nullptr}, options, &repeated);
  EXPECT_EQ(repeated, (std::vector<char>{1, 0, 1}));
}

TEST(RepeatedTexture, UniqueInliersAreThoseNotRepeated) {
  // Inliers on query features 0, 2, 3, 5; features 0 and 3 are repeated:
  // 2 and 5 are unique.
  const std::vector<char> repeated{1, 0, 0, 1, 0, 0};
  std::vector<Correspondence> inliers(4);
  inliers[0].query_index = 0;
  inliers[1].query_index = 2;
  inliers[2].query_index = 3;
  inliers[3].query_index = 5;
  EXPECT_EQ(uniqueInliers(inliers, repeated), 2);
  EXPECT_EQ(uniqueInliers(inliers, std::vector<char>(6, 0)), 4);
  EXPECT_EQ(uniqueInliers({}, repeated), 0);
}

}  // namespace
}  // namespace bowg
