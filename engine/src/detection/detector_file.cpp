// Persistence of the database and the detector state (format in database.h).
// Every count read from the file is checked against the bytes left before
// anything is allocated, so a corrupt count cannot trigger a huge allocation;
// the checksum is verified before any content is interpreted.
#include <cmath>
#include <limits>
#include <cstring>
#include <fstream>
#include <sstream>

#include "bowg/core/atomic_file.h"
#include "bowg/core/checksum.h"
#include "bowg/core/errors.h"
#include "bowg/detection/detector_file.h"
#include "bowg/vocabulary/vocabulary.h"

namespace bowg {
namespace {

const char kMagic[8] = {'B', 'O', 'W', 'G', 'D', 'B', 0, 0};
// Version 2 appends the normaliser history; version 3 then the two
// missed-query counters (previous scores, temporal chain) and the entries'
// odometers (u32 count = entries, f64 each, NaN = unknown). Older files still
// load, with an empty history, zero counters and unknown odometers. Version 4
// appends the temporal verification's other hypotheses (u32 count, then an
// island and an i32 chain length each); older files load with none.
const std::uint32_t kVersion = 4;
const std::uint32_t kOldestVersion = 1;
// magic + version + fingerprint + payload size | ... | checksum
const std::size_t kHeaderBytes = 8 + 4 + 8 + 8;
const std::size_t kTrailerBytes = 8;
// Fixed bytes of one entry / one feature in the payload.
const std::size_t kEntryFixedBytes = 8 * 3 + 1 + 8 * 4 + 4 + 4 + 4;
const std::size_t kFeatureBytes = 6 * 4 + 32 + 4;
const std::size_t kPairBytes = 4 + 8;
const std::size_t kNormaliserBytes = 3 * 8;
const std::size_t kIslandBytes = 4 + 4 + 8 + 4 + 8 + 4;

class Writer {
 public:
  void u8(std::uint8_t v) { out_.push_back(static_cast<char>(v)); }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out_.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
  }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) out_.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
  }
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void f32(float v) {
    std::uint32_t b;
    std::memcpy(&b, &v, 4);
    u32(b);
  }
  void f64(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, 8);
    u64(b);
  }
  void bytes(const char* p, std::size_t n) { out_.append(p, n); }
  void pairs(const std::vector<std::pair<WordId, double>>& v) {
    u32(static_cast<std::uint32_t>(v.size()));
    for (const auto& p : v) {
      u32(p.first);
      f64(p.second);
    }
  }
  std::string& str() { return out_; }

 private:
  std::string out_;
};

class Reader {
 public:
  Reader(const std::string& path, const char* data, std::size_t size)
      : path_(path), p_(data), end_(data + size) {}
  std::size_t left() const { return static_cast<std::size_t>(end_ - p_); }
  void need(std::size_t n, const char* what) const {
    if (n > left()) fail(std::string("truncated while reading ") + what);
  }
  [[noreturn]] void fail(const std::string& why) const {
    throw FormatError("database file '" + path_ + "': " + why);
  }
  std::uint8_t u8(const char* what) {
    need(1, what);
    return static_cast<std::uint8_t>(*p_++);
  }
  std::uint32_t u32(const char* what) { return littleEndian<std::uint32_t>(what); }
  std::uint64_t u64(const char* what) { return littleEndian<std::uint64_t>(what); }
  // The file is little-endian whatever the host: assemble byte by byte.
  template <typename T>
  T littleEndian(const char* what) {
    need(sizeof(T), what);
    T v = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i)
      v |= static_cast<T>(static_cast<unsigned char>(p_[i])) << (8 * i);
    p_ += sizeof(T);
    return v;
  }
  std::int32_t i32(const char* what) { return static_cast<std::int32_t>(u32(what)); }
  float f32(const char* what) {
    const std::uint32_t b = u32(what);
    float v;
    std::memcpy(&v, &b, 4);
    return v;
  }
  double f64(const char* what) {
    const std::uint64_t b = u64(what);
    double v;
    std::memcpy(&v, &b, 8);
    return v;
  }
  /// A count of items of `item_bytes` each that must fit in the bytes left.
  std::size_t count(std::size_t item_bytes, const char* what) {
    const std::uint64_t n = u32(what);
    if (item_bytes > 0 && n > left() / item_bytes) {
      fail(std::string("count of ") + what + " (" + std::to_string(n) +
           ") exceeds the file length");
    }
    return static_cast<std::size_t>(n);
  }
  std::vector<std::pair<WordId, double>> pairs(const char* what) {
    const std::size_t n = count(kPairBytes, what);
    std::vector<std::pair<WordId, double>> v;
    v.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      const WordId id = u32(what);
      const double w = f64(what);
      if (!std::isfinite(w)) fail(std::string("non-finite weight in ") + what);
      if (!v.empty() && id <= v.back().first) fail(std::string(what) + " not sorted by id");
      v.emplace_back(id, w);
    }
    return v;
  }

 private:
  std::string path_;
  const char* p_;
  const char* end_;
};

void writeIsland(Writer* w, const Island& i) {
  w->u32(i.first);
  w->u32(i.last);
  w->f64(i.score);
  w->u32(i.best_entry);
  w->f64(i.best_score);
  w->i32(i.size);
}

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

std::string readWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open database file '" + path + "' for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw IoError("error while reading database file '" + path + "'");
  return ss.str();
}

}  // namespace

void saveDetectorFile(const std::string& path, const Database& database,
                      const DetectorState& state) {
  Writer w;
  w.bytes(kMagic, 8);
  w.u32(kVersion);
  w.u64(database.vocabulary().fingerprint());
  w.u64(0);  // payload size, patched below
  const std::size_t payload_start = w.str().size();
  w.u32(static_cast<std::uint32_t>(database.scoring()));

  w.u32(static_cast<std::uint32_t>(database.size()));
  for (const DatabaseEntry& e : database.entries()) {
    w.f64(e.stamp);
    w.f64(e.centre_x);
    w.f64(e.centre_y);
    w.u8(e.intrinsics.valid ? 1 : 0);
    w.f64(e.intrinsics.fx);
    w.f64(e.intrinsics.fy);
    w.f64(e.intrinsics.cx);
    w.f64(e.intrinsics.cy);
    w.u32(static_cast<std::uint32_t>(e.keypoints.size()));
    for (std::size_t i = 0; i < e.keypoints.size(); ++i) {
      const Keypoint& k = e.keypoints[i];
      w.f32(k.x);
      w.f32(k.y);
      w.f32(k.size);
      w.f32(k.angle);
      w.f32(k.response);
      w.i32(k.octave);
      for (std::uint64_t b : e.descriptors[i].bits) w.u64(b);
      w.u32(e.words[i]);
    }
    w.pairs(e.bow);
    w.pairs(e.raw_groups);
  }
  w.pairs(state.previous_etas);
  writeIsland(&w, state.consistency.lastIsland());
  w.i32(state.consistency.chainLength());
  const std::vector<Normalisers> normalisers = state.normalisers.values();
  w.u32(static_cast<std::uint32_t>(normalisers.size()));
  for (const Normalisers& v : normalisers) {
    w.f64(v.word);
    w.f64(v.group);
    w.f64(v.distribution);
  }
  w.i32(state.missed_queries);
  w.i32(state.consistency.missedQueries());
  w.u32(static_cast<std::uint32_t>(database.size()));
  for (const DatabaseEntry& e : database.entries()) w.f64(e.odometer);
  w.f64(state.previous_odometer);
  w.f64(state.consistency.lastQueryOdometer());
  const std::vector<IslandHypothesis>& others = state.consistency.otherHypotheses();
  w.u32(static_cast<std::uint32_t>(others.size()));
  for (const IslandHypothesis& h : others) {
    writeIsland(&w, h.island);
    w.i32(h.chain_length);
  }

  std::string& bytes = w.str();
  const std::uint64_t payload = bytes.size() - payload_start;
  for (int i = 0; i < 8; ++i) {
    bytes[payload_start - 8 + i] = static_cast<char>((payload >> (8 * i)) & 0xff);
  }
  w.u64(checksum64(bytes.data(), bytes.size()));
  writeFileAtomically(path, bytes);
}

std::unique_ptr<Database> loadDetectorFile(const std::string& path,
                                           std::shared_ptr<const Vocabulary> vocabulary,
                                           ScoringType scoring, int direct_index_level,
                                           int fan_bins, DetectorState* state) {
  const std::string bytes = readWholeFile(path);
  Reader header(path, bytes.data(), bytes.size());
  if (bytes.size() < kHeaderBytes + kTrailerBytes) {
    header.fail("file too short (" + std::to_string(bytes.size()) + " bytes) to be a database");
  }
  if (std::memcmp(bytes.data(), kMagic, 8) != 0) header.fail("not a BoWG database (bad magic)");
  Reader r(path, bytes.data() + 8, bytes.size() - 8);
  const std::uint32_t version = r.u32("version");
  if (version < kOldestVersion || version > kVersion) {
    r.fail("unsupported version " + std::to_string(version) + " (expected " +
           std::to_string(kOldestVersion) + " to " + std::to_string(kVersion) + ")");
  }
  const std::uint64_t fingerprint = r.u64("vocabulary fingerprint");
  const std::uint64_t payload = r.u64("payload size");
  if (payload != bytes.size() - kHeaderBytes - kTrailerBytes) {
    r.fail("payload size " + std::to_string(payload) + " does not match the file length " +
           std::to_string(bytes.size()) + " (truncated or extended)");
  }
  Reader trailer(path, bytes.data() + bytes.size() - kTrailerBytes, kTrailerBytes);
  const std::uint64_t stored_sum = trailer.u64("checksum");
  if (checksum64(bytes.data(), bytes.size() - kTrailerBytes) != stored_sum) {
    r.fail("checksum mismatch (the file is corrupt)");
  }
  if (fingerprint != vocabulary->fingerprint()) {
    r.fail(
        "it was built with another vocabulary (fingerprint mismatch): load the vocabulary "
        "the database was created with");
  }

  Reader p(path, bytes.data() + kHeaderBytes, static_cast<std::size_t>(payload));
  std::unique_ptr<Database> db(new Database(vocabulary, scoring, direct_index_level, fan_bins));
  const std::uint32_t stored_scoring = p.u32("scoring type");
  if (stored_scoring > static_cast<std::uint32_t>(ScoringType::kDotProduct)) {
    p.fail("unknown scoring type " + std::to_string(stored_scoring));
  }
  // Vectors stored for the same scoring type are used bit for bit.
  const bool bow_normalised = static_cast<ScoringType>(stored_scoring) == scoring;
  const std::size_t n = p.count(kEntryFixedBytes, "entries");
  // Entries join the database once the state after them (their odometers,
  // version 3) has been read.
  std::vector<DatabaseEntry> entries;
  entries.reserve(n);
  try {
    for (std::size_t i = 0; i < n; ++i) {
      DatabaseEntry e;
      e.stamp = p.f64("entry stamp");
      e.centre_x = p.f64("entry centre");
      e.centre_y = p.f64("entry centre");
      e.intrinsics.valid = p.u8("intrinsics") != 0;
      e.intrinsics.fx = p.f64("intrinsics");
      e.intrinsics.fy = p.f64("intrinsics");
      e.intrinsics.cx = p.f64("intrinsics");
      e.intrinsics.cy = p.f64("intrinsics");
      const std::string entry = "entry " + std::to_string(i);
      if (!std::isfinite(e.stamp) || !std::isfinite(e.centre_x) || !std::isfinite(e.centre_y)) {
        p.fail(entry + " has a non-finite stamp or centre");
      }
      if (e.intrinsics.valid &&
          !(e.intrinsics.fx > 0.0 && e.intrinsics.fy > 0.0 && std::isfinite(e.intrinsics.fx) &&
            std::isfinite(e.intrinsics.fy) && std::isfinite(e.intrinsics.cx) &&
            std::isfinite(e.intrinsics.cy))) {
        p.fail(entry + " has invalid intrinsics (fx, fy must be finite > 0, cx, cy finite)");
      }
      const std::size_t nf = p.count(kFeatureBytes, "features");
      e.keypoints.resize(nf);
      e.descriptors.resize(nf);
      e.words.resize(nf);
      for (std::size_t f = 0; f < nf; ++f) {
        Keypoint& k = e.keypoints[f];
        k.x = p.f32("keypoint");
        k.y = p.f32("keypoint");
        k.size = p.f32("keypoint");
        k.angle = p.f32("keypoint");
        k.response = p.f32("keypoint");
        k.octave = p.i32("keypoint");
        if (!std::isfinite(k.x) || !std::isfinite(k.y) || !std::isfinite(k.angle) ||
            !std::isfinite(k.response) || !(k.size >= 0.0f && std::isfinite(k.size))) {
          p.fail(entry + " keypoint " + std::to_string(f) +
                 " has a non-finite coordinate, angle or response, or an invalid size");
        }
        for (auto& b : e.descriptors[f].bits) b = p.u64("descriptor");
        e.words[f] = p.u32("word");
      }
      e.bow = p.pairs("BoW vector");
      e.raw_groups = p.pairs("word groups");
      // Stored weights are > 0 (words of weight 0 are never stored) and, for
      // every scoring type but the dot product, normalised to at most 1.
      const bool normalised =
          static_cast<ScoringType>(stored_scoring) != ScoringType::kDotProduct;
      for (const auto& b : e.bow) {
        if (!(b.second > 0.0) || (normalised && b.second > 1.0 + 1e-9)) {
          p.fail(entry + " has a BoW weight " + std::to_string(b.second) + " outside (0, " +
                 (normalised ? "1]" : "inf)"));
        }
      }
      for (const auto& g : e.raw_groups) {
        if (!(g.second > 0.0)) p.fail(entry + " has a word-group weight <= 0");
      }
      entries.push_back(std::move(e));
    }
    state->previous_etas = p.pairs("previous scores");
    if (!state->previous_etas.empty() && state->previous_etas.back().first >= n) {
      p.fail("previous scores refer to an entry beyond the database");
    }
    for (const auto& e : state->previous_etas) {
      if (e.second < 0.0) p.fail("a previous score is negative");
    }
    Island last = readIsland(&p);
    const int chain = p.i32("chain length");
    // A chain counts queries, one per entry: it cannot be longer than the
    // database (a forged one would pass the temporal check at once).
    if (chain < 0 || static_cast<std::size_t>(chain) > n) {
      p.fail("temporal-consistency chain length " + std::to_string(chain) +
             " outside 0.." + std::to_string(n) + " (the number of entries)");
    }
    if (version >= 2) {
      const std::size_t nn = p.count(kNormaliserBytes, "normalisers");
      std::vector<Normalisers> normalisers(nn);
      for (Normalisers& v : normalisers) {
        v.word = p.f64("normaliser");
        v.group = p.f64("normaliser");
        v.distribution = p.f64("normaliser");
        if (!(v.word >= 0.0) || !(v.group >= 0.0) || !(v.distribution >= 0.0) ||
            !std::isfinite(v.word + v.group + v.distribution)) {
          p.fail("a stored normaliser is negative or not finite");
        }
      }
      state->normalisers.restore(normalisers);
    }
    int chain_missed = 0;
    double last_query_m = std::numeric_limits<double>::quiet_NaN();
    if (version >= 3) {
      state->missed_queries = p.i32("missed queries");
      chain_missed = p.i32("missed queries");
      if (state->missed_queries < 0 || chain_missed < 0 ||
          static_cast<std::size_t>(state->missed_queries) > n ||
          static_cast<std::size_t>(chain_missed) > n) {
        p.fail("missed-query count outside 0.." + std::to_string(n));
      }
      if (state->missed_queries > 0 && state->previous_etas.empty()) {
        p.fail("missed queries counted without previous scores");
      }
      if (chain_missed > 0 && chain == 0) p.fail("missed queries counted without a temporal chain");
      if (p.count(8, "odometers") != n) p.fail("odometer count differs from the entry count");
      double previous = -1.0;
      for (std::size_t i = 0; i < n; ++i) {
        const double o = p.f64("odometer");
        entries[i].odometer = o;
        if (std::isnan(o)) continue;
        if (!std::isfinite(o) || o < 0.0 || o < previous) {
          p.fail("entry " + std::to_string(i) + " has a negative, non-finite or decreasing odometer");
        }
        previous = o;
      }
      state->previous_odometer = p.f64("odometer");
      last_query_m = p.f64("odometer");
      for (double o : {state->previous_odometer, last_query_m}) {
        if (!std::isnan(o) && !(std::isfinite(o) && o >= 0.0)) p.fail("a stored query odometer is invalid");
      }
    }
    std::vector<IslandHypothesis> others;
    if (version >= 4) {
      const std::size_t no = p.count(kIslandBytes + 4, "hypotheses");
      if (no > 0 && chain == 0) p.fail("temporal hypotheses stored without a temporal chain");
      others.resize(no);
      for (IslandHypothesis& h : others) {
        h.island = readIsland(&p);
        h.chain_length = p.i32("chain length");
        if (h.chain_length < 1 || static_cast<std::size_t>(h.chain_length) > n) {
          p.fail("a temporal hypothesis has a chain length outside 1.." + std::to_string(n));
        }
      }
    }
    for (DatabaseEntry& e : entries) {
      db->addToGroupTable(e.raw_groups);
      db->add(std::move(e), bow_normalised);
    }
    const auto place = [&](Island* i) {
      if (i->first > i->last || i->last >= n || i->best_entry < i->first ||
          i->best_entry > i->last) {
        p.fail("a temporal island lies outside the database");
      }
      i->first_m = db->entry(i->first).odometer;
      i->last_m = db->entry(i->last).odometer;
    };
    if (chain > 0) place(&last);
    for (IslandHypothesis& h : others) place(&h.island);
    state->consistency.restore(last, chain, chain_missed, last_query_m, std::move(others));
  } catch (const std::invalid_argument& e) {
    // Content the database itself rejects (word ids out of range,
    // non-increasing stamps, invalid weights): still a format problem.
    p.fail(std::string("invalid content: ") + e.what());
  }
  if (p.left() != 0) p.fail("unexpected bytes after the detector state");
  return db;
}

}  // namespace bowg
