// ORB-SLAM's text vocabulary "ORBvoc.txt" (ORB-SLAM2's
// TemplatedVocabulary::loadFromTextFile):
//   line 1: k L scoringType weightingType
//   then one line per node, node id = line number (root = 0, not listed):
//     parentId isLeaf d0 .. d31 weight
// d0..d31 are the ORB descriptor bytes; words are numbered in the order
// their leaves appear (isLeaf = 1). ORB-SLAM's reader needs every parent
// listed before its children, which our layout guarantees.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "bowg/core/atomic_file.h"
#include "bowg/core/errors.h"
#include "vocabulary/formats/vocabulary_io_internal.h"

namespace bowg {
namespace vocabulary_io {
namespace {

// The header line "k L scoring weighting" is far shorter than this.
const std::uint64_t kHeadBytes = 256;

// A cursor over one NUL-terminated buffer that never crosses a line end
// unless asked to.
class TextCursor {
 public:
  TextCursor(const std::string& path, const std::string& text)
      : path_(path), p_(text.c_str()), end_(text.c_str() + text.size()) {}

  bool atEnd() const { return p_ >= end_; }
  int line() const { return line_; }
  void skipBlanks() {
    while (p_ < end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\r')) ++p_;
  }
  bool atLineEnd() {
    skipBlanks();
    return p_ >= end_ || *p_ == '\n';
  }
  void nextLine() {
    skipBlanks();
    if (p_ < end_ && *p_ != '\n')
      fail(path_, "line " + std::to_string(line_) + ": unexpected extra values");
    if (p_ < end_) ++p_;
    ++line_;
  }
  void skipEmptyLines() {
    for (;;) {
      const char* q = p_;
      while (q < end_ && (*q == ' ' || *q == '\t' || *q == '\r')) ++q;
      if (q < end_ && *q == '\n') {
        p_ = q + 1;
        ++line_;
      } else {
        return;
      }
    }
  }
  long integer(const char* what) {
    if (atLineEnd()) missing(what);
    char* stop = nullptr;
    errno = 0;
    const long v = std::strtol(p_, &stop, 10);
    if (stop == p_ || errno != 0 || (stop < end_ && !isSeparator(*stop))) bad(what);
    p_ = stop;
    return v;
  }
  double real(const char* what) {
    if (atLineEnd()) missing(what);
    char* stop = nullptr;
    const double v = std::strtod(p_, &stop);
    if (stop == p_ || (stop < end_ && !isSeparator(*stop))) bad(what);
    p_ = stop;
    return v;
  }

 private:
  static bool isSeparator(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
  [[noreturn]] void missing(const char* what) {
    fail(path_, "line " + std::to_string(line_) + ": missing " + what);
  }
  [[noreturn]] void bad(const char* what) {
    fail(path_, "line " + std::to_string(line_) + ": invalid " + what);
  }

  std::string path_;
  const char* p_;
  const char* end_;
  int line_ = 1;
};

}  // namespace

Vocabulary loadOrbSlamText(const std::string& path) {
  // The header line first (it fits the first bytes), the body only when it
  // is plausible.
  BoundedFile file(path, FileKind::kVocabulary);
  std::string text(static_cast<std::size_t>(std::min<std::uint64_t>(file.size(), kHeadBytes)),
                   '\0');
  file.readExactly(&text[0], text.size());
  const std::size_t eol = text.find('\n');
  const std::string first_line = text.substr(0, eol);
  TextCursor head(path, first_line);
  // One statement each: the order of a call's arguments is unspecified.
  const long head_k = head.integer("k");
  const long head_L = head.integer("L");
  const long head_scoring = head.integer("scoringType");
  checkHeader(path, head_k, head_L, head_scoring, head.integer("weightingType"));
  text = readTextRest(&file, std::move(text));
  TextCursor c(path, text);
  const long k = c.integer("k");
  const long L = c.integer("L");
  const long scoring = c.integer("scoringType");
  const long weighting = c.integer("weightingType");
  c.nextLine();
  std::vector<ForeignNode> nodes;
  std::vector<ForeignWord> words;
  for (;;) {
    c.skipEmptyLines();
    if (c.atEnd()) break;
    ForeignNode f;
    f.id = static_cast<std::int64_t>(nodes.size()) + 1;
    f.parent = c.integer("parent id");
    if (f.parent < 0 || f.parent >= f.id) {
      fail(path, "line " + std::to_string(c.line()) + ": parent " + std::to_string(f.parent) +
                     " of node " + std::to_string(f.id) + " is not an earlier node");
    }
    const long is_leaf = c.integer("isLeaf flag");
    if (is_leaf != 0 && is_leaf != 1)
      fail(path, "line " + std::to_string(c.line()) + ": isLeaf must be 0 or 1");
    unsigned char bytes[32];
    for (int j = 0; j < 32; ++j) {
      const long b = c.integer("descriptor byte");
      if (b < 0 || b > 255)
        fail(path, "line " + std::to_string(c.line()) + ": descriptor byte out of range");
      bytes[j] = static_cast<unsigned char>(b);
    }
    f.descriptor = descriptorFromBytes(bytes);
    f.weight = c.real("weight");
    c.nextLine();
    if (is_leaf) words.push_back({static_cast<std::int64_t>(words.size()), f.id});
    nodes.push_back(f);
  }
  return buildFromForeign(path, k, L, scoring, weighting, nodes, words);
}

void saveOrbSlamText(const Vocabulary& v, const std::string& path) {
  const auto& nodes = v.nodes();
  std::string out;
  out.reserve(nodes.size() * 140);
  out += std::to_string(v.branching()) + " " + std::to_string(v.depth()) + " " +
         std::to_string(static_cast<int>(v.scoring())) + " " +
         std::to_string(static_cast<int>(v.weighting())) + "\n";
  char buf[40];
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    const auto& n = nodes[i];
    out += std::to_string(n.parent);
    out += n.num_children == 0 ? " 1" : " 0";
    unsigned char bytes[32];
    descriptorToBytes(n.descriptor, bytes);
    for (int j = 0; j < 32; ++j) {
      out += ' ';
      out += std::to_string(static_cast<int>(bytes[j]));
    }
    // 17 significant digits: the weight survives the text exactly.
    std::snprintf(buf, sizeof(buf), " %.17g\n", n.weight);
    out += buf;
  }
  writeFileAtomically(path, out);
}

}  // namespace vocabulary_io
}  // namespace bowg
