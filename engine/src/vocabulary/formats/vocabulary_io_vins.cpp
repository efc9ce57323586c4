// VINS-Mono / VINS-Fusion "brief_k10L6.bin" (VINSLoop::Vocabulary::serialize):
// raw little-endian structs, no magic, no padding:
//   i32 k, L, scoringType, weightingType, nNodes, nWords;
//   nNodes x {i32 nodeId, i32 parentId, f64 weight, u64 descriptor[4]}  (48 B)
//   nWords x {i32 nodeId, i32 wordId}                                    (8 B)
// The root is not stored. descriptor[] are the blocks of a 256-bit
// boost::dynamic_bitset, block 0 = bits 0..63: the same bit order as our
// Descriptor (see vocabulary_io.h), so blocks are copied as they are.
#include "bowg/core/atomic_file.h"
#include "bowg/core/errors.h"
#include "vocabulary/formats/vocabulary_io_internal.h"

namespace bowg {
namespace vocabulary_io {
namespace {
const std::size_t kHeaderSize = 24;
const std::uint64_t kNodeRecord = 48, kWordRecord = 8;
}  // namespace

Vocabulary loadVinsBinary(const std::string& path) {
  // The header and the file size first: a body is read only when the
  // header's counts account for every byte of the file.
  BoundedFile file(path, FileKind::kVocabulary);
  char header[kHeaderSize];
  if (file.size() < kHeaderSize) {
    fail(path, "truncated: " + std::to_string(file.size()) + " bytes, shorter than the " +
                   std::to_string(kHeaderSize) + "-byte header");
  }
  file.readExactly(header, kHeaderSize);
  ByteReader h(path, header, kHeaderSize);
  const std::int32_t k = h.i32("k");
  const std::int32_t L = h.i32("L");
  const std::int32_t scoring = h.i32("scoringType");
  const std::int32_t weighting = h.i32("weightingType");
  const std::int32_t n_nodes = h.i32("nNodes");
  const std::int32_t n_words = h.i32("nWords");
  checkHeader(path, k, L, scoring, weighting);
  if (n_nodes < 1 || n_words < 0 || static_cast<std::uint64_t>(n_nodes) > maxTreeNodes(k, L)) {
    fail(path, "invalid counts nNodes = " + std::to_string(n_nodes) +
                   ", nWords = " + std::to_string(n_words) + " for k = " + std::to_string(k) +
                   ", L = " + std::to_string(L));
  }
  const std::uint64_t expected = kHeaderSize + kNodeRecord * static_cast<std::uint64_t>(n_nodes) +
                                 kWordRecord * static_cast<std::uint64_t>(n_words);
  if (expected != file.size()) {
    fail(path, "size " + std::to_string(file.size()) + " bytes does not match the header (" +
                   std::to_string(n_nodes) + " nodes, " + std::to_string(n_words) + " words need " +
                   std::to_string(expected) + "): truncated, corrupt or not a VINS vocabulary");
  }
  const std::string data = file.readRest();
  ByteReader r(path, data.data(), data.size());
  std::vector<ForeignNode> nodes(static_cast<std::size_t>(n_nodes));
  for (ForeignNode& f : nodes) {
    f.id = r.i32("nodeId");
    f.parent = r.i32("parentId");
    f.weight = r.f64("weight");
    for (auto& b : f.descriptor.bits) b = r.u64("descriptor");
  }
  std::vector<ForeignWord> words(static_cast<std::size_t>(n_words));
  for (ForeignWord& w : words) {
    w.node = r.i32("word nodeId");
    w.word = r.i32("wordId");
  }
  return buildFromForeign(path, k, L, scoring, weighting, nodes, words);
}

void saveVinsBinary(const Vocabulary& v, const std::string& path) {
  const auto& nodes = v.nodes();
  std::string out;
  out.reserve(24 + 48 * nodes.size() + 8 * v.wordCount());
  putU(&out, static_cast<std::uint32_t>(v.branching()), 4);
  putU(&out, static_cast<std::uint32_t>(v.depth()), 4);
  putU(&out, static_cast<std::uint32_t>(v.scoring()), 4);
  putU(&out, static_cast<std::uint32_t>(v.weighting()), 4);
  putU(&out, nodes.size() - 1, 4);
  putU(&out, v.wordCount(), 4);
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    putU(&out, i, 4);
    putU(&out, nodes[i].parent, 4);
    putF64(&out, nodes[i].weight);
    for (std::uint64_t b : nodes[i].descriptor.bits) putU(&out, b, 8);
  }
  for (std::size_t w = 0; w < v.wordCount(); ++w) {
    putU(&out, v.nodeOfWord(static_cast<WordId>(w)), 4);
    putU(&out, w, 4);
  }
  writeFileAtomically(path, out);
}

}  // namespace vocabulary_io
}  // namespace bowg
