// Our binary vocabulary format ".bowgvoc", built to load with one read
// (fbow's lesson, see vocabulary.h). Layout, all little-endian:
//
//   offset  size  field
//        0     8  magic "BOWGVOC\0"
//        8     4  format version (1)
//       12     4  k
//       16     4  L
//       20     4  weighting (WeightingType, DBoW2 numbering)
//       24     4  scoring (ScoringType, DBoW2 numbering)
//       28     4  node record size (64)
//       32     8  node count N (root included)
//       40     8  word count W
//       48  64*N  node records, node i at 48 + 64 i:
//                   u32 parent, u32 first_child, u32 num_children, u32 level,
//                   u32 word (0xffffffff = none), u32 reserved (0),
//                   f64 weight, u64 descriptor blocks 0..3
//  48+64N     8  checksum64() of bytes [0, 48 + 64 N)
//
// The record is the in-memory Vocabulary::Node on little-endian hosts, so
// the node block is read straight into the node array.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <condition_variable>
#include <cstddef>
#include <cstring>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#include "bowg/core/atomic_file.h"
#include "bowg/core/checksum.h"
#include "bowg/core/errors.h"
#include "core/positional_io.h"
#include "vocabulary/formats/vocabulary_io_internal.h"
#include "vocabulary/vocabulary_records.h"

#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "vocabulary_io_bowg.cpp reads node records in place and needs a little-endian host"
#endif

namespace bowg {
namespace vocabulary_io {
namespace {

const std::uint32_t kVersion = 1;
const std::size_t kHeaderSize = 48;
const std::size_t kRecordSize = 64;
// Records read at a time (1 MB): hashed and checked while in the cache.
const std::size_t kChunkRecords = 16384;
using Node = Vocabulary::Node;
static_assert(sizeof(Node) == kRecordSize, "Node must match the 64-byte record");
static_assert(offsetof(Node, parent) == 0 && offsetof(Node, first_child) == 4 &&
                  offsetof(Node, num_children) == 8 && offsetof(Node, level) == 12 &&
                  offsetof(Node, word) == 16 && offsetof(Node, weight) == 24 &&
                  offsetof(Node, descriptor) == 32,
              "Node layout must match the record layout");

void readFully(int fd, void* out, std::size_t size, std::uint64_t offset, const std::string& path) {
  if (preadUpTo(fd, out, size, offset, "cannot read '" + path + "'") < size) {
    fail(path, "truncated while reading");
  }
}

// The block's two hashes (file checksum and fingerprint) on a helper thread,
// one chunk behind the reader: hashing 71 MB word by word is a serial
// multiply chain (~10 ms), which a second core takes off the load's
// critical path (the read, the copy into fresh pages and the tree checks).
// Two chunk buffers: the reader fills one while the other is hashed. Where
// no thread can be started, the reader hashes each chunk itself.
class ChunkHasher {
 public:
  ChunkHasher(Checksum64* sum, Checksum64* fingerprint, std::size_t chunk_records)
      : sum_(sum), fingerprint_(fingerprint) {
    for (auto& b : buffers_) b.resize(chunk_records);
    try {
      thread_ = std::thread([this] { run(); });
    } catch (const std::system_error&) {
      // Hashed inline by publish().
    }
  }
  ~ChunkHasher() { stop(); }
  ChunkHasher(const ChunkHasher&) = delete;
  ChunkHasher& operator=(const ChunkHasher&) = delete;

  /// The buffer chunk number `c` is read into, once the chunk that used it
  /// before (c - 2) has been hashed.
  std::vector<Node>& buffer(std::size_t c) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return hashed_ + 2 > c; });
    return buffers_[c % 2];
  }

  /// Chunk `c` (the next one) holds `records` records: hash it. The reader
  /// may go on reading the buffer (both sides only read it).
  void publish(std::size_t c, std::size_t records) {
    if (!thread_.joinable()) {
      updateBoth(sum_, fingerprint_, buffers_[c % 2].data(), records * sizeof(Node));
      hashed_ = c + 1;
      return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    records_[c % 2] = records;
    published_ = c + 1;
    changed_.notify_all();
  }

  /// Waits until every published chunk is hashed and ends the thread.
  void finish() { stop(); }

 private:
  void run() {
    for (std::size_t c = 0;; ++c) {
      std::size_t records;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        changed_.wait(lock, [&] { return published_ > c || stopping_; });
        if (published_ <= c) return;
        records = records_[c % 2];
      }
      updateBoth(sum_, fingerprint_, buffers_[c % 2].data(), records * sizeof(Node));
      std::lock_guard<std::mutex> lock(mutex_);
      hashed_ = c + 1;
      changed_.notify_all();
    }
  }

  void stop() {
    if (!thread_.joinable()) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;  // after the published chunks: run() drains them first
      changed_.notify_all();
    }
    thread_.join();
  }

  Checksum64* sum_;
  Checksum64* fingerprint_;
  std::vector<Node> buffers_[2];
  std::size_t records_[2] = {0, 0};
  std::mutex mutex_;
  std::condition_variable changed_;
  std::size_t published_ = 0, hashed_ = 0;
  bool stopping_ = false;
  std::thread thread_;
};

struct Header {
  char bytes[kHeaderSize];
  std::uint32_t k = 0, L = 0, weighting = 0, scoring = 0;
  std::uint64_t node_count = 0, word_count = 0;
};

// The header, checked on its own and against the file's length before any
// allocation.
Header readHeader(const BoundedFile& file) {
  const std::string& path = file.path();
  const std::uint64_t file_size = file.size();
  if (file_size < kHeaderSize + 8) {
    fail(path, "truncated: " + std::to_string(file_size) + " bytes, shorter than the header");
  }
  Header h;
  readFully(file.fd(), h.bytes, kHeaderSize, 0, path);
  if (std::memcmp(h.bytes, kBowgMagic, 8) != 0) fail(path, "not a .bowgvoc file (bad magic)");
  ByteReader r(path, h.bytes, kHeaderSize);
  r.u64("magic");
  const std::uint32_t version = r.u32("version");
  h.k = r.u32("k");
  h.L = r.u32("L");
  h.weighting = r.u32("weighting");
  h.scoring = r.u32("scoring");
  const std::uint32_t record_size = r.u32("record size");
  h.node_count = r.u64("node count");
  h.word_count = r.u64("word count");
  if (version != kVersion) {
    fail(path, "unsupported .bowgvoc version " + std::to_string(version) + " (this build reads " +
                   std::to_string(kVersion) + ")");
  }
  if (record_size != kRecordSize)
    fail(path, "node record size " + std::to_string(record_size) + " != 64");
  // The ranges every other format's loader enforces: they bound the counts.
  checkHeader(path, h.k, h.L, h.scoring, h.weighting);
  if (h.node_count < 2 || h.node_count > (file_size - kHeaderSize - 8) / kRecordSize ||
      kHeaderSize + h.node_count * kRecordSize + 8 != file_size) {
    fail(path, "node count " + std::to_string(h.node_count) + " does not match the file size " +
                   std::to_string(file_size) + " (truncated or corrupt)");
  }
  if (h.node_count - 1 > maxTreeNodes(h.k, h.L)) {
    fail(path, "node count " + std::to_string(h.node_count) + " is more than a tree with k = " +
                   std::to_string(h.k) + ", L = " + std::to_string(h.L) + " can have");
  }
  if (h.word_count >= h.node_count)
    fail(path, "word count " + std::to_string(h.word_count) + " >= node count");
  return h;
}

}  // namespace

Vocabulary loadBowg(const std::string& path) {
  const BoundedFile file(path, FileKind::kVocabulary);
  const Header h = readHeader(file);
  const char* header = h.bytes;
  const std::uint32_t k = h.k, L = h.L, weighting = h.weighting, scoring = h.scoring;
  const std::uint64_t node_count = h.node_count, word_count = h.word_count;

  // The block is the file checksum's tail and, with its reserved words zero,
  // the fingerprint's records: it is read in chunks that stay in the cache
  // while they are hashed for both (one pass), checked and appended.
  Checksum64 sum;
  sum.update(header, kHeaderSize);
  Checksum64 fingerprint = VocabularyRecords::fingerprintStart(
      static_cast<int>(k), static_cast<int>(L), static_cast<WeightingType>(weighting),
      static_cast<std::size_t>(node_count));
  const std::size_t count = static_cast<std::size_t>(node_count);
  Vocabulary::NodeArray nodes;
  nodes.reserve(count);
  std::size_t first_bad_reserved = count;
  // The tree checked chunk by chunk while the chunk is in the cache.
  TreeStreamCheck tree(static_cast<int>(k), static_cast<int>(L), count);
  {
    ChunkHasher hasher(&sum, &fingerprint, std::min<std::size_t>(count, kChunkRecords));
    for (std::size_t done = 0, c = 0; done < count; ++c) {
      std::vector<Node>& chunk = hasher.buffer(c);
      const std::size_t n = std::min(chunk.size(), count - done);
      readFully(file.fd(), chunk.data(), n * kRecordSize, kHeaderSize + done * kRecordSize, path);
      hasher.publish(c, n);
      for (std::size_t i = 0; i < n && first_bad_reserved == count; ++i) {
        // The reserved word sits in Node's padding; it must be zero in files.
        std::uint32_t reserved;
        std::memcpy(&reserved, reinterpret_cast<const char*>(&chunk[i]) + 20, 4);
        if (reserved != 0) first_bad_reserved = done + i;
      }
      nodes.insert(nodes.end(), chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(n));
      tree.consume(nodes, done, done + n);
      done += n;
    }
    hasher.finish();
  }
  unsigned char stored_bytes[8];
  readFully(file.fd(), stored_bytes, 8, kHeaderSize + count * kRecordSize, path);
  std::uint64_t stored = 0;
  for (int i = 7; i >= 0; --i) stored = (stored << 8) | stored_bytes[i];
  if (sum.value() != stored) fail(path, "checksum mismatch (the file is corrupt)");
  if (first_bad_reserved != count) {
    fail(path, "node " + std::to_string(first_bad_reserved) + ": reserved field is not zero");
  }
  try {
    Vocabulary v = VocabularyRecords::buildChecked(
        static_cast<int>(k), static_cast<int>(L), static_cast<WeightingType>(weighting),
        static_cast<ScoringType>(scoring), std::move(nodes), fingerprint.value(), &tree);
    if (v.wordCount() != word_count) {
      fail(path, "header says " + std::to_string(word_count) + " words, the tree has " +
                     std::to_string(v.wordCount()));
    }
    return v;
  } catch (const FormatError& e) {
    const std::string what = e.what();
    if (what.compare(0, path.size(), path) == 0) throw;
    fail(path, what);
  }
}

void saveBowg(const Vocabulary& v, const std::string& path) {
  const auto& nodes = v.nodes();
  std::string out;
  out.reserve(kHeaderSize + nodes.size() * kRecordSize + 8);
  out.append(kBowgMagic, 8);
  putU(&out, kVersion, 4);
  putU(&out, static_cast<std::uint32_t>(v.branching()), 4);
  putU(&out, static_cast<std::uint32_t>(v.depth()), 4);
  putU(&out, static_cast<std::uint32_t>(v.weighting()), 4);
  putU(&out, static_cast<std::uint32_t>(v.scoring()), 4);
  putU(&out, kRecordSize, 4);
  putU(&out, nodes.size(), 8);
  putU(&out, v.wordCount(), 8);
  for (const Node& n : nodes) {
    // Field by field: Node's padding bytes are indeterminate in memory.
    putU(&out, n.parent, 4);
    putU(&out, n.first_child, 4);
    putU(&out, n.num_children, 4);
    putU(&out, n.level, 4);
    putU(&out, n.word, 4);
    putU(&out, 0, 4);
    putF64(&out, n.weight);
    for (std::uint64_t b : n.descriptor.bits) putU(&out, b, 8);
  }
  putU(&out, checksum64(out.data(), out.size()), 8);
  writeFileAtomically(path, out);
}

}  // namespace vocabulary_io
}  // namespace bowg
