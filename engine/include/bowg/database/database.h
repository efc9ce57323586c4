// The BoWG database (paper Sec. III-A "BoWG Database"): the keyframes seen so
// far and every index the queries need, each a piece of its own:
//  - the entries' storage (entries_, their odometers): per entry its words
//    (2-3 bytes each, PackedWords), keypoint positions (4 bytes each where
//    that is lossless, PackedPoints), descriptors and fan centre. An entry's
//    BoW vector and raw groups are rebuilt from its words and the inverse
//    index when needed (bow(), rawGroups()), not kept; its direct index
//    (Sec. III-D's correspondence search) is rebuilt from its words when it
//    is verified (directIndexFromWords, a few microseconds);
//  - the inverse index of words and word groups (inverse_index.h);
//  - the online word-group table (eq. 1's IDF totals, word_groups.h);
//  - the distribution table (distribution_table.h, Sec. III-C);
//  - the newest entries' vectors (recent_vectors.h).
// The query (database_query.cpp) touches only entries that share a word or a
// group with the query (never a scan of all entries) and only entries with
// id < a limit (the recent-exclusion window); its working memory belongs to
// the caller (query_scratch.h).
//
// Per-keyframe order, enforced by the CountedGroups type (counted_groups.h):
//   transform -> raw groups -> addToGroupTable(raw) gives CountedGroups ->
//   makeQuery(.., counted, ..) (refined weights) -> query ->
//   add(entry, std::move(counted), ..).
// The query's raw groups enter the table BEFORE its refined weights are
// computed: eq. 1's IDF log(total / cumulative(i)) is then finite for every
// group of the query (cumulative(i) > 0). The entry itself enters the inverse
// indexes only AFTER the query, so a keyframe never matches itself.
#pragma once

#include <cstdint>
#include <deque>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/database/counted_groups.h"
#include "bowg/database/descriptor_file.h"
#include "bowg/database/distribution_table.h"
#include "bowg/database/inverse_index.h"
#include "bowg/database/missions.h"
#include "bowg/database/packed_points.h"
#include "bowg/database/packed_words.h"
#include "bowg/database/query_scratch.h"
#include "bowg/database/recent_vectors.h"
#include "bowg/scoring/word_groups.h"
#include "bowg/vocabulary/bow_vector.h"

namespace bowg {

class Vocabulary;

/// Per-feature ancestors of the words at depth `level` of the vocabulary
/// (parent links; a leaf shallower than `level` stands for itself), as a
/// DirectIndex. Equal to the direct index Vocabulary::transform builds.
DirectIndex directIndexFromWords(const Vocabulary& vocabulary, const std::vector<WordId>& words,
                                 int level);

/// One past the largest keyframe stamp, 2^32 s: stamps are ROS times
/// (unsigned 32-bit seconds) or an image folder's n / rate, in [0, 2^32).
constexpr double kStampLimit = 4294967296.0;

/// One keyframe as stored in the database.
struct DatabaseEntry {
  EntryId id = 0;
  double stamp = 0;  ///< in [0, kStampLimit), increasing
  /// Keypoint positions: the only part of a keypoint read after insertion,
  /// packed in 4 bytes each where that is lossless.
  PackedPoints points;
  /// The descriptors, index-aligned with the points; empty when they were
  /// left in the file the entry was loaded from (`on_disk`,
  /// descriptor_file.h). Read them through descriptorsRead().
  std::vector<Descriptor> descriptors;
  DescriptorsOnDisk on_disk;
  PackedWords words;                  ///< word of each feature (index-aligned)
  double centre_x = 0, centre_y = 0;  ///< centre of the distribution fan
  CameraIntrinsics intrinsics;
  /// Metres driven since the first keyframe (KeyframeInput::odometer); NaN
  /// when unknown.
  double odometer = std::numeric_limits<double>::quiet_NaN();
  /// KeyframeInput::position, and the odometry run it belongs to: positions
  /// are compared within one run only (one odometry frame; a detector
  /// loaded from a file starts a new run, DetectorState::odometry_run).
  OdometryPosition position;
  std::uint32_t odometry_run = 0;
  /// KeyframeInput::heading, in the frame of `odometry_run` as the position.
  OdometryHeading heading;
  /// The mission (survey) the keyframe was taken in: an id of the
  /// database's missions(). A mission's odometry runs are its own.
  std::uint32_t mission = 0;
  /// False: the entry stays out of the inverse index (Database::add), so no
  /// query finds it as a candidate, while its scores against a query
  /// (Database::score, the normalisers of eqs. 2 and 4), its words, points
  /// and descriptors stay available. A keyframe whose loop made its place
  /// larger than IslandOptions::indexed_per_place is one: the index then
  /// grows with the places driven, not with the laps.
  bool searchable = true;

  /// The number of descriptors, in memory or on disk.
  std::size_t descriptorCount() const { return on_disk.file ? on_disk.count : descriptors.size(); }
  /// The descriptors: `descriptors`, or the block on disk read into
  /// `scratch` (DescriptorFile::read's errors).
  const std::vector<Descriptor>& descriptorsRead(std::vector<Descriptor>* scratch) const;
  // Derived from `words` when needed, not kept: the BoW vector
  // (Database::bow()), the raw groups (Database::rawGroups()) and the direct
  // index at Database::directLevel() (directIndexFromWords). The distribution vector for the
  // current m lives in the database's contiguous distribution table (Database::distribution()).
};

/// Largest number of entries a database holds: ids fit a posting's 24 bits
/// (16,777,216 keyframes, 670 km of pipe at one keyframe per 4 cm).
constexpr std::size_t kMaxEntries = std::size_t{1} << Posting::kEntryBits;

/// Raw scores of one database entry against a query (paper notation).
struct EntryScores {
  EntryId entry = 0;
  double s_w = 0;  ///< word score (bow_vector.h metric)
  double s_g = 0;  ///< word-group score (eq. 3)
  double s_d = 0;  ///< distribution score (Sec. III-C)
};

/// What a query needs of the query keyframe.
struct DatabaseQuery {
  BowVector bow;                     ///< normalised for the database's scoring
  GroupVector refined_groups;        ///< eq. 1 with the current table
  std::vector<double> distribution;  ///< for the current m (may be empty)
  /// The IDF of each refined group (index-aligned) and the version of the
  /// table it was read from (makeQuery): query() and score() need the same
  /// IDFs again and reuse these while the table's version is this one.
  std::vector<double> group_idf;
  std::uint64_t group_table_version = 0;
  /// The scoring `bow` was normalised for.
  ScoringType scoring = ScoringType::kL1;
};

class Database {
 public:
  Database(std::shared_ptr<const Vocabulary> vocabulary, ScoringType scoring,
           int direct_index_level, int fan_bins);

  std::size_t size() const { return entries_.size(); }
  bool empty() const { return entries_.empty(); }
  const DatabaseEntry& entry(EntryId id) const { return entries_.at(id); }
  const std::deque<DatabaseEntry>& entries() const { return entries_; }
  /// Odometer per entry, non-decreasing: an entry without one (NaN) takes
  /// the last known value before it (-inf before the first), so that an
  /// entry id range of a metre interval is two binary searches
  /// (temporal_alignment.h).
  const std::vector<double>& odometers() const { return odometers_; }
  /// The largest odometer known (-inf when no entry has one).
  double lastOdometer() const {
    return odometers_.empty() ? -std::numeric_limits<double>::infinity() : odometers_.back();
  }
  const Vocabulary& vocabulary() const { return *vocabulary_; }
  const WordGroupTable& groupTable() const { return group_table_; }
  /// The cached distribution vector of entry `id` for the current m.
  std::vector<double> distribution(EntryId id) const;

  /// The missions the entries belong to (a new database: the unnamed
  /// mission 0).
  const MissionTable& missions() const { return missions_; }
  /// MissionTable::add and MissionTable::reassign.
  void addMission(std::uint32_t id, const std::string& name) { missions_.add(id, name); }
  void reassignMission(std::uint32_t id, std::uint32_t new_id, const std::string& name) {
    missions_.reassign(id, new_id, name);
  }
  /// MissionTable::restore, for a database without entries (a loaded file's
  /// missions before its entries are added); std::logic_error otherwise.
  void restoreMissions(const std::vector<Mission>& missions);

  ScoringType scoring() const { return scoring_; }
  int directLevel() const { return direct_level_; }
  int fanBins() const { return distributions_.bins(); }

  /// Option changes. Each rebuilds only what depends on it: the scoring type
  /// rewrites every posting's BoW weight; the direct-index level applies to
  /// the next verification; m rebuilds every cached distribution vector from
  /// the stored keypoint positions.
  void setScoring(ScoringType scoring);
  void setDirectLevel(int level);
  void setFanBins(int m);

  /// Step 3 of the order above: a keyframe's raw groups (buildWordGroups()
  /// of its keypoints) join the table; the token returned carries them to
  /// makeQuery and add. Empty groups leave the table as it is. Throws
  /// std::invalid_argument on a weight that is not finite and positive.
  CountedGroups addToGroupTable(GroupVector raw);

  /// Step 5: appends `entry` (its id is set to size()), computes its derived
  /// fields and adds it to the inverse index (its BoW vector from its words,
  /// as bow() does, and the counted raw groups), marking `counted` added once
  /// it is in (a throw leaves it as it was). Returns the id. Throws
  /// std::invalid_argument on inconsistent sizes or word ids, and on a raw
  /// group that is not one of the entry's words or whose weight is not a
  /// whole count in [1, 2^24); std::length_error when the database already
  /// holds kMaxEntries; std::invalid_argument also when the entry's
  /// mission is not in missions(); std::logic_error when `counted` was added
  /// already, moved from or counted by another database.
  /// `distribution`: the entry's distribution vector for the current
  /// fanBins() when the caller has it already (makeQuery's, for the keyframe
  /// just queried: the same positions give the same vector); empty: it is
  /// computed here from the entry's positions. A non-empty vector of another
  /// size is refused (std::invalid_argument).
  EntryId add(DatabaseEntry entry, CountedGroups&& counted,
              const std::vector<double>& distribution = std::vector<double>());
  /// add() for the keyframe just queried with `queried`: makeQuery's query
  /// for this entry, from the BoW vector of the entry's words (the one
  /// Vocabulary::transform gave with them) and its positions. Its BoW and
  /// distribution vectors are the ones add() would build again, so they are
  /// taken from it. std::invalid_argument also when `queried` was normalised
  /// for another scoring or its BoW holds a word the entry does not have.
  EntryId add(DatabaseEntry entry, CountedGroups&& counted, const DatabaseQuery& queried);

  /// Entry `id`'s BoW vector normalised for scoring(): the vocabulary's
  /// transform of its words (Vocabulary::bowFromWords), normalised; the
  /// weights the inverse index holds for it (as floats). Rebuilt on each call (a
  /// few microseconds): keeping it would cost ~5 kB per keyframe. The newest
  /// few entries' vectors are kept (see recent_).
  BowVector bow(EntryId id) const;

  /// Entry `id`'s raw groups w_{g,t}^(i) as add() received them, read back
  /// from the inverse index through its words (or, for an entry that is not
  /// searchable, from the groups kept apart).
  GroupVector rawGroups(EntryId id) const;

  /// Step 4: the query's normalised BoW and refined groups (eq. 1 on the
  /// counted groups with the table as it stands). std::logic_error when
  /// `counted` was moved from or counted by another database.
  DatabaseQuery makeQuery(BowVector bow, const CountedGroups& counted,
                          const std::vector<ImagePoint>& points, double centre_x, double centre_y,
                          bool with_distribution) const;

  /// Number of searchable entries (DatabaseEntry::searchable): those a
  /// query can return.
  std::size_t searchableCount() const { return index_.searchableCount(); }

  /// Scores every searchable entry with id < limit that shares at least one word (and,
  /// when `with_groups`, at least one group) with the query, through the
  /// inverse index. s_d is filled when the query has a distribution vector.
  /// Result sorted by entry id. `scratch`: the caller's working memory,
  /// reused across queries (query_scratch.h); the overload without it
  /// allocates its own.
  std::vector<EntryScores> query(const DatabaseQuery& q, EntryId limit, bool with_groups,
                                 QueryScratch* scratch) const;
  std::vector<EntryScores> query(const DatabaseQuery& q, EntryId limit, bool with_groups) const;

  /// The same three scores against one entry computed directly from the
  /// stored vectors (the normalisers of eqs. 2 and 4 use it with I_{t-1}).
  EntryScores score(const DatabaseQuery& q, EntryId id) const;

  /// Heap bytes held by the entries and indexes, with glibc's per-allocation
  /// overhead (docs/benchmarks.md compares it with the resident set).
  std::size_t memoryBytes() const;

  /// Forgets every entry; the missions go back to the unnamed mission 0.
  void clear();

 private:
  // Throws std::logic_error unless `counted` is this database's and, when
  // `to_add`, not added yet.
  void checkCounted(const CountedGroups& counted, const char* function, bool to_add) const;
  // Both add()s: `queried` is the query made for the entry when the caller
  // has it (its BoW vector is taken; null: built from the words); marks
  // `counted` added once the entry is in.
  EntryId addEntry(DatabaseEntry entry, CountedGroups* counted,
                   const std::vector<double>& distribution, const DatabaseQuery* queried);
  // add()'s checks of the entry against itself, the database and its inputs.
  void checkEntry(const DatabaseEntry& e, const std::vector<WordId>& words,
                  const GroupVector& raw_groups, const std::vector<double>& distribution,
                  const BowVector* bow) const;
  // Whether q's group IDFs were read from the table as it stands.
  bool queryIdfCurrent(const DatabaseQuery& q) const {
    return q.group_table_version == group_table_.version() &&
           q.group_idf.size() == q.refined_groups.size();
  }
  /// The normalised BoW vector of an entry's words (bow()).
  BowVector bowOfWords(const std::vector<WordId>& words) const;
  /// query()'s terms: the query's words and groups with their weights.
  void collectQueryWords(const DatabaseQuery& q, bool with_groups, QueryScratch* scratch) const;
  /// query()'s scores of the touched entries, which it resets for the next.
  std::vector<EntryScores> finishScores(const DatabaseQuery& q, bool with_groups, double base,
                                        std::size_t touched, QueryScratch* scratch) const;

  std::shared_ptr<const Vocabulary> vocabulary_;
  ScoringType scoring_;
  int direct_level_;
  /// A deque, not a vector: adding never moves the entries. A vector
  /// grown by an eighth moved them all every ~2,000 keyframes at 17,000,
  /// and the fresh 3.5 MB block's page faults made those keyframes take
  /// 5-15 ms instead of ~1 (the long run's slowest keyframes, one at each
  /// growth). Same memory per entry (~212 bytes either way).
  std::deque<DatabaseEntry> entries_;
  std::vector<double> odometers_;  ///< see odometers()
  WordGroupTable group_table_;
  InverseIndex index_;
  DistributionTable distributions_;
  RecentVectors recent_;
  MissionTable missions_;
};

}  // namespace bowg
