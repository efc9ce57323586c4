// Format names, detection and dispatch of the vocabulary files, and the
// helpers every foreign loader shares (vocabulary_io_internal.h).
#include "bowg/vocabulary/vocabulary_io.h"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "bowg/core/bounded_file.h"
#include "bowg/core/errors.h"
#include "vocabulary/formats/vocabulary_io_internal.h"

namespace bowg {

namespace vocabulary_io {

const char kBowgMagic[8] = {'B', 'O', 'W', 'G', 'V', 'O', 'C', '\0'};

void fail(const std::string& path, const std::string& what) {
  throw FormatError(path + ": " + what);
}

std::string readVocabularyFile(const std::string& path) {
  return readBoundedFile(path, FileKind::kVocabulary);
}

void checkText(const std::string& path, const char* data, std::size_t size, std::uint64_t offset) {
  const void* nul = std::memchr(data, '\0', size);
  if (nul != nullptr) {
    const std::uint64_t at =
        offset + static_cast<std::uint64_t>(static_cast<const char*>(nul) - data);
    fail(path, "a NUL byte at offset " + std::to_string(at) +
                   ": not text (a binary, zero-filled or sparse file)");
  }
}

std::string readTextRest(BoundedFile* file, std::string text) {
  checkText(file->path(), text.data(), text.size(), 0);
  std::vector<char> chunk(1 << 20);
  for (;;) {
    const std::size_t got = file->readSome(chunk.data(), chunk.size());
    if (got == 0) return text;
    checkText(file->path(), chunk.data(), got, text.size());
    text.append(chunk.data(), got);
  }
}

void checkHeader(const std::string& path, std::int64_t k, std::int64_t L, std::int64_t scoring,
                 std::int64_t weighting) {
  if (k < 2 || k > kMaxBranching) {
    fail(path, "branching factor k = " + std::to_string(k) + " out of range [2, " +
                   std::to_string(kMaxBranching) + "]");
  }
  if (L < 1 || L > kMaxDepth) {
    fail(path,
         "depth L = " + std::to_string(L) + " out of range [1, " + std::to_string(kMaxDepth) + "]");
  }
  if (scoring < 0 || scoring > 5) fail(path, "unknown scoring type " + std::to_string(scoring));
  if (weighting < 0 || weighting > 3)
    fail(path, "unknown weighting type " + std::to_string(weighting));
}

std::uint64_t maxTreeNodes(std::int64_t k, std::int64_t L) {
  const std::uint64_t kMax = UINT64_MAX;
  std::uint64_t level = 1, total = 0;
  for (std::int64_t l = 1; l <= L; ++l) {
    if (level > kMax / static_cast<std::uint64_t>(k)) return kMax;
    level *= static_cast<std::uint64_t>(k);
    if (total > kMax - level) return kMax;
    total += level;
  }
  return total;
}

namespace {

// Children lists in file order, as compressed rows (no per-node allocation):
// the children of file id p are children[row[p] .. row[p + 1]).
struct ChildRows {
  std::vector<std::uint32_t> count, row, children;
};

// The header first: its values also bound every later allocation.
void checkForeignHeader(const std::string& path, std::int64_t k, std::int64_t L,
                        std::int64_t scoring, std::int64_t weighting, std::size_t nodes) {
  checkHeader(path, k, L, scoring, weighting);
  if (nodes == 0) fail(path, "the vocabulary has no nodes");
  if (nodes + 1 >= Vocabulary::kNoWord) fail(path, "too many nodes");
}

// Position in `nodes` of every file id; ids must be exactly 1..N, parents
// valid ids other than the node's own.
std::vector<std::uint32_t> slotsById(const std::string& path,
                                     const std::vector<ForeignNode>& nodes) {
  const std::size_t n = nodes.size() + 1;  // + root
  std::vector<std::uint32_t> slot(n, Vocabulary::kNoWord);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const ForeignNode& f = nodes[i];
    if (f.id < 1 || f.id >= static_cast<std::int64_t>(n)) {
      fail(path,
           "node id " + std::to_string(f.id) + " out of range [1, " + std::to_string(n - 1) + "]");
    }
    if (slot[f.id] != Vocabulary::kNoWord)
      fail(path, "node id " + std::to_string(f.id) + " listed twice");
    if (f.parent < 0 || f.parent >= static_cast<std::int64_t>(n) || f.parent == f.id) {
      fail(path,
           "node " + std::to_string(f.id) + " has invalid parent " + std::to_string(f.parent));
    }
    slot[f.id] = static_cast<std::uint32_t>(i);
  }
  return slot;
}

ChildRows childRows(const std::vector<ForeignNode>& nodes) {
  const std::size_t n = nodes.size() + 1;
  ChildRows c;
  c.count.assign(n, 0);
  for (const ForeignNode& f : nodes) ++c.count[f.parent];
  c.row.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) c.row[i + 1] = c.row[i] + c.count[i];
  c.children.resize(nodes.size());
  std::vector<std::uint32_t> fill(c.row.begin(), c.row.end() - 1);
  for (const ForeignNode& f : nodes)
    c.children[fill[f.parent]++] = static_cast<std::uint32_t>(f.id);
  return c;
}

// The new index of every file id: the file's own ids when they already are
// our layout (children contiguous, after their parent), else breadth-first
// order from the root. Also the level of every node; nodes never reached
// hang off a cycle.
std::vector<std::uint32_t> newIndices(const std::string& path, std::int64_t L, const ChildRows& c,
                                      std::vector<std::uint32_t>* level) {
  const std::size_t n = c.count.size();
  const std::vector<std::uint32_t>& row = c.row;
  const std::vector<std::uint32_t>& children = c.children;
  bool identity = true;
  for (std::size_t p = 0; p < n && identity; ++p) {
    for (std::uint32_t i = row[p]; i < row[p + 1]; ++i) {
      if (children[i] != children[row[p]] + (i - row[p]) || children[row[p]] <= p) {
        identity = false;
        break;
      }
    }
  }
  std::vector<std::uint32_t> order;  // new index -> file id
  order.reserve(n);
  order.push_back(0);
  level->assign(n, 0);
  for (std::size_t head = 0; head < order.size(); ++head) {
    const std::uint32_t p = order[head];
    for (std::uint32_t i = row[p]; i < row[p + 1]; ++i) {
      (*level)[children[i]] = (*level)[p] + 1;
      order.push_back(children[i]);
      if ((*level)[children[i]] > static_cast<std::uint32_t>(L)) {
        fail(path,
             "node " + std::to_string(children[i]) + " is deeper than L = " + std::to_string(L));
      }
    }
  }
  if (order.size() != n) {
    fail(path, std::to_string(n - order.size()) + " nodes are not reachable from the root (cycle)");
  }
  std::vector<std::uint32_t> new_index(n);
  if (identity) {
    for (std::size_t i = 0; i < n; ++i) new_index[i] = static_cast<std::uint32_t>(i);
  } else {
    for (std::size_t i = 0; i < n; ++i) new_index[order[i]] = static_cast<std::uint32_t>(i);
  }
  return new_index;
}

// Each word on its node; ids 0..W-1, one word per node.
void placeWords(const std::string& path, const std::vector<ForeignWord>& words,
                const std::vector<std::uint32_t>& new_index, std::vector<Vocabulary::Node>* out) {
  const std::size_t n = new_index.size();
  for (const ForeignWord& w : words) {
    if (w.word < 0 || w.word >= static_cast<std::int64_t>(words.size())) {
      fail(path, "word id " + std::to_string(w.word) + " out of range [0, " +
                     std::to_string(words.size()) + ")");
    }
    if (w.node < 1 || w.node >= static_cast<std::int64_t>(n)) {
      fail(path,
           "word " + std::to_string(w.word) + " is on unknown node " + std::to_string(w.node));
    }
    Vocabulary::Node& node = (*out)[new_index[w.node]];
    if (node.word != Vocabulary::kNoWord) {
      fail(path, "node " + std::to_string(w.node) + " carries two words");
    }
    node.word = static_cast<WordId>(w.word);
  }
}

}  // namespace

Vocabulary buildFromForeign(const std::string& path, std::int64_t k, std::int64_t L,
                            std::int64_t scoring, std::int64_t weighting,
                            const std::vector<ForeignNode>& nodes,
                            const std::vector<ForeignWord>& words) {
  checkForeignHeader(path, k, L, scoring, weighting, nodes.size());
  const std::size_t n = nodes.size() + 1;  // + root
  const std::vector<std::uint32_t> slot = slotsById(path, nodes);
  const ChildRows c = childRows(nodes);
  std::vector<std::uint32_t> level;
  const std::vector<std::uint32_t> new_index = newIndices(path, L, c, &level);
  std::vector<Vocabulary::Node> out(n);
  for (std::size_t id = 0; id < n; ++id) {
    Vocabulary::Node& node = out[new_index[id]];
    node.level = level[id];
    node.num_children = c.count[id];
    node.first_child = c.count[id] ? new_index[c.children[c.row[id]]] : 0;
    if (id != 0) {
      const ForeignNode& f = nodes[slot[id]];
      node.parent = new_index[f.parent];
      node.weight = f.weight;
      node.descriptor = f.descriptor;
    }
  }
  placeWords(path, words, new_index, &out);
  try {
    return Vocabulary(static_cast<int>(k), static_cast<int>(L),
                      static_cast<WeightingType>(weighting), static_cast<ScoringType>(scoring),
                      std::move(out));
  } catch (const FormatError& e) {
    fail(path, e.what());
  }
}

}  // namespace vocabulary_io

namespace {

struct FormatName {
  VocabularyFormat format;
  const char* name;
};
const FormatName kFormatNames[] = {
    {VocabularyFormat::kBowg, "bowg"},
    {VocabularyFormat::kDbow2Yaml, "dbow2_yaml"},
    {VocabularyFormat::kDbow2BriefYaml, "dbow2_brief_yaml"},
    {VocabularyFormat::kDbow3Yaml, "dbow3_yaml"},
    {VocabularyFormat::kDbow3Binary, "dbow3"},
    {VocabularyFormat::kOrbSlamText, "orbslam_txt"},
    {VocabularyFormat::kVinsBinary, "vins_bin"},
};

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The first bytes, enough to tell the formats apart; the file is refused
// here already when it is not a regular file or over the limit.
std::string readHead(const std::string& path, std::size_t max) {
  BoundedFile file(path, FileKind::kVocabulary);
  std::string head(max, '\0');
  std::size_t done = 0;
  while (done < max) {
    const std::size_t got = file.readSome(&head[done], max - done);
    if (got == 0) break;
    done += got;
  }
  head.resize(done);
  return head;
}

}  // namespace

VocabularyFormat vocabularyFormatFromString(const std::string& s) {
  std::string names;
  for (const auto& f : kFormatNames) {
    if (s == f.name) return f.format;
    names += std::string(names.empty() ? "" : ", ") + f.name;
  }
  throw std::invalid_argument("unknown vocabulary format '" + s + "' (expected one of: " + names +
                              ")");
}

std::string toString(VocabularyFormat f) {
  for (const auto& n : kFormatNames) {
    if (n.format == f) return n.name;
  }
  return "unknown";
}

VocabularyFormat detectVocabularyFormat(const std::string& path) {
  const std::string head = readHead(path, 512);
  if (head.size() >= 8 && std::memcmp(head.data(), vocabulary_io::kBowgMagic, 8) == 0) {
    return VocabularyFormat::kBowg;
  }
  if (head.size() >= 8) {
    std::uint64_t magic = 0;
    for (int i = 7; i >= 0; --i) magic = (magic << 8) | static_cast<unsigned char>(head[i]);
    if (magic == vocabulary_io::kDbow3Magic) return VocabularyFormat::kDbow3Binary;
  }
  // gzip: OpenCV YAML (the only compressed format we read); DBoW2 and DBoW3
  // YAML share one loader, which tells the descriptor encodings apart.
  if (head.size() >= 2 && static_cast<unsigned char>(head[0]) == 0x1f &&
      static_cast<unsigned char>(head[1]) == 0x8b) {
    return VocabularyFormat::kDbow2Yaml;
  }
  if (head.compare(0, 5, "%YAML") == 0 || head.find("vocabulary:") != std::string::npos) {
    return VocabularyFormat::kDbow2Yaml;
  }
  // ORB-SLAM text: a first line of exactly four integers.
  const std::size_t eol = head.find('\n');
  if (eol != std::string::npos) {
    const std::string line = head.substr(0, eol);
    bool ok = !line.empty();
    int numbers = 0;
    bool in_number = false;
    for (char c : line) {
      if (c >= '0' && c <= '9') {
        if (!in_number) ++numbers;
        in_number = true;
      } else if (c == ' ' || c == '\t' || c == '\r') {
        in_number = false;
      } else {
        ok = false;
      }
    }
    if (ok && numbers == 4) return VocabularyFormat::kOrbSlamText;
  }
  if (endsWith(path, ".bin")) return VocabularyFormat::kVinsBinary;
  throw FormatError(path +
                    ": unrecognised vocabulary format (expected .bowgvoc, DBoW2/DBoW3 YAML, "
                    "DBoW3 binary, ORB-SLAM text or a VINS .bin file)");
}

Vocabulary loadVocabulary(const std::string& path) {
  return loadVocabulary(path, detectVocabularyFormat(path));
}

Vocabulary loadVocabulary(const std::string& path, VocabularyFormat format) {
  switch (format) {
    case VocabularyFormat::kBowg:
      return vocabulary_io::loadBowg(path);
    case VocabularyFormat::kDbow2Yaml:
    case VocabularyFormat::kDbow2BriefYaml:
    case VocabularyFormat::kDbow3Yaml:
      return vocabulary_io::loadDbowYaml(path);
    case VocabularyFormat::kDbow3Binary:
      return vocabulary_io::loadDbow3Binary(path);
    case VocabularyFormat::kOrbSlamText:
      return vocabulary_io::loadOrbSlamText(path);
    case VocabularyFormat::kVinsBinary:
      return vocabulary_io::loadVinsBinary(path);
  }
  throw std::invalid_argument("loadVocabulary: unknown format");
}

void saveVocabulary(const Vocabulary& vocabulary, const std::string& path,
                    VocabularyFormat format) {
  if (vocabulary.empty()) throw std::invalid_argument("saveVocabulary: the vocabulary is empty");
  // What every loader refuses is never written.
  if (vocabulary.branching() < 2 || vocabulary.branching() > kMaxBranching ||
      vocabulary.depth() < 1 || vocabulary.depth() > kMaxDepth) {
    throw std::invalid_argument(
        "saveVocabulary: '" + path + "': k = " + std::to_string(vocabulary.branching()) +
        ", L = " + std::to_string(vocabulary.depth()) + " outside the loadable ranges k in [2, " +
        std::to_string(kMaxBranching) + "], L in [1, " + std::to_string(kMaxDepth) + "]");
  }
  switch (format) {
    case VocabularyFormat::kBowg:
      return vocabulary_io::saveBowg(vocabulary, path);
    case VocabularyFormat::kDbow2Yaml:
      return vocabulary_io::saveDbowYaml(vocabulary, path, vocabulary_io::YamlFlavour::kDbow2Orb);
    case VocabularyFormat::kDbow2BriefYaml:
      return vocabulary_io::saveDbowYaml(vocabulary, path, vocabulary_io::YamlFlavour::kDbow2Brief);
    case VocabularyFormat::kDbow3Yaml:
      return vocabulary_io::saveDbowYaml(vocabulary, path, vocabulary_io::YamlFlavour::kDbow3);
    case VocabularyFormat::kDbow3Binary:
      return vocabulary_io::saveDbow3Binary(vocabulary, path);
    case VocabularyFormat::kOrbSlamText:
      return vocabulary_io::saveOrbSlamText(vocabulary, path);
    case VocabularyFormat::kVinsBinary:
      return vocabulary_io::saveVinsBinary(vocabulary, path);
  }
  throw std::invalid_argument("saveVocabulary: unknown format");
}

}  // namespace bowg
