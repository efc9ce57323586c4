// A tokenizer for the YAML subset OpenCV's FileStorage writes (DBoW2/DBoW3
// vocabularies, BRIEF pattern files): block keys ("k: 10"), block sequences
// ("- { ... }", "- 3"), flow maps and sequences, plain and quoted scalars,
// comments, directives ("%YAML:1.0") and document markers. Untrusted files
// are read with it instead of cv::FileStorage, whose parser spins for ever on
// some malformed input:
// every call to next() consumes at least one character or returns kEnd, so a
// file of n bytes yields at most n tokens and no input can make it loop.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace bowg {

class YamlTokens {
 public:
  enum class Kind {
    kEnd,
    kScalar,    ///< plain scalar: up to the end of the line or one of : , { } [ ] # " ',
                ///< trailing blanks dropped (spaces inside are kept)
    kQuoted,    ///< "..." or '...' (text without the quotes, escapes resolved)
    kColon,
    kComma,
    kOpenMap,   ///< {
    kCloseMap,  ///< }
    kOpenSeq,   ///< [
    kCloseSeq,  ///< ]
    kDash,      ///< "- " of a block sequence item
  };
  struct Token {
    Kind kind = Kind::kEnd;
    std::string text;
    std::size_t line = 1;  ///< 1-based line of the token's first character
  };

  /// `text` must outlive the tokenizer. Throws FormatError naming `path` on
  /// an unterminated quoted scalar.
  YamlTokens(const std::string& text, const std::string& path);

  /// The next token; kEnd at the end of the text (and ever after).
  Token next();
  /// The next token without consuming it.
  const Token& peek();

 private:
  Token read();
  void skipBlanks();

  const std::string& text_;
  const std::string& path_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
  bool line_start_ = true;  ///< only blanks since the last newline
  bool peeked_ = false;
  Token peek_;
};

/// Human-readable name of a token kind, for error messages.
const char* toString(YamlTokens::Kind kind);

/// A scalar's text as a decimal integer: an optional sign and 1 to 18 digits
/// (so that it fits in 64 bits), nothing else. False otherwise.
bool parseInteger(const std::string& text, std::int64_t* value);

}  // namespace bowg
