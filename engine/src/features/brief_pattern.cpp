// Read with the project's YAML-subset tokenizer (yaml_tokens.h), not
// cv::FileStorage, whose parser spins for ever on some malformed files.
#include "bowg/features/brief_pattern.h"

#include "bowg/core/bounded_file.h"
#include "bowg/core/errors.h"
#include "core/yaml_tokens.h"

namespace bowg {
namespace {

// VINS' file is ~6 KB; anything past this is not a pattern file.
constexpr std::size_t kMaxPatternFileBytes = 1 << 20;

std::string readPatternFile(const std::string& path) {
  BoundedFile file(path, FileKind::kText, "BRIEF pattern file");
  if (file.size() > kMaxPatternFileBytes) {
    throw FormatError("BRIEF pattern file '" + path + "' is " + formatBytes(file.size()) +
                      ", larger than a pattern file can be (1.0 MiB)");
  }
  return file.readRest();
}

[[noreturn]] void failAt(const std::string& path, const YamlTokens::Token& t,
                         const std::string& why) {
  throw FormatError("BRIEF pattern file " + path + ": line " + std::to_string(t.line) + ": " +
                    why);
}

int entry(const std::string& path, const std::string& key, const YamlTokens::Token& t) {
  std::int64_t v = 0;
  if (t.kind != YamlTokens::Kind::kScalar || !parseInteger(t.text, &v)) {
    failAt(path, t, "sequence '" + key + "' holds a non-integer entry");
  }
  if (v > kBriefPatternMaxOffset || v < -kBriefPatternMaxOffset) {
    failAt(path, t, "sequence '" + key + "' entry " + t.text + " exceeds +-" +
                        std::to_string(kBriefPatternMaxOffset) + " px");
  }
  return static_cast<int>(v);
}

// The integers of one sequence, block ("- 3" lines) or flow ("[3, 4]").
std::vector<int> readSequence(YamlTokens* tokens, const std::string& path, const std::string& key) {
  std::vector<int> values;
  const auto add = [&](const YamlTokens::Token& t) {
    if (values.size() == static_cast<std::size_t>(kBriefPatternPairs)) {
      failAt(path, t, "sequence '" + key + "' has more than " +
                          std::to_string(kBriefPatternPairs) + " entries");
    }
    values.push_back(entry(path, key, t));
  };
  if (tokens->peek().kind == YamlTokens::Kind::kOpenSeq) {
    tokens->next();
    while (tokens->peek().kind != YamlTokens::Kind::kCloseSeq) {
      add(tokens->next());
      const YamlTokens::Token sep = tokens->peek();
      if (sep.kind == YamlTokens::Kind::kComma) tokens->next();
      else if (sep.kind != YamlTokens::Kind::kCloseSeq)
        failAt(path, sep, "expected ',' or ']' in sequence '" + key + "'");
    }
    tokens->next();
  } else {
    if (tokens->peek().kind != YamlTokens::Kind::kDash) {
      failAt(path, tokens->peek(), "missing integer sequence '" + key + "'");
    }
    while (tokens->peek().kind == YamlTokens::Kind::kDash) {
      tokens->next();
      add(tokens->next());
    }
  }
  return values;
}

}  // namespace

std::vector<cv::Vec4i> loadBriefPattern(const std::string& path) {
  const std::string text = readPatternFile(path);
  YamlTokens tokens(text, path);
  const char* names[4] = {"x1", "y1", "x2", "y2"};
  std::vector<int> seq[4];
  bool seen[4] = {false, false, false, false};
  while (tokens.peek().kind != YamlTokens::Kind::kEnd) {
    const YamlTokens::Token key = tokens.next();
    int which = -1;
    for (int i = 0; i < 4; ++i) {
      if (key.kind == YamlTokens::Kind::kScalar && key.text == names[i]) which = i;
    }
    if (which < 0) failAt(path, key, "expected one of the keys x1, y1, x2, y2");
    if (seen[which]) failAt(path, key, "'" + key.text + "' appears twice");
    seen[which] = true;
    const YamlTokens::Token colon = tokens.next();
    if (colon.kind != YamlTokens::Kind::kColon) failAt(path, colon, "expected ':' after " + key.text);
    seq[which] = readSequence(&tokens, path, key.text);
  }
  for (int i = 0; i < 4; ++i) {
    if (!seen[i]) {
      throw FormatError("BRIEF pattern file " + path + ": missing integer sequence '" +
                        names[i] + "'");
    }
    if (seq[i].size() != static_cast<std::size_t>(kBriefPatternPairs)) {
      throw FormatError("BRIEF pattern file " + path + ": sequence '" + names[i] + "' has " +
                        std::to_string(seq[i].size()) + " entries, expected " +
                        std::to_string(kBriefPatternPairs));
    }
  }
  std::vector<cv::Vec4i> pattern(kBriefPatternPairs);
  for (int i = 0; i < kBriefPatternPairs; ++i) {
    pattern[i] = cv::Vec4i(seq[0][i], seq[1][i], seq[2][i], seq[3][i]);
  }
  return pattern;
}

}  // namespace bowg
