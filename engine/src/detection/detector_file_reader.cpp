// Loading the detector file (detector_file.h; layout in
// detector_file_format.h). Every count read is checked against the bytes
// left before anything is allocated, so a corrupt count cannot trigger a huge
// allocation; the checksum is verified before any content is interpreted;
// every value restored is checked against what a run can produce.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "bowg/core/bounded_file.h"
#include "bowg/core/checksum.h"
#include "bowg/database/descriptor_file.h"
#include "bowg/detection/detector_file.h"
#include "bowg/vocabulary/vocabulary.h"
#include "detection/detector_file_format.h"

namespace bowg {

using namespace detector_file;

namespace {

Island readIsland(Reader* r) {
  Island i;
  i.first = r->u32("island");
  i.last = r->u32("island");
  i.score = r->f64("island");
  i.best_entry = r->u32("island");
  i.best_score = r->f64("island");
  i.size = r->i32("island");
  return i;
}

// Magic, version and payload size of a file of `file_size` bytes whose
// first bytes are `head`; returns the version.
std::uint32_t checkFrame(const std::string& path, const char* head, std::size_t head_size,
                         std::uint64_t file_size, std::uint64_t* payload_size) {
  Reader header(path, head, head_size);
  if (file_size < kHeaderBytes + kTrailerBytes) {
    header.fail("file too short (" + std::to_string(file_size) + " bytes) to be a database");
  }
  if (std::memcmp(head, kMagic, 8) != 0) header.fail("not a BoWG database (bad magic)");
  Reader r(path, head + 8, head_size - 8);
  const std::uint32_t version = r.u32("version");
  if (version < kOldestVersion || version > kVersion) {
    r.fail("unsupported version " + std::to_string(version) + " (expected " +
           std::to_string(kOldestVersion) + " to " + std::to_string(kVersion) + ")");
  }
  r.u64("vocabulary fingerprint");
  const std::uint64_t payload = r.u64("payload size");
  if (payload != file_size - kHeaderBytes - kTrailerBytes) {
    r.fail("payload size " + std::to_string(payload) + " does not match the file length " +
           std::to_string(file_size) + " (truncated or extended)");
  }
  *payload_size = payload;
  return version;
}

// The stored checksum against the one computed, then the vocabulary's
// fingerprint; `r` names the file.
void checkSumAndVocabulary(const Reader& r, std::uint64_t computed, std::uint64_t stored,
                           std::uint64_t fingerprint, const Vocabulary& vocabulary) {
  if (computed != stored) r.fail("checksum mismatch (the file is corrupt)");
  if (fingerprint != vocabulary.fingerprint()) {
    r.fail(
        "it was built with another vocabulary (fingerprint mismatch): load the vocabulary "
        "the database was created with");
  }
}

// Frame, checksum and vocabulary of bytes in memory; returns the version.
std::uint32_t checkHeader(const std::string& path, const char* bytes, std::size_t size,
                          const Vocabulary& vocabulary, std::uint64_t* payload_size) {
  const std::uint32_t version = checkFrame(path, bytes, size, size, payload_size);
  Reader r(path, bytes + 8, size - 8);
  r.u32("version");
  const std::uint64_t fingerprint = r.u64("vocabulary fingerprint");
  Reader trailer(path, bytes + size - kTrailerBytes, kTrailerBytes);
  checkSumAndVocabulary(r, checksum64(bytes, size - kTrailerBytes), trailer.u64("checksum"),
                        fingerprint, vocabulary);
  return version;
}

// The same of an open file (bounded_file.h: a regular file within
// BOWG_MAX_DATABASE_MB): its header checked against its length first, then
// the checksum over the file read in chunks, before any content is
// interpreted. Nothing is held but one chunk.
std::uint32_t checkFileHeader(const BoundedFile& file, const Vocabulary& vocabulary,
                              std::uint64_t* payload_size) {
  char head[kHeaderBytes];
  const std::size_t head_size =
      static_cast<std::size_t>(std::min<std::uint64_t>(file.size(), kHeaderBytes));
  file.readAt(head, head_size, 0);
  const std::uint32_t version = checkFrame(file.path(), head, head_size, file.size(), payload_size);
  Reader r(file.path(), head + 8, head_size - 8);
  r.u32("version");
  const std::uint64_t fingerprint = r.u64("vocabulary fingerprint");
  const std::uint64_t summed = file.size() - kTrailerBytes;
  char stored[kTrailerBytes];
  file.readAt(stored, kTrailerBytes, summed);
  Reader trailer(file.path(), stored, kTrailerBytes);
  checkSumAndVocabulary(r, checksumOfFile(file, summed), trailer.u64("checksum"), fingerprint,
                        vocabulary);
  return version;
}

// Stamp, fan centre and intrinsics of entry `i`.
void readEntryHeader(Reader* p, const std::string& entry, DatabaseEntry* e) {
  e->stamp = p->f64("entry stamp");
  e->centre_x = p->f64("entry centre");
  e->centre_y = p->f64("entry centre");
  e->intrinsics.valid = p->u8("intrinsics") != 0;
  e->intrinsics.fx = p->f64("intrinsics");
  e->intrinsics.fy = p->f64("intrinsics");
  e->intrinsics.cx = p->f64("intrinsics");
  e->intrinsics.cy = p->f64("intrinsics");
  // A keyframe's stamp is a ROS time (unsigned 32-bit seconds) or an image
  // folder's n / rate: a value outside [0, 2^32) s was never written by a run.
  if (!(e->stamp >= 0.0 && e->stamp < kStampLimit)) {
    p->fail(entry + " has an implausible stamp (" + std::to_string(e->stamp) +
            " s; stamps lie in [0, 2^32) s)");
  }
  if (!std::isfinite(e->centre_x) || !std::isfinite(e->centre_y)) {
    p->fail(entry + " has a non-finite centre");
  }
  const CameraIntrinsics& k = e->intrinsics;
  if (k.valid && !(k.fx > 0.0 && k.fy > 0.0 && std::isfinite(k.fx) && std::isfinite(k.fy) &&
                   std::isfinite(k.cx) && std::isfinite(k.cy))) {
    p->fail(entry + " has invalid intrinsics (fx, fy must be finite > 0, cx, cy finite)");
  }
}

// Where a file's descriptors are left (descriptor_file.h): the open file the
// payload is streamed from.
struct DiskDescriptors {
  std::shared_ptr<const DescriptorFile> file;
};

// Keypoints, descriptors and words of one entry (the words also unpacked in
// `words`, for the checks). With `disk`, the descriptors stay in the file:
// the entry keeps where its records are and their checksum.
void readFeatures(Reader* p, const std::string& entry, const DiskDescriptors* disk,
                  DatabaseEntry* e, std::vector<WordId>* words) {
  const std::size_t nf = p->count(kFeatureBytes, "features");
  p->need(nf * kFeatureBytes, "features");  // the block at once, contiguous
  const char* records = p->position();
  const std::uint64_t records_offset = p->offset();
  std::vector<ImagePoint> points(nf);
  if (disk == nullptr) e->descriptors.resize(nf);
  words->resize(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    // Every field is checked; the database keeps the position only.
    Keypoint k;
    k.x = p->f32("keypoint");
    k.y = p->f32("keypoint");
    k.size = p->f32("keypoint");
    k.angle = p->f32("keypoint");
    k.response = p->f32("keypoint");
    k.octave = p->i32("keypoint");
    if (!std::isfinite(k.x) || !std::isfinite(k.y) || !std::isfinite(k.angle) ||
        !std::isfinite(k.response) || !(k.size >= 0.0f && std::isfinite(k.size))) {
      p->fail(entry + " keypoint " + std::to_string(f) +
              " has a non-finite coordinate, angle or response, or an invalid size");
    }
    points[f] = ImagePoint{k.x, k.y};
    if (disk == nullptr) {
      for (auto& b : e->descriptors[f].bits) b = p->u64("descriptor");
    } else {
      p->skip(sizeof(Descriptor), "descriptor");
    }
    (*words)[f] = p->u32("word");
  }
  if (disk != nullptr) {
    e->on_disk.file = disk->file;
    e->on_disk.offset = records_offset;
    e->on_disk.count = static_cast<std::uint32_t>(nf);
    e->on_disk.checksum =
        DescriptorFile::blockChecksum(records, static_cast<std::size_t>(p->position() - records));
  }
  // Packed again with the entry's scale factor once it is read (version 5).
  e->points = PackedPoints(points, 0.f);
  e->words = PackedWords(*words);
}

DatabaseEntry readEntry(Reader* p, std::size_t i, ScoringType stored_scoring,
                        const Vocabulary& vocabulary, const DiskDescriptors* disk,
                        GroupVector* raw_groups) {
  DatabaseEntry e;
  const std::string entry = "entry " + std::to_string(i);
  readEntryHeader(p, entry, &e);
  std::vector<WordId> words;
  readFeatures(p, entry, disk, &e, &words);
  const BowVector bow = p->pairs("BoW vector");
  *raw_groups = p->pairs("word groups");
  // Stored weights are > 0 (words of weight 0 are never stored) and, for
  // every scoring type but the dot product, normalised to at most 1.
  const bool normalised = stored_scoring != ScoringType::kDotProduct;
  for (const auto& b : bow) {
    if (!(b.second > 0.0) || (normalised && b.second > 1.0 + 1e-9)) {
      p->fail(entry + " has a BoW weight " + std::to_string(b.second) + " outside (0, " +
              (normalised ? "1]" : "inf)"));
    }
  }
  // The database rebuilds the vector from the words (Database::bow): the
  // stored one must be that vector, or the file contradicts itself. (Word
  // ids out of range are the database's to reject, with its message.)
  const bool words_in_range =
      std::all_of(words.begin(), words.end(), [&](WordId w) { return w < vocabulary.wordCount(); });
  if (words_in_range) {
    BowVector expected = vocabulary.bowFromWords(words);
    normaliseBowVector(stored_scoring, &expected);
    bool same = expected.size() == bow.size();
    for (std::size_t k = 0; same && k < bow.size(); ++k) {
      same = expected[k].first == bow[k].first &&
             std::abs(expected[k].second - bow[k].second) <= 1e-9 * expected[k].second;
    }
    if (!same) p->fail(entry + " has a BoW vector that is not the one its words give");
  }
  for (const auto& g : *raw_groups) {
    if (!(g.second > 0.0)) p->fail(entry + " has a word-group weight <= 0");
  }
  return e;
}

// The temporal chain as stored, restored once the entries are in.
struct StoredChain {
  Island last;
  int length = 0;
  int missed = 0;
  double last_query_m = std::numeric_limits<double>::quiet_NaN();
  std::vector<IslandHypothesis> others;
};

// Version 1: eq. 7's previous scores and the chosen island's chain.
void readPreviousScoresAndChain(Reader* p, std::size_t n, DetectorState* state,
                                StoredChain* chain) {
  state->previous_etas = p->pairs("previous scores");
  if (!state->previous_etas.empty() && state->previous_etas.back().first >= n) {
    p->fail("previous scores refer to an entry beyond the database");
  }
  for (const auto& e : state->previous_etas) {
    if (e.second < 0.0) p->fail("a previous score is negative");
  }
  chain->last = readIsland(p);
  chain->length = p->i32("chain length");
  // A chain counts queries, one per entry: it cannot be longer than the
  // database (a forged one would pass the temporal check at once).
  if (chain->length < 0 || static_cast<std::size_t>(chain->length) > n) {
    p->fail("temporal-consistency chain length " + std::to_string(chain->length) + " outside 0.." +
            std::to_string(n) + " (the number of entries)");
  }
}

// Version 2: the normaliser history.
void readNormalisers(Reader* p, DetectorState* state) {
  const std::size_t nn = p->count(kNormaliserBytes, "normalisers");
  std::vector<Normalisers> normalisers(nn);
  for (Normalisers& v : normalisers) {
    v.word = p->f64("normaliser");
    v.group = p->f64("normaliser");
    v.distribution = p->f64("normaliser");
    if (!(v.word >= 0.0) || !(v.group >= 0.0) || !(v.distribution >= 0.0) ||
        !std::isfinite(v.word + v.group + v.distribution)) {
      p->fail("a stored normaliser is negative or not finite");
    }
  }
  state->normalisers.restore(normalisers);
}

// Version 3: the missed-query counters and the odometers.
void readCountersAndOdometers(Reader* p, std::vector<DatabaseEntry>* entries, DetectorState* state,
                              StoredChain* chain) {
  const std::size_t n = entries->size();
  state->missed_queries = p->i32("missed queries");
  chain->missed = p->i32("missed queries");
  if (state->missed_queries < 0 || chain->missed < 0 ||
      static_cast<std::size_t>(state->missed_queries) > n ||
      static_cast<std::size_t>(chain->missed) > n) {
    p->fail("missed-query count outside 0.." + std::to_string(n));
  }
  if (state->missed_queries > 0 && state->previous_etas.empty()) {
    p->fail("missed queries counted without previous scores");
  }
  if (chain->missed > 0 && chain->length == 0) {
    p->fail("missed queries counted without a temporal chain");
  }
  if (p->count(8, "odometers") != n) p->fail("odometer count differs from the entry count");
  double previous = -1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double o = p->f64("odometer");
    (*entries)[i].odometer = o;
    if (std::isnan(o)) continue;
    if (!std::isfinite(o) || o < 0.0 || o < previous) {
      p->fail("entry " + std::to_string(i) + " has a negative, non-finite or decreasing odometer");
    }
    previous = o;
  }
  state->previous_odometer = p->f64("odometer");
  chain->last_query_m = p->f64("odometer");
  for (double o : {state->previous_odometer, chain->last_query_m}) {
    if (!std::isnan(o) && !(std::isfinite(o) && o >= 0.0)) {
      p->fail("a stored query odometer is invalid");
    }
  }
}

// Version 4: the temporal verification's other hypotheses.
void readHypotheses(Reader* p, std::size_t n, StoredChain* chain) {
  const std::size_t no = p->count(kIslandBytes + 4, "hypotheses");
  if (no > 0 && chain->length == 0) p->fail("temporal hypotheses stored without a temporal chain");
  chain->others.resize(no);
  for (IslandHypothesis& h : chain->others) {
    h.island = readIsland(p);
    h.chain_length = p->i32("chain length");
    if (h.chain_length < 1 || static_cast<std::size_t>(h.chain_length) > n) {
      p->fail("a temporal hypothesis has a chain length outside 1.." + std::to_string(n));
    }
  }
}

// Each entry's pyramid scale factor: its positions are packed with it.
void readScaleFactors(Reader* p, std::vector<DatabaseEntry>* entries) {
  if (p->count(4, "scale factors") != entries->size()) {
    p->fail("scale factor count differs from the entry count");
  }
  for (std::size_t i = 0; i < entries->size(); ++i) {
    const float f = p->f32("scale factor");
    if (!(std::isfinite(f) && f >= 0.f)) {
      p->fail("entry " + std::to_string(i) + " has a negative or non-finite pyramid scale factor");
    }
    DatabaseEntry& e = (*entries)[i];
    if (f > 0.f) e.points = PackedPoints(e.points.unpack(), f);
  }
}

// Version 6: the entries joined by accepted loops.
void readPlaceLinks(Reader* p, std::size_t n, DetectorState* state) {
  if (p->count(4, "place links") != n) p->fail("place link count differs from the entry count");
  std::vector<EntryId> parents(n);
  for (EntryId& e : parents) e = p->u32("place link");
  state->place_links.restore(std::move(parents));
}

// Version 7: the odometry run new entries belong to, then each entry's run
// and odometry position (all finite or all NaN; runs never after the
// current one).
void readOdometryPositions(Reader* p, std::vector<DatabaseEntry>* entries, DetectorState* state) {
  state->odometry_run = p->u32("odometry run");
  if (p->count(4 + 3 * 8, "odometry positions") != entries->size()) {
    p->fail("odometry position count differs from the entry count");
  }
  for (std::size_t i = 0; i < entries->size(); ++i) {
    DatabaseEntry& e = (*entries)[i];
    e.odometry_run = p->u32("odometry run");
    e.position.x = p->f64("odometry position");
    e.position.y = p->f64("odometry position");
    e.position.z = p->f64("odometry position");
    if (e.odometry_run > state->odometry_run) {
      p->fail("entry " + std::to_string(i) + " belongs to odometry run " +
              std::to_string(e.odometry_run) + ", after the current run " +
              std::to_string(state->odometry_run));
    }
    if (!e.position.valid()) {
      p->fail("entry " + std::to_string(i) +
              " has an odometry position that is neither all "
              "finite nor all NaN");
    }
  }
}

// Version 10: each entry's odometry heading (a unit vector or all NaN).
void readHeadings(Reader* p, std::vector<DatabaseEntry>* entries) {
  if (p->count(3 * 4, "odometry headings") != entries->size()) {
    p->fail("odometry heading count differs from the entry count");
  }
  for (std::size_t i = 0; i < entries->size(); ++i) {
    OdometryHeading& h = (*entries)[i].heading;
    h.x = p->f32("odometry heading");
    h.y = p->f32("odometry heading");
    h.z = p->f32("odometry heading");
    if (!h.valid()) {
      p->fail("entry " + std::to_string(i) +
              " has an odometry heading that is neither a unit vector nor all NaN");
    }
  }
}

void readSearchable(Reader* p, std::vector<DatabaseEntry>* entries) {
  if (p->count(1, "searchable flags") != entries->size()) {
    p->fail("searchable flag count differs from the entry count");
  }
  for (std::size_t i = 0; i < entries->size(); ++i) {
    const std::uint8_t flag = p->u8("searchable flag");
    if (flag > 1) {
      p->fail("entry " + std::to_string(i) + " has searchable flag " + std::to_string(flag) +
              " (0 or 1)");
    }
    (*entries)[i].searchable = flag == 1;
  }
}

// The chain's islands must lie inside the database; their odometers come
// from the entries.
void restoreChain(Reader* p, const Database& db, StoredChain* chain, DetectorState* state) {
  const std::size_t n = db.size();
  const auto place = [&](Island* i) {
    if (i->first > i->last || i->last >= n || i->best_entry < i->first || i->best_entry > i->last) {
      p->fail("a temporal island lies outside the database");
    }
    i->first_m = db.entry(i->first).odometer;
    i->last_m = db.entry(i->last).odometer;
  };
  if (chain->length > 0) place(&chain->last);
  for (IslandHypothesis& h : chain->others) place(&h.island);
  state->consistency.restore(chain->last, chain->length, chain->missed, chain->last_query_m,
                             std::move(chain->others));
}

// The payload of a file of `version` whose header was checked, from `p`;
// with `disk`, `p` streams its file, whose descriptors stay there.
std::unique_ptr<Database> decodePayload(Reader& p, std::uint32_t version,
                                        std::shared_ptr<const Vocabulary> vocabulary,
                                        ScoringType scoring, int direct_index_level, int fan_bins,
                                        DetectorState* state, ScoringType* stored_scoring_out,
                                        const DiskDescriptors* disk) {
  std::unique_ptr<Database> db(new Database(vocabulary, scoring, direct_index_level, fan_bins));
  const std::uint32_t stored_scoring = p.u32("scoring type");
  if (stored_scoring > static_cast<std::uint32_t>(ScoringType::kDotProduct)) {
    p.fail("unknown scoring type " + std::to_string(stored_scoring));
  }
  if (stored_scoring_out != nullptr) *stored_scoring_out = static_cast<ScoringType>(stored_scoring);
  const std::size_t n = p.count(kEntryFixedBytes, "entries");
  if (n > kMaxEntries) {
    p.fail(std::to_string(n) + " entries, more than a database holds (" +
           std::to_string(kMaxEntries) + ")");
  }
  // Entries join the database once the state after them (their odometers,
  // version 3) has been read.
  std::vector<DatabaseEntry> entries;
  std::vector<GroupVector> raw_groups(n);
  entries.reserve(n);
  try {
    for (std::size_t i = 0; i < n; ++i) {
      entries.push_back(readEntry(&p, i, static_cast<ScoringType>(stored_scoring), *vocabulary,
                                  disk, &raw_groups[i]));
    }
    StoredChain chain;
    readPreviousScoresAndChain(&p, n, state, &chain);
    if (version >= 2) readNormalisers(&p, state);
    if (version >= 3) readCountersAndOdometers(&p, &entries, state, &chain);
    if (version >= 4) readHypotheses(&p, n, &chain);
    if (version >= 5) readScaleFactors(&p, &entries);
    if (version >= 6) readPlaceLinks(&p, n, state);
    if (version >= 7) readOdometryPositions(&p, &entries, state);
    if (version >= 8) readSearchable(&p, &entries);
    if (version >= 9) {
      std::vector<Mission> missions;
      readMissions(&p, &entries, state, &missions);
      db->restoreMissions(missions);
    }
    if (version >= 10) readHeadings(&p, &entries);
    for (std::size_t i = 0; i < n; ++i) {
      db->add(std::move(entries[i]), db->addToGroupTable(std::move(raw_groups[i])));
    }
    restoreChain(&p, *db, &chain, state);
  } catch (const std::invalid_argument& e) {
    // Content the database itself rejects (word ids out of range,
    // non-increasing stamps, invalid weights): still a format problem.
    p.fail(std::string("invalid content: ") + e.what());
  }
  if (p.left() != 0) p.fail("unexpected bytes after the detector state");
  return db;
}

}  // namespace

std::unique_ptr<Database> loadDetectorFile(const std::string& path,
                                           std::shared_ptr<const Vocabulary> vocabulary,
                                           ScoringType scoring, int direct_index_level,
                                           int fan_bins, DetectorState* state,
                                           ScoringType* stored_scoring_out) {
  DiskDescriptors disk;
  disk.file =
      std::make_shared<DescriptorFile>(BoundedFile(path, FileKind::kDatabase, "database file"),
                                       kFeatureBytes, kFeatureDescriptorOffset);
  const BoundedFile& file = disk.file->file();
  std::uint64_t payload = 0;
  const std::uint32_t version = checkFileHeader(file, *vocabulary, &payload);
  Reader p(file, kHeaderBytes, payload);
  return decodePayload(p, version, std::move(vocabulary), scoring, direct_index_level, fan_bins,
                       state, stored_scoring_out, &disk);
}

std::unique_ptr<Database> decodeDetectorFile(const std::string& bytes, const std::string& path,
                                             std::shared_ptr<const Vocabulary> vocabulary,
                                             ScoringType scoring, int direct_index_level,
                                             int fan_bins, DetectorState* state,
                                             ScoringType* stored_scoring_out) {
  std::uint64_t payload = 0;
  const std::uint32_t version =
      checkHeader(path, bytes.data(), bytes.size(), *vocabulary, &payload);
  Reader p(path, bytes.data() + kHeaderBytes, static_cast<std::size_t>(payload));
  return decodePayload(p, version, std::move(vocabulary), scoring, direct_index_level, fan_bins,
                       state, stored_scoring_out, nullptr);
}

namespace detector_file {

void Reader::refill(std::size_t n) {
  const std::size_t kept = static_cast<std::size_t>(end_ - p_);
  const std::size_t fill =
      static_cast<std::size_t>(std::min<std::uint64_t>(std::max(n, window_bytes_) - kept, unread_));
  if (window_.size() < kept + fill) {
    std::vector<char> larger(kept + fill);
    if (kept > 0) std::memcpy(larger.data(), p_, kept);
    window_.swap(larger);
  } else if (kept > 0) {
    std::memmove(window_.data(), p_, kept);
  }
  file_->readAt(window_.data() + kept, fill, next_);
  next_ += fill;
  unread_ -= fill;
  p_ = window_.data();
  end_ = p_ + kept + fill;
}

}  // namespace detector_file

}  // namespace bowg
