// The detector file's binary layout (detector_file.h) and the little-endian
// writer and bounds-checked reader it is written and read with. Internal to
// the detection stage.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "bowg/core/atomic_file.h"
#include "bowg/core/bounded_file.h"
#include "bowg/core/checksum.h"
#include "bowg/core/errors.h"
#include "bowg/core/types.h"
#include "bowg/database/database.h"
#include "bowg/database/missions.h"
#include "bowg/detection/detector_state.h"
#include "bowg/detection/islands.h"
#include "core/little_endian.h"

namespace bowg {
namespace detector_file {

constexpr char kMagic[8] = {'B', 'O', 'W', 'G', 'D', 'B', 0, 0};
// Version 2 appends the normaliser history; version 3 then the two
// missed-query counters (previous scores, temporal chain) and the entries'
// odometers (u32 count = entries, f64 each, NaN = unknown). Older files still
// load, with an empty history, zero counters and unknown odometers. Version 4
// appends the temporal verification's other hypotheses (u32 count, then an
// island and an i32 chain length each); older files load with none. Version
// 5 appends each entry's pyramid scale factor (u32 count = entries, f32 each,
// 0 = none: PackedPoints), with which the positions are packed again as they
// were; older files load with every position kept as read (same values, more
// memory for multi-scale keypoints). Version 6 appends the place links
// (u32 count = entries, then each entry's u32 parent in PlaceLinks, never a
// larger id); older files load with none. Version 7 appends the odometry
// run new entries belong to (u32), then each entry's run and odometry
// position (u32 count = entries, then u32 run and f64 x, y, z each, NaN =
// unknown); older files load with unknown positions. Version 8 appends
// whether each entry is in the inverse index (u32 count = entries, then u8
// 1 = searchable, 0 = not: DatabaseEntry::searchable); older files load with
// every entry searchable. Version 9 appends the missions: the mission new
// entries belong to (u32), the missions (u32 count, then u32 id, u32 name
// length and the name's bytes each) and each entry's mission (u32 count =
// entries, u32 id each); older files load as the unnamed mission 0 holding
// every entry. Version 10 appends each entry's odometry heading (u32 count =
// entries, then f32 x, y, z each: a unit vector, or NaN = unknown); older
// files load with unknown headings, which the heading gate lets through. A
// keypoint's size, angle, response and
// octave are read and checked but not kept (the database keeps positions
// only); they are written as 0, -1, 0, 0.
constexpr std::uint32_t kVersion = 10;
constexpr std::uint32_t kOldestVersion = 1;
// magic + version + fingerprint + payload size | ... | checksum
constexpr std::size_t kHeaderBytes = 8 + 4 + 8 + 8;
constexpr std::size_t kTrailerBytes = 8;
// Fixed bytes of one entry / one feature in the payload.
constexpr std::size_t kEntryFixedBytes = 8 * 3 + 1 + 8 * 4 + 4 + 4 + 4;
constexpr std::size_t kFeatureBytes = 6 * 4 + 32 + 4;
// Where a feature record's descriptor starts: after its keypoint.
constexpr std::size_t kFeatureDescriptorOffset = 6 * 4;
constexpr std::size_t kPairBytes = 4 + 8;
constexpr std::size_t kNormaliserBytes = 3 * 8;
constexpr std::size_t kIslandBytes = 4 + 4 + 8 + 4 + 8 + 4;

// Checksum64 of the first `end` bytes of `file` (BoundedFile or
// AtomicFileStream: anything with readAt), read 4 MB at a time.
template <typename File>
std::uint64_t checksumOfFile(const File& file, std::uint64_t end) {
  Checksum64 sum;
  std::vector<char> chunk(std::size_t{4} << 20);
  for (std::uint64_t at = 0; at < end;) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(chunk.size(), end - at));
    file.readAt(chunk.data(), n, at);
    sum.update(chunk.data(), n);
    at += n;
  }
  return sum.value();
}

// Writes the file's little-endian fields into memory, or streams them: with
// a sink, flush() appends what was written since the last flush to it.
class Writer {
 public:
  Writer() = default;
  explicit Writer(AtomicFileStream* sink) : sink_(sink) {}
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
  void text(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    bytes(s.data(), s.size());
  }
  void pairs(const std::vector<std::pair<WordId, double>>& v) {
    u32(static_cast<std::uint32_t>(v.size()));
    for (const auto& p : v) {
      u32(p.first);
      f64(p.second);
    }
  }
  std::string& str() { return out_; }
  void flush() {
    if (sink_ == nullptr) return;
    sink_->write(out_.data(), out_.size());
    out_.clear();
  }

 private:
  std::string out_;
  AtomicFileStream* sink_ = nullptr;
};

// Reads the payload either from bytes in memory or streamed from an open
// file through a window of a few MB: a network's archive is tens of GB and
// is decoded without ever being held whole. need(n) makes the next n bytes
// contiguous at position(); offset() is the file offset of the next byte
// (streamed), or its index from `data` (in memory).
class Reader {
 public:
  Reader(const std::string& path, const char* data, std::size_t size)
      : path_(path), p_(data), end_(data + size), next_(size) {}
  /// The `size` bytes of `file` from `offset` (left open by the caller),
  /// read `window` bytes at a time (more when one need() asks for more).
  Reader(const BoundedFile& file, std::uint64_t offset, std::uint64_t size,
         std::size_t window = std::size_t{4} << 20)
      : path_(file.path()), file_(&file), next_(offset), unread_(size), window_bytes_(window) {}
  std::uint64_t left() const { return static_cast<std::uint64_t>(end_ - p_) + unread_; }
  const char* position() const { return p_; }
  std::uint64_t offset() const { return next_ - static_cast<std::uint64_t>(end_ - p_); }
  void skip(std::size_t n, const char* what) {
    need(n, what);
    p_ += n;
  }
  void need(std::size_t n, const char* what) {
    if (n > left()) fail(std::string("truncated while reading ") + what);
    if (n > static_cast<std::size_t>(end_ - p_)) refill(n);
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
    const T v = loadLittleEndian<T>(reinterpret_cast<const unsigned char*>(p_));
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
  std::string text(const char* what) {
    const std::size_t n = count(1, what);
    need(n, what);
    std::string s(p_, n);
    p_ += n;
    return s;
  }
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
  // Streamed: keeps the bytes not yet read, then reads at least `n` - those
  // (n <= left()) and up to the window's size after them.
  void refill(std::size_t n);

  std::string path_;
  const char* p_ = nullptr;
  const char* end_ = nullptr;
  const BoundedFile* file_ = nullptr;  ///< null: the bytes are all in memory
  std::uint64_t next_ = 0;             ///< file offset of the byte after the window
  std::uint64_t unread_ = 0;           ///< bytes of the range after the window
  std::size_t window_bytes_ = 0;
  std::vector<char> window_;
};

// Version 9's section (detector_file_missions.cpp).
void writeMissions(Writer* w, const Database& database, const DetectorState& state);
// Reads the missions into `missions` and each entry's mission; checks that
// the ids are unique, that every entry's mission and the state's are held
// and that no odometry run spans two missions.
void readMissions(Reader* p, std::vector<DatabaseEntry>* entries, DetectorState* state,
                  std::vector<Mission>* missions);

}  // namespace detector_file
}  // namespace bowg
