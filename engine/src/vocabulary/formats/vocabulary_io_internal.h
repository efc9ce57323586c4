// Shared helpers of the vocabulary loaders and writers (vocabulary_io_*.cpp).
// Not installed: private to the engine library.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "bowg/core/bounded_file.h"
#include "bowg/core/errors.h"
#include "bowg/vocabulary/vocabulary.h"

namespace bowg {
namespace vocabulary_io {

/// "<path>: <what>" as a FormatError.
[[noreturn]] void fail(const std::string& path, const std::string& what);

/// The file's bytes, refused (IoError naming the file and the reason)
/// unless it is a regular file within the vocabulary limit
/// (bounded_file.h, BOWG_MAX_VOCABULARY_MB).
std::string readVocabularyFile(const std::string& path);

/// Refuses (FormatError) text holding a NUL byte: no text vocabulary has
/// one, and a zero-filled or sparse file is refused at its first chunk
/// instead of after it has been read whole. `offset`: of `data` in the text.
void checkText(const std::string& path, const char* data, std::size_t size, std::uint64_t offset);

/// The rest of a text vocabulary after `text` (its first bytes), read in
/// chunks that checkText() vets as they come.
std::string readTextRest(BoundedFile* file, std::string text);

/// Plausibility of a foreign header: k in [2, 1000], L in [1, 100], known
/// scoring and weighting types. Checked before a loader reads the body,
/// since these values bound every later allocation.
void checkHeader(const std::string& path, std::int64_t k, std::int64_t L, std::int64_t scoring,
                 std::int64_t weighting);

/// The most non-root nodes a tree of branching k and depth L can have
/// (k + k^2 + ... + k^L), saturated at UINT64_MAX: a file's node count above
/// it is corrupt, whatever its size.
std::uint64_t maxTreeNodes(std::int64_t k, std::int64_t L);

/// A node as foreign formats list it: by id, with its parent's id (root = 0,
/// not listed).
struct ForeignNode {
  std::int64_t id = 0;
  std::int64_t parent = 0;
  double weight = 0.0;
  Descriptor descriptor;
};
struct ForeignWord {
  std::int64_t word = 0;
  std::int64_t node = 0;
};

/// Rebuilds a foreign tree into our layout. Node ids must be 1..N (dense, as
/// DBoW2 indexes its node array by id), each listed once; children keep the
/// order in which the file lists them. If the file's ids already satisfy
/// our layout (children consecutive and after their parent, as DBoW2's
/// training and our writers produce), they are kept, so that node ids of the
/// file are our node indices; otherwise nodes are renumbered breadth-first.
/// Word ids are kept. Throws FormatError "<path>: ..." on any inconsistency.
Vocabulary buildFromForeign(const std::string& path, std::int64_t k, std::int64_t L,
                            std::int64_t scoring, std::int64_t weighting,
                            const std::vector<ForeignNode>& nodes,
                            const std::vector<ForeignWord>& words);

/// Bounds-checked little-endian reader over a byte buffer.
class ByteReader {
 public:
  ByteReader(const std::string& path, const char* data, std::size_t size)
      : path_(path), data_(data), size_(size) {}

  std::size_t offset() const { return pos_; }
  std::size_t remaining() const { return size_ - pos_; }

  void need(std::size_t n, const char* what) const {
    if (n > size_ - pos_) {
      fail(path_, std::string("truncated: ") + what + " needs " + std::to_string(n) +
                      " bytes at offset " + std::to_string(pos_) + ", file has " +
                      std::to_string(size_));
    }
  }
  std::uint64_t u(int bytes, const char* what) {
    need(static_cast<std::size_t>(bytes), what);
    std::uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) {
      v = (v << 8) | static_cast<unsigned char>(data_[pos_ + static_cast<std::size_t>(i)]);
    }
    pos_ += static_cast<std::size_t>(bytes);
    return v;
  }
  std::uint32_t u32(const char* what) { return static_cast<std::uint32_t>(u(4, what)); }
  std::int32_t i32(const char* what) { return static_cast<std::int32_t>(u32(what)); }
  std::uint64_t u64(const char* what) { return u(8, what); }
  std::uint8_t u8(const char* what) { return static_cast<std::uint8_t>(u(1, what)); }
  double f64(const char* what) {
    const std::uint64_t bits = u64(what);
    double v;
    std::memcpy(&v, &bits, sizeof(v));
    return v;
  }
  void bytes(void* out, std::size_t n, const char* what) {
    need(n, what);
    std::memcpy(out, data_ + pos_, n);
    pos_ += n;
  }

 private:
  std::string path_;
  const char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

/// Little-endian appenders for writers.
inline void putU(std::string* out, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out->push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
inline void putF64(std::string* out, double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof(bits));
  putU(out, bits, 8);
}

/// Descriptor <-> 32 OpenCV bytes (byte j = bits 8j..8j+7, see types.h).
inline void descriptorToBytes(const Descriptor& d, unsigned char out[32]) {
  for (int j = 0; j < 32; ++j) out[j] = static_cast<unsigned char>(d.bits[j / 8] >> (8 * (j % 8)));
}
inline Descriptor descriptorFromBytes(const unsigned char in[32]) {
  Descriptor d;
  for (int j = 0; j < 32; ++j) d.bits[j / 8] |= static_cast<std::uint64_t>(in[j]) << (8 * (j % 8));
  return d;
}

// Per-format entry points (one file each).
Vocabulary loadBowg(const std::string& path);
void saveBowg(const Vocabulary& v, const std::string& path);
Vocabulary loadDbowYaml(const std::string& path);
enum class YamlFlavour { kDbow2Orb, kDbow2Brief, kDbow3 };
void saveDbowYaml(const Vocabulary& v, const std::string& path, YamlFlavour flavour);
Vocabulary loadDbow3Binary(const std::string& path);
void saveDbow3Binary(const Vocabulary& v, const std::string& path);
Vocabulary loadOrbSlamText(const std::string& path);
void saveOrbSlamText(const Vocabulary& v, const std::string& path);
Vocabulary loadVinsBinary(const std::string& path);
void saveVinsBinary(const Vocabulary& v, const std::string& path);

/// Magic numbers used for detection.
extern const char kBowgMagic[8];
const std::uint64_t kDbow3Magic = 88877711233ull;

}  // namespace vocabulary_io
}  // namespace bowg
