// DBoW3's binary vocabulary (Vocabulary::toStream / fromStream), read and
// written field by field, little-endian, no padding:
//   u64 magic 88877711233, u8 compressed, u32 nnodes (root included),
//   then (uncompressed) i32 k, L, scoring, weighting,
//   nnodes-1 records {u32 id, u32 parent, f64 weight,
//                     i32 cols, i32 rows, i32 cv type, cols*elemSize bytes},
//   u32 nwords, nwords records {u32 wordId, u32 nodeId}.
// Compressed files use QuickLZ chunks, which we do not ship: refused with a
// message that says how to re-save them.
#include "bowg/core/atomic_file.h"
#include "bowg/core/errors.h"
#include "vocabulary/formats/vocabulary_io_internal.h"

namespace bowg {
namespace vocabulary_io {

namespace {
// magic, compressed flag, node count, k, L, scoring, weighting.
const std::size_t kHeaderSize = 8 + 1 + 4 + 16;
// A node record with the only descriptor we read (1x32 CV_8U).
const std::uint64_t kRecord = 4 + 4 + 8 + 12 + 32;
const std::uint64_t kWordRecord = 8;
}  // namespace

namespace {

struct Header {
  std::uint32_t nnodes = 0;
  std::int32_t k = 0, L = 0, scoring = 0, weighting = 0;
};

// The header, checked against the file size before the body is read: the
// body is read only when the node count fits the bytes that follow.
Header readHeader(BoundedFile* file) {
  const std::string& path = file->path();
  // Magic, flag and node count decide whether the rest is worth a look.
  char bytes[kHeaderSize];
  const std::size_t kFlagsEnd = 13;
  if (file->size() < kFlagsEnd) {
    fail(path, "truncated: " + std::to_string(file->size()) + " bytes, shorter than the header");
  }
  file->readExactly(bytes, kFlagsEnd);
  ByteReader r(path, bytes, kHeaderSize);
  if (r.u64("magic") != kDbow3Magic) fail(path, "not a DBoW3 binary vocabulary (bad magic)");
  const std::uint8_t compressed = r.u8("compressed flag");
  if (compressed > 1) fail(path, "invalid compressed flag " + std::to_string(compressed));
  if (compressed == 1) {
    fail(path,
         "QuickLZ-compressed DBoW3 vocabularies are not supported; re-save it uncompressed "
         "with DBoW3 (Vocabulary::save(file, false)) or as YAML");
  }
  Header h;
  h.nnodes = r.u32("node count");
  if (file->size() < kHeaderSize) {
    fail(path, "truncated: " + std::to_string(file->size()) + " bytes, shorter than the " +
                   std::to_string(kHeaderSize) + "-byte header");
  }
  file->readExactly(bytes + kFlagsEnd, kHeaderSize - kFlagsEnd);
  h.k = r.i32("k");
  h.L = r.i32("L");
  h.scoring = r.i32("scoring");
  h.weighting = r.i32("weighting");
  checkHeader(path, h.k, h.L, h.scoring, h.weighting);
  if (h.nnodes < 2) fail(path, "the vocabulary has no nodes");
  // Every record we accept holds a 32-byte descriptor; a word count and at
  // most one word per node follow: the body's size lies between bounds the
  // node count sets.
  const std::uint64_t body = file->size() - kHeaderSize;
  const std::uint64_t nodes = h.nnodes - 1;
  if (nodes > maxTreeNodes(h.k, h.L) || body < 4 + nodes * kRecord ||
      body > 4 + nodes * (kRecord + kWordRecord)) {
    fail(path, "node count " + std::to_string(h.nnodes) + " does not fit the file size (" +
                   std::to_string(file->size()) + " bytes) or a tree with k = " +
                   std::to_string(h.k) + ", L = " + std::to_string(h.L) +
                   " (truncated or corrupt)");
  }
  return h;
}

}  // namespace

Vocabulary loadDbow3Binary(const std::string& path) {
  BoundedFile file(path, FileKind::kVocabulary);
  const Header h = readHeader(&file);
  const std::uint32_t nnodes = h.nnodes;
  const std::string data = file.readRest();
  ByteReader r(path, data.data(), data.size());
  std::vector<ForeignNode> nodes(nnodes - 1);
  for (ForeignNode& f : nodes) {
    f.id = r.u32("node id");
    f.parent = r.u32("parent id");
    f.weight = r.f64("weight");
    const std::int32_t cols = r.i32("descriptor cols");
    const std::int32_t rows = r.i32("descriptor rows");
    const std::int32_t type = r.i32("descriptor type");
    if (cols != 32 || rows != 1 || type != 0 /* CV_8UC1 */) {
      fail(path, "node " + std::to_string(f.id) + ": descriptor is " + std::to_string(rows) + "x" +
                     std::to_string(cols) + " of OpenCV type " + std::to_string(type) +
                     ", expected a 1x32 CV_8U (256-bit binary) descriptor");
    }
    unsigned char bytes[32];
    r.bytes(bytes, 32, "descriptor");
    f.descriptor = descriptorFromBytes(bytes);
  }
  const std::uint32_t nwords = r.u32("word count");
  if (nwords > r.remaining() / 8)
    fail(path, "word count " + std::to_string(nwords) + " exceeds the file (truncated)");
  std::vector<ForeignWord> words(nwords);
  for (ForeignWord& w : words) {
    w.word = r.u32("word id");
    w.node = r.u32("word node id");
  }
  if (r.remaining() != 0)
    fail(path, std::to_string(r.remaining()) + " unexpected bytes after the words");
  return buildFromForeign(path, h.k, h.L, h.scoring, h.weighting, nodes, words);
}

void saveDbow3Binary(const Vocabulary& v, const std::string& path) {
  const auto& nodes = v.nodes();
  std::string out;
  out.reserve(13 + 16 + nodes.size() * kRecord + 4 + 8 * v.wordCount());
  putU(&out, kDbow3Magic, 8);
  putU(&out, 0, 1);  // not compressed
  putU(&out, nodes.size(), 4);
  putU(&out, static_cast<std::uint32_t>(v.branching()), 4);
  putU(&out, static_cast<std::uint32_t>(v.depth()), 4);
  putU(&out, static_cast<std::uint32_t>(v.scoring()), 4);
  putU(&out, static_cast<std::uint32_t>(v.weighting()), 4);
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    putU(&out, i, 4);
    putU(&out, nodes[i].parent, 4);
    putF64(&out, nodes[i].weight);
    putU(&out, 32, 4);  // cols
    putU(&out, 1, 4);   // rows
    putU(&out, 0, 4);   // CV_8UC1
    unsigned char bytes[32];
    descriptorToBytes(nodes[i].descriptor, bytes);
    out.append(reinterpret_cast<const char*>(bytes), 32);
  }
  putU(&out, v.wordCount(), 4);
  for (std::size_t w = 0; w < v.wordCount(); ++w) {
    putU(&out, w, 4);
    putU(&out, v.nodeOfWord(static_cast<WordId>(w)), 4);
  }
  writeFileAtomically(path, out);
}

}  // namespace vocabulary_io
}  // namespace bowg
