#include "core/yaml_tokens.h"

#include <cstdlib>

#include "bowg/core/errors.h"

namespace bowg {
namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

// Characters that end a plain scalar (this subset never has them inside one).
// Spaces do not: OpenCV writes "descriptor:dbw3 0 32 243 ... }" unquoted.
bool endsPlain(char c) {
  return c == '\n' || c == '\r' || c == ':' || c == ',' || c == '{' || c == '}' || c == '[' ||
         c == ']' || c == '#' || c == '"' || c == '\'';
}

}  // namespace

const char* toString(YamlTokens::Kind kind) {
  switch (kind) {
    case YamlTokens::Kind::kEnd:
      return "end of file";
    case YamlTokens::Kind::kScalar:
      return "a value";
    case YamlTokens::Kind::kQuoted:
      return "a quoted string";
    case YamlTokens::Kind::kColon:
      return "':'";
    case YamlTokens::Kind::kComma:
      return "','";
    case YamlTokens::Kind::kOpenMap:
      return "'{'";
    case YamlTokens::Kind::kCloseMap:
      return "'}'";
    case YamlTokens::Kind::kOpenSeq:
      return "'['";
    case YamlTokens::Kind::kCloseSeq:
      return "']'";
    case YamlTokens::Kind::kDash:
      return "'-'";
  }
  return "?";
}

bool parseInteger(const std::string& text, std::int64_t* value) {
  const std::size_t digits = !text.empty() && (text[0] == '-' || text[0] == '+') ? 1 : 0;
  if (digits == text.size() || text.size() - digits > 18 ||
      text.find_first_not_of("0123456789", digits) != std::string::npos) {
    return false;
  }
  *value = std::strtoll(text.c_str(), nullptr, 10);
  return true;
}

YamlTokens::YamlTokens(const std::string& text, const std::string& path)
    : text_(text), path_(path) {}

const YamlTokens::Token& YamlTokens::peek() {
  if (!peeked_) {
    peek_ = read();
    peeked_ = true;
  }
  return peek_;
}

YamlTokens::Token YamlTokens::next() {
  if (peeked_) {
    peeked_ = false;
    return std::move(peek_);
  }
  return read();
}

void YamlTokens::skipBlanks() {
  const std::size_t n = text_.size();
  while (pos_ < n) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++pos_;
      ++line_;
      line_start_ = true;
    } else if (isBlank(c)) {
      ++pos_;
    } else if (c == '#' || (line_start_ && c == '%')) {
      // A comment, or a directive line ("%YAML:1.0"): to the end of the line.
      while (pos_ < n && text_[pos_] != '\n') ++pos_;
    } else if (line_start_ && (text_.compare(pos_, 3, "---") == 0 ||
                               text_.compare(pos_, 3, "...") == 0) &&
               (pos_ + 3 == n || isBlank(text_[pos_ + 3]))) {
      pos_ += 3;  // document start / end marker
    } else {
      return;
    }
  }
}

YamlTokens::Token YamlTokens::read() {
  skipBlanks();
  Token t;
  t.line = line_;
  const std::size_t n = text_.size();
  if (pos_ >= n) return t;  // kEnd
  line_start_ = false;
  const char c = text_[pos_];
  auto punctuation = [&](Kind kind) {
    ++pos_;
    t.kind = kind;
    return t;
  };
  switch (c) {
    case ':':
      return punctuation(Kind::kColon);
    case ',':
      return punctuation(Kind::kComma);
    case '{':
      return punctuation(Kind::kOpenMap);
    case '}':
      return punctuation(Kind::kCloseMap);
    case '[':
      return punctuation(Kind::kOpenSeq);
    case ']':
      return punctuation(Kind::kCloseSeq);
    default:
      break;
  }
  if (c == '-' && (pos_ + 1 == n || isBlank(text_[pos_ + 1]))) return punctuation(Kind::kDash);
  if (c == '"' || c == '\'') {
    // Quoted scalar: to the matching quote; in "..." a backslash escapes the
    // next character, in '...' a doubled quote is one quote.
    t.kind = Kind::kQuoted;
    std::size_t p = pos_ + 1;
    for (;;) {
      if (p >= n) {
        throw FormatError("file '" + path_ + "': line " + std::to_string(t.line) +
                          ": unterminated quoted string");
      }
      const char d = text_[p];
      if (d == '\n') ++line_;
      if (c == '"' && d == '\\' && p + 1 < n) {
        t.text += text_[p + 1];
        p += 2;
      } else if (d == c) {
        if (c == '\'' && p + 1 < n && text_[p + 1] == '\'') {
          t.text += '\'';
          p += 2;
        } else {
          ++p;
          break;
        }
      } else {
        t.text += d;
        ++p;
      }
    }
    pos_ = p;
    return t;
  }
  // Plain scalar: at least this character (none of the terminators above,
  // and not a blank: skipBlanks stopped here).
  t.kind = Kind::kScalar;
  const std::size_t start = pos_;
  do {
    ++pos_;
  } while (pos_ < n && !endsPlain(text_[pos_]));
  std::size_t stop = pos_;
  while (stop > start && (text_[stop - 1] == ' ' || text_[stop - 1] == '\t')) --stop;
  t.text.assign(text_, start, stop - start);
  return t;
}

}  // namespace bowg
