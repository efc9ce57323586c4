// The two sides of a geometric verification within one query: the query's
// and the database entries' keypoints, descriptors and direct indexes, made
// on demand (the database keeps packed positions and words, not direct
// indexes). Internal to the detection stage.
#pragma once

#include <deque>
#include <unordered_map>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/database/database.h"
#include "bowg/detection/geometric_verification.h"
#include "bowg/vocabulary/vocabulary.h"

namespace bowg {
namespace query_steps {

// What a verification view of a database entry points into: its positions
// unpacked (the database packs them, PackedPoints), its direct index, made
// from its words, and its descriptors when they were left on disk
// (descriptor_file.h).
struct EntryViewStorage {
  std::vector<ImagePoint> points;
  std::vector<WordId> words;
  DirectIndex direct;
  std::vector<Descriptor> read;
};

// Entry `e`'s descriptors: its own, or those read into `storage`.
inline const std::vector<Descriptor>* viewDescriptors(const DatabaseEntry& e,
                                                      const EntryViewStorage& storage) {
  return e.on_disk.file ? &storage.read : &e.descriptors;
}

// The views of recent database entries, kept across queries: the verified
// chain's recent past (repeated_texture.h) is a dozen keyframes a query, most
// of them the previous queries' too. Entries never change once added; a
// change of the direct-index level empties it. At most kCapacity entries,
// the oldest out first.
class EntryViewCache {
 public:
  static constexpr std::size_t kCapacity = 128;
  /// Entry `id`'s storage at direct-index `level`, or nullptr.
  const EntryViewStorage* find(EntryId id, int level) {
    if (level != level_) clear();
    level_ = level;
    const auto it = views_.find(id);
    return it == views_.end() ? nullptr : &it->second;
  }
  /// Stores `storage` for `id`; valid until kCapacity later insertions.
  const EntryViewStorage& insert(EntryId id, EntryViewStorage storage) {
    if (order_.size() == kCapacity) {
      views_.erase(order_.front());
      order_.pop_front();
    }
    order_.push_back(id);
    return views_[id] = std::move(storage);
  }
  void clear() {
    views_.clear();
    order_.clear();
  }

 private:
  int level_ = -1;
  std::unordered_map<EntryId, EntryViewStorage> views_;
  std::deque<EntryId> order_;
};

// The two sides of a geometric verification. The query's direct index is
// built on the first verification only (with one verified candidate most
// queries stop at the temporal check before it), a database entry's for each
// correspondence search with it: the database keeps words, not direct
// indexes. RANSAC on correspondences already found needs none (features()).
// A candidate of a loaded map has its descriptors on disk: the last one read
// is kept, so its correspondences (match()), RANSAC (features()) and metric
// step (entry()) read and check its block once.
class Verifier {
 public:
  Verifier(const Vocabulary& vocabulary, const Database& database, const DatabaseEntry& query,
           const CameraIntrinsics& k, bool exhaustive)
      : vocabulary_(vocabulary),
        database_(database),
        query_(query),
        intrinsics_(k),
        exhaustive_(exhaustive),
        built_(false) {}

  VerificationView query() {
    if (!built_) {
      unpack(query_, &query_storage_);
      built_ = true;
    }
    return VerificationView{&query_storage_.points, viewDescriptors(query_, query_storage_),
                            &query_storage_.direct};
  }

  /// Valid until the next call.
  VerificationView match(EntryId id) {
    const DatabaseEntry& m = database_.entry(id);
    unpackWithoutDescriptors(m, &match_storage_);
    return VerificationView{&match_storage_.points, descriptorsOf(id, m), &match_storage_.direct};
  }

  /// Entry `id`'s keypoints and descriptors without a direct index: enough
  /// for RANSAC on correspondences already found (verifyCorrespondences).
  /// Valid until the next call.
  VerificationView features(EntryId id) {
    const DatabaseEntry& m = database_.entry(id);
    m.points.unpack(&features_points_);
    return VerificationView{&features_points_, descriptorsOf(id, m), nullptr};
  }

  /// Entry `id`'s view from `cache` (made and stored there when absent).
  VerificationView cached(EntryId id, EntryViewCache* cache) const {
    const DatabaseEntry& m = database_.entry(id);
    const EntryViewStorage* storage = cache->find(id, database_.directLevel());
    if (storage == nullptr) {
      EntryViewStorage made;
      unpack(m, &made);
      storage = &cache->insert(id, std::move(made));
    }
    return VerificationView{&storage->points, viewDescriptors(m, *storage), &storage->direct};
  }

  /// Entry `id`'s view, its positions and direct index in `storage`; its
  /// descriptors there too unless they are the last read (valid then until
  /// the next match() or features()).
  VerificationView entry(EntryId id, EntryViewStorage* storage) const {
    const DatabaseEntry& m = database_.entry(id);
    if (id != read_id_) return viewOf(m, storage);
    unpackWithoutDescriptors(m, storage);
    return VerificationView{&storage->points, &read_, &storage->direct};
  }

  /// Descriptor blocks read from disk so far (descriptor_file.h).
  std::size_t blocksRead() const { return blocks_read_; }

  const CameraIntrinsics& intrinsics() const { return intrinsics_; }
  const DatabaseEntry& queryEntry() const { return query_; }

 private:
  VerificationView viewOf(const DatabaseEntry& m, EntryViewStorage* storage) const {
    unpack(m, storage);
    return VerificationView{&storage->points, viewDescriptors(m, *storage), &storage->direct};
  }

  // Entry `id`'s descriptors: its own, or its block on disk read once.
  const std::vector<Descriptor>* descriptorsOf(EntryId id, const DatabaseEntry& m) {
    if (!m.on_disk.file) return &m.descriptors;
    if (id != read_id_) {
      read_id_ = kNoneRead;  // a read that throws leaves no stale block behind
      m.descriptorsRead(&read_);
      ++blocks_read_;
      read_id_ = id;
    }
    return &read_;
  }

  void unpack(const DatabaseEntry& e, EntryViewStorage* storage) const {
    unpackWithoutDescriptors(e, storage);
    if (e.on_disk.file) {
      e.descriptorsRead(&storage->read);
      ++blocks_read_;
    }
  }

  void unpackWithoutDescriptors(const DatabaseEntry& e, EntryViewStorage* storage) const {
    e.points.unpack(&storage->points);
    if (!exhaustive_) {
      e.words.unpack(&storage->words);
      storage->direct = directIndexFromWords(vocabulary_, storage->words, database_.directLevel());
    }
  }

  const Vocabulary& vocabulary_;
  const Database& database_;
  const DatabaseEntry& query_;
  const CameraIntrinsics& intrinsics_;
  static constexpr EntryId kNoneRead = static_cast<EntryId>(-1);
  EntryViewStorage query_storage_, match_storage_;
  std::vector<ImagePoint> features_points_;
  std::vector<Descriptor> read_;  // entry read_id_'s descriptors, read from disk
  EntryId read_id_ = kNoneRead;
  mutable std::size_t blocks_read_ = 0;
  bool exhaustive_;
  bool built_;
};

}  // namespace query_steps
}  // namespace bowg
