// Shared by the vocabulary file tests: output paths, whole-file reads and
// writes, every format with a file name, and a vocabulary whose tree is not
// the regular k^L one.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bowg/vocabulary/vocabulary_io.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace testing {

inline std::string outPath(const std::string& name) {
  return std::string(BOWG_TEST_OUTPUT_DIR) + "/vocio_" + name;
}

inline std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void writeAll(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

struct FormatCase {
  VocabularyFormat format;
  const char* file;
};
const FormatCase kCases[] = {
    {VocabularyFormat::kBowg, "v.bowgvoc"},
    {VocabularyFormat::kDbow2Yaml, "v_dbow2.yml"},
    {VocabularyFormat::kDbow2Yaml, "v_dbow2.yml.gz"},
    {VocabularyFormat::kDbow2BriefYaml, "v_brief.yml"},
    {VocabularyFormat::kDbow3Yaml, "v_dbow3.yml.gz"},
    {VocabularyFormat::kDbow3Binary, "v.dbow3"},
    {VocabularyFormat::kOrbSlamText, "v_ORBvoc.txt"},
    {VocabularyFormat::kVinsBinary, "v_brief.bin"},
};

// An unbalanced trained-like tree: k = 3, L = 3, with one shallow leaf.
inline Vocabulary unbalanced(WeightingType w = WeightingType::kIdf,
                             ScoringType s = ScoringType::kChiSquare) {
  const Vocabulary full = testing::makeSyntheticVocabulary(3, 3, 11, w, s);
  // Cut the subtree of node 1 (level 1): keep its first child only... simpler:
  // rebuild with node 2 turned into a leaf by dropping its children.
  std::vector<Vocabulary::Node> nodes;
  const auto& src = full.nodes();
  std::vector<NodeId> map(src.size(), Vocabulary::kNoWord);
  // Breadth-first copy skipping the descendants of node 2.
  std::vector<NodeId> queue{0};
  map[0] = 0;
  nodes.push_back(src[0]);
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const NodeId old = queue[head];
    const NodeId now = map[old];
    if (old == 2) {
      nodes[now].num_children = 0;
      nodes[now].first_child = 0;
      continue;
    }
    if (src[old].num_children == 0) continue;
    nodes[now].first_child = static_cast<std::uint32_t>(nodes.size());
    for (std::uint32_t c = src[old].first_child; c < src[old].first_child + src[old].num_children;
         ++c) {
      map[c] = static_cast<NodeId>(nodes.size());
      Vocabulary::Node child = src[c];
      child.parent = now;
      nodes.push_back(child);
      queue.push_back(c);
    }
  }
  WordId word = 0;
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    nodes[i].word = nodes[i].num_children == 0 ? word++ : Vocabulary::kNoWord;
    if (nodes[i].num_children == 0 && nodes[i].weight == 0.0) nodes[i].weight = 0.25 * i;
  }
  return Vocabulary(3, 3, w, s, std::move(nodes));
}

}  // namespace testing
}  // namespace bowg
