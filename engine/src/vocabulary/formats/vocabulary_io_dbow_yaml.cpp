// DBoW2 and DBoW3 vocabularies in OpenCV's YAML (optionally gzipped; OpenCV's
// FileStorage reads and writes .gz transparently). Layout (DBoW2's
// TemplatedVocabulary::save, DBoW3's Vocabulary::save):
//   vocabulary: { k, L, scoringType, weightingType,
//                 nodes: [ {nodeId, parentId, weight, descriptor}, ... ],
//                 words: [ {wordId, nodeId}, ... ] }
// The root (id 0) is not listed. Descriptor strings, told apart by content:
//   DBoW2 ORB (FORB::toString):    "b0 b1 ... b31"            32 byte values
//   DBoW2 BRIEF (FBrief::toString): 256 '0'/'1' characters, most significant
//                                   bit (bit 255) first (boost::to_string)
//   DBoW3 (DescManip::toString):   "dbw3 <cv type> <cols> b0 ... b31"
//   early DBoW3 (e.g. slambook2):  "<cv type> <cols> b0 ... b31" (34 values)
// Only 256-bit binary descriptors (CV_8U, 32 columns) are accepted.
// Read with this project's tokenizer (yaml_tokens.h), not cv::FileStorage,
// whose parser never returns on some malformed files; written with
// cv::FileStorage.
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "bowg/core/atomic_file.h"
#include "bowg/core/errors.h"
#include "core/yaml_tokens.h"
#include "vocabulary/formats/vocabulary_io_internal.h"

namespace bowg {
namespace vocabulary_io {
namespace {

// Parses whitespace-separated non-negative integers; false on anything else.
bool parseInts(const std::string& s, std::size_t from, std::vector<long>* out) {
  out->clear();
  const char* p = s.c_str() + from;
  const char* end = s.c_str() + s.size();
  while (p < end) {
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')) ++p;
    if (p == end) break;
    if (*p < '0' || *p > '9') return false;
    long v = 0;
    int digits = 0;
    while (p < end && *p >= '0' && *p <= '9') {
      if (++digits > 9) return false;
      v = v * 10 + (*p++ - '0');
    }
    out->push_back(v);
    if (out->size() > 300) return false;
  }
  return true;
}

bool bytesToDescriptor(const std::vector<long>& values, std::size_t from, Descriptor* d) {
  if (values.size() != from + 32) return false;
  unsigned char bytes[32];
  for (std::size_t j = 0; j < 32; ++j) {
    const long v = values[from + j];
    if (v < 0 || v > 255) return false;
    bytes[j] = static_cast<unsigned char>(v);
  }
  *d = descriptorFromBytes(bytes);
  return true;
}

bool parseDescriptor(const std::string& s, Descriptor* d) {
  std::size_t start = s.find_first_not_of(" \t");
  if (start == std::string::npos) return false;
  std::size_t stop = s.find_last_not_of(" \t") + 1;
  const std::string t = s.substr(start, stop - start);
  std::vector<long> values;
  if (t.compare(0, 4, "dbw3") == 0) {
    if (!parseInts(t, 4, &values) || values.size() < 2) return false;
    if (values[0] != 0 /* CV_8UC1 */ || values[1] != 32) return false;
    return bytesToDescriptor(values, 2, d);
  }
  if (t.size() == 256 && t.find_first_not_of("01") == std::string::npos) {
    *d = Descriptor();
    for (std::size_t i = 0; i < 256; ++i) {
      if (t[i] == '1') {
        const std::size_t bit = 255 - i;
        d->bits[bit / 64] |= 1ull << (bit % 64);
      }
    }
    return true;
  }
  if (!parseInts(t, 0, &values)) return false;
  if (values.size() == 32) return bytesToDescriptor(values, 0, d);
  if (values.size() == 34 && values[0] == 0 && values[1] == 32)
    return bytesToDescriptor(values, 2, d);
  return false;
}

// Decompressed bytes per compressed byte beyond which a .gz is refused as
// a bomb, not a vocabulary. Real vocabularies inflate 3.9:1 (DBoW2 k9L3
// small_voc.yml.gz), 4.5:1 (slambook2's DBoW3 k10L5 vocabulary.yml.gz);
// the default vocabulary saved gzipped inflates 3.9:1 (DBoW2 ORB), 4.1:1
// (DBoW3) and 5.4:1 (BRIEF bit strings, the most redundant text we write).
// 64:1 leaves a wide margin for degenerate but honest trees, while a gzip of
// zeros or blanks inflates about 1000:1: refused after kRatioGrace bytes, in
// milliseconds and a few tens of MB, instead of at the decompressed limit.
const std::uint64_t kMaxRatio = 64;
// Below this much text the ratio is not judged: a small file's header and
// first records may compress well by chance.
const std::uint64_t kRatioGrace = std::uint64_t(16) << 20;

// The file's text, gunzipped when it is gzip (zlib reads plain files as
// they are). Bounded: the file by the vocabulary limit before a byte is
// read, its text by the same limit and by kMaxRatio while it is inflated.
std::string readText(const std::string& path) {
  const BoundedFile file(path, FileKind::kVocabulary);
  const FileLimit limit = fileLimit(FileKind::kVocabulary);
  // gzdopen owns the descriptor it is given; `file` keeps its own.
  const int fd = ::dup(file.fd());
  gzFile f = fd < 0 ? nullptr : gzdopen(fd, "rb");
  if (f == nullptr) {
    const std::string why = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    throw IoError("cannot read vocabulary '" + path + "': " + why);
  }
  std::string text;
  std::vector<char> buffer(1 << 16);
  try {
    for (;;) {
      const int got = gzread(f, buffer.data(), static_cast<unsigned>(buffer.size()));
      if (got < 0) {
        int code = 0;
        fail(path, std::string("cannot decompress it (") + gzerror(f, &code) + ")");
      }
      if (got == 0) break;
      checkText(path, buffer.data(), static_cast<std::size_t>(got), text.size());
      text.append(buffer.data(), static_cast<std::size_t>(got));
      if (text.size() > limit.max_bytes) {
        throw IoError("cannot read " + limitMessage(FileKind::kVocabulary, path,
                                                    "decompresses to " + formatBytes(text.size()),
                                                    limit));
      }
      const std::uint64_t consumed = static_cast<std::uint64_t>(std::max<z_off_t>(gzoffset(f), 1));
      if (text.size() > kRatioGrace && text.size() > kMaxRatio * consumed) {
        fail(path, "decompresses more than " + std::to_string(kMaxRatio) + ":1 (" +
                       formatBytes(text.size()) + " from the first " + formatBytes(consumed) +
                       "): a compression bomb, not a vocabulary");
      }
    }
  } catch (...) {
    gzclose(f);
    throw;
  }
  gzclose(f);
  return text;
}

// Reads the YAML layout of the header comment token by token (yaml_tokens.h):
// no input can make it loop, and whatever does not fit the layout is a
// FormatError naming the file, the line and what was expected.
class DbowYamlReader {
 public:
  DbowYamlReader(const std::string& text, const std::string& path)
      : path_(path), tokens_(text, path) {}

  Vocabulary read() {
    YamlTokens::Token t = tokens_.next();
    if (t.kind != YamlTokens::Kind::kScalar || t.text != "vocabulary") {
      fail(path_, "no 'vocabulary' map (not a DBoW2/DBoW3 vocabulary)");
    }
    expect(YamlTokens::Kind::kColon, "':' after 'vocabulary'");
    std::int64_t header[4] = {0, 0, 0, 0};
    bool have_header[4] = {false, false, false, false};
    const char* header_keys[4] = {"k", "L", "scoringType", "weightingType"};
    bool have_nodes = false, have_words = false;
    std::vector<ForeignNode> nodes;
    std::vector<ForeignWord> words;
    while (tokens_.peek().kind != YamlTokens::Kind::kEnd) {
      const YamlTokens::Token key = expect(YamlTokens::Kind::kScalar, "a key of 'vocabulary'");
      expect(YamlTokens::Kind::kColon, "':' after '" + key.text + "'");
      bool known = false;
      for (int i = 0; i < 4; ++i) {
        if (key.text != header_keys[i]) continue;
        if (have_header[i]) failAt(key, "'" + key.text + "' appears twice");
        header[i] =
            integer(expect(YamlTokens::Kind::kScalar, "the value of '" + key.text + "'"), key.text);
        if (header[i] < 0) {
          failAt(key,
                 "'" + key.text + "' is " + std::to_string(header[i]) + ", must not be negative");
        }
        have_header[i] = true;
        known = true;
      }
      if (key.text == "nodes" || key.text == "words") {
        bool& seen = key.text == "nodes" ? have_nodes : have_words;
        if (seen) failAt(key, "'" + key.text + "' appears twice");
        seen = true;
        known = true;
        if (key.text == "nodes") {
          records(key.text, [&](const Fields& f, const YamlTokens::Token& at) {
            nodes.push_back(node(f, at, nodes.size()));
          });
        } else {
          records(key.text, [&](const Fields& f, const YamlTokens::Token& at) {
            words.push_back(word(f, at, words.size()));
          });
        }
      }
      if (!known) failAt(key, "unknown key '" + key.text + "' in 'vocabulary'");
    }
    for (int i = 0; i < 4; ++i) {
      if (!have_header[i]) fail(path_, std::string("missing '") + header_keys[i] + "'");
    }
    if (!have_nodes) fail(path_, "missing 'nodes' sequence");
    if (!have_words) fail(path_, "missing 'words' sequence");
    return buildFromForeign(path_, header[0], header[1], header[2], header[3], nodes, words);
  }

 private:
  // The fields of one flow map: key -> (value token).
  using Fields = std::vector<std::pair<std::string, YamlTokens::Token>>;

  [[noreturn]] void failAt(const YamlTokens::Token& t, const std::string& why) const {
    fail(path_, "line " + std::to_string(t.line) + ": " + why);
  }

  // The next token, which must be of `kind` (`what` describes it).
  YamlTokens::Token expect(YamlTokens::Kind kind, const std::string& what) {
    YamlTokens::Token t = tokens_.next();
    if (t.kind != kind) {
      failAt(t, "expected " + what + ", found " +
                    (t.kind == YamlTokens::Kind::kScalar || t.kind == YamlTokens::Kind::kQuoted
                         ? "'" + t.text.substr(0, 40) + "'"
                         : std::string(toString(t.kind))));
    }
    return t;
  }

  std::int64_t integer(const YamlTokens::Token& t, const std::string& what) const {
    std::int64_t v = 0;
    if (!parseInteger(t.text, &v)) {
      failAt(t, "'" + what + "' is not an integer ('" + t.text.substr(0, 40) + "')");
    }
    return v;
  }

  double real(const YamlTokens::Token& t, const std::string& what) const {
    const char* begin = t.text.c_str();
    char* end = nullptr;
    const double v = t.text.empty() ? 0.0 : std::strtod(begin, &end);
    if (t.text.empty() || end != begin + t.text.size()) {
      failAt(t, "'" + what + "' is not a number ('" + t.text.substr(0, 40) + "')");
    }
    return v;
  }

  // A sequence of flow maps, block ("- { ... }" items) or flow ("[ {...}, ]").
  template <typename OnRecord>
  void records(const std::string& name, OnRecord on_record) {
    if (tokens_.peek().kind == YamlTokens::Kind::kOpenSeq) {
      tokens_.next();
      while (tokens_.peek().kind != YamlTokens::Kind::kCloseSeq) {
        const YamlTokens::Token at = tokens_.peek();
        on_record(flowMap(name), at);
        if (tokens_.peek().kind == YamlTokens::Kind::kComma)
          tokens_.next();
        else if (tokens_.peek().kind != YamlTokens::Kind::kCloseSeq)
          expect(YamlTokens::Kind::kCloseSeq, "',' or ']' in '" + name + "'");
      }
      tokens_.next();
      return;
    }
    if (tokens_.peek().kind != YamlTokens::Kind::kDash) {
      expect(YamlTokens::Kind::kDash, "'-' or '[' starting the '" + name + "' sequence");
    }
    while (tokens_.peek().kind == YamlTokens::Kind::kDash) {
      tokens_.next();
      const YamlTokens::Token at = tokens_.peek();
      on_record(flowMap(name), at);
    }
  }

  Fields flowMap(const std::string& name) {
    expect(YamlTokens::Kind::kOpenMap, "'{' opening an item of '" + name + "'");
    Fields fields;
    while (tokens_.peek().kind != YamlTokens::Kind::kCloseMap) {
      const YamlTokens::Token key = expect(YamlTokens::Kind::kScalar, "a key in '" + name + "'");
      expect(YamlTokens::Kind::kColon, "':' after '" + key.text + "'");
      YamlTokens::Token value = tokens_.next();
      if (value.kind != YamlTokens::Kind::kScalar && value.kind != YamlTokens::Kind::kQuoted) {
        failAt(value, "'" + key.text + "' has no value");
      }
      for (const auto& f : fields) {
        if (f.first == key.text) failAt(key, "'" + key.text + "' appears twice in one item");
      }
      if (fields.size() >= 4) failAt(key, "an item of '" + name + "' has more than 4 fields");
      fields.emplace_back(key.text, std::move(value));
      if (tokens_.peek().kind == YamlTokens::Kind::kComma)
        tokens_.next();
      else if (tokens_.peek().kind != YamlTokens::Kind::kCloseMap)
        expect(YamlTokens::Kind::kCloseMap, "',' or '}' in an item of '" + name + "'");
    }
    tokens_.next();
    return fields;
  }

  const YamlTokens::Token& field(const Fields& f, const char* key, const YamlTokens::Token& at,
                                 const std::string& where) const {
    for (const auto& kv : f) {
      if (kv.first == key) return kv.second;
    }
    failAt(at, std::string("missing '") + where + "." + key + "'");
  }

  ForeignNode node(const Fields& f, const YamlTokens::Token& at, std::size_t index) const {
    const std::string where = "nodes[" + std::to_string(index) + "]";
    ForeignNode n;
    n.id = integer(field(f, "nodeId", at, where), where + ".nodeId");
    n.parent = integer(field(f, "parentId", at, where), where + ".parentId");
    n.weight = real(field(f, "weight", at, where), where + ".weight");
    const YamlTokens::Token& d = field(f, "descriptor", at, where);
    if (!parseDescriptor(d.text, &n.descriptor)) {
      failAt(d, where + ".descriptor (node " + std::to_string(n.id) +
                    ") is not a 256-bit binary descriptor (32 bytes, 'dbw3 0 32 ...' or a "
                    "256-character bit string)");
    }
    if (f.size() != 4)
      failAt(at, where + " has fields other than nodeId, parentId, weight, descriptor");
    return n;
  }

  ForeignWord word(const Fields& f, const YamlTokens::Token& at, std::size_t index) const {
    const std::string where = "words[" + std::to_string(index) + "]";
    ForeignWord w;
    w.word = integer(field(f, "wordId", at, where), where + ".wordId");
    w.node = integer(field(f, "nodeId", at, where), where + ".nodeId");
    if (f.size() != 2) failAt(at, where + " has fields other than wordId, nodeId");
    return w;
  }

  const std::string& path_;
  YamlTokens tokens_;
};

Vocabulary loadYaml(const std::string& path) {
  const std::string text = readText(path);
  return DbowYamlReader(text, path).read();
}

std::string descriptorString(const Descriptor& d, YamlFlavour flavour) {
  std::string s;
  if (flavour == YamlFlavour::kDbow2Brief) {
    s.resize(256);
    for (int i = 0; i < 256; ++i) {
      const int bit = 255 - i;
      s[static_cast<std::size_t>(i)] = (d.bits[bit / 64] >> (bit % 64)) & 1 ? '1' : '0';
    }
    return s;
  }
  unsigned char bytes[32];
  descriptorToBytes(d, bytes);
  if (flavour == YamlFlavour::kDbow3) s = "dbw3 0 32 ";
  for (int j = 0; j < 32; ++j) {
    s += std::to_string(static_cast<int>(bytes[j]));
    s += ' ';
  }
  return s;
}

}  // namespace

Vocabulary loadDbowYaml(const std::string& path) { return loadYaml(path); }

void saveDbowYaml(const Vocabulary& v, const std::string& path, YamlFlavour flavour) {
  AtomicFileWriter writer(path);
  try {
    // FORMAT_YAML: FileStorage would pick XML for unknown extensions.
    cv::FileStorage fs(writer.tempPath(), cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
    if (!fs.isOpened()) throw IoError("cannot write '" + path + "'");
    const auto& nodes = v.nodes();
    fs << "vocabulary"
       << "{";
    fs << "k" << v.branching() << "L" << v.depth();
    fs << "scoringType" << static_cast<int>(v.scoring());
    fs << "weightingType" << static_cast<int>(v.weighting());
    fs << "nodes"
       << "[";
    for (std::size_t i = 1; i < nodes.size(); ++i) {
      fs << "{:"
         << "nodeId" << static_cast<int>(i) << "parentId" << static_cast<int>(nodes[i].parent)
         << "weight" << nodes[i].weight << "descriptor"
         << descriptorString(nodes[i].descriptor, flavour) << "}";
    }
    fs << "]";
    fs << "words"
       << "[";
    for (std::size_t w = 0; w < v.wordCount(); ++w) {
      fs << "{:"
         << "wordId" << static_cast<int>(w) << "nodeId"
         << static_cast<int>(v.nodeOfWord(static_cast<WordId>(w))) << "}";
    }
    fs << "]"
       << "}";
    fs.release();
  } catch (const cv::Exception& e) {
    throw IoError("cannot write '" + path + "': " + e.what());
  }
  writer.commit();
}

}  // namespace vocabulary_io
}  // namespace bowg
