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
#include <cstdlib>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "bowg/atomic_file.h"
#include "bowg/errors.h"
#include "vocabulary_io_internal.h"

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

std::int64_t readInt(const cv::FileNode& node, const std::string& path, const std::string& what) {
  if (node.empty() || !node.isInt()) fail(path, "missing or non-integer '" + what + "'");
  return static_cast<int>(node);
}

double readReal(const cv::FileNode& node, const std::string& path, const std::string& what) {
  if (node.isInt()) return static_cast<int>(node);
  if (node.empty() || !node.isReal()) fail(path, "missing or non-numeric '" + what + "'");
  return static_cast<double>(node);
}

Vocabulary loadYaml(const std::string& path) {
  cv::FileStorage fs(path, cv::FileStorage::READ);
  if (!fs.isOpened()) fail(path, "OpenCV cannot parse it as YAML/XML");
  const cv::FileNode voc = fs["vocabulary"];
  if (voc.empty() || !voc.isMap()) fail(path, "no 'vocabulary' map (not a DBoW2/DBoW3 vocabulary)");
  const std::int64_t k = readInt(voc["k"], path, "k");
  const std::int64_t L = readInt(voc["L"], path, "L");
  const std::int64_t scoring = readInt(voc["scoringType"], path, "scoringType");
  const std::int64_t weighting = readInt(voc["weightingType"], path, "weightingType");
  const cv::FileNode fn = voc["nodes"];
  if (fn.empty() || !fn.isSeq()) fail(path, "missing 'nodes' sequence");
  std::vector<ForeignNode> nodes;
  nodes.reserve(fn.size());
  for (cv::FileNodeIterator it = fn.begin(); it != fn.end(); ++it) {
    const cv::FileNode n = *it;
    const std::string where = "nodes[" + std::to_string(nodes.size()) + "]";
    if (!n.isMap()) fail(path, where + " is not a map");
    ForeignNode f;
    f.id = readInt(n["nodeId"], path, where + ".nodeId");
    f.parent = readInt(n["parentId"], path, where + ".parentId");
    f.weight = readReal(n["weight"], path, where + ".weight");
    const cv::FileNode dn = n["descriptor"];
    if (dn.empty() || !dn.isString()) fail(path, where + ".descriptor is missing or not a string");
    if (!parseDescriptor(static_cast<std::string>(dn), &f.descriptor)) {
      fail(path, where + ".descriptor (node " + std::to_string(f.id) +
                     ") is not a 256-bit binary descriptor (32 bytes, 'dbw3 0 32 ...' or a "
                     "256-character bit string)");
    }
    nodes.push_back(f);
  }
  const cv::FileNode wn = voc["words"];
  if (wn.empty() || !wn.isSeq()) fail(path, "missing 'words' sequence");
  std::vector<ForeignWord> words;
  words.reserve(wn.size());
  for (cv::FileNodeIterator it = wn.begin(); it != wn.end(); ++it) {
    const cv::FileNode w = *it;
    const std::string where = "words[" + std::to_string(words.size()) + "]";
    if (!w.isMap()) fail(path, where + " is not a map");
    ForeignWord f;
    f.word = readInt(w["wordId"], path, where + ".wordId");
    f.node = readInt(w["nodeId"], path, where + ".nodeId");
    words.push_back(f);
  }
  return buildFromForeign(path, k, L, scoring, weighting, nodes, words);
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

Vocabulary loadDbowYaml(const std::string& path) {
  // FileStorage reports a missing file as a parse failure: tell them apart.
  checkReadable(path);
  try {
    return loadYaml(path);
  } catch (const cv::Exception& e) {
    fail(path, std::string("not a valid OpenCV YAML file: ") + e.what());
  }
}

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
