// The YAML-subset tokenizer of the vocabulary loader: tokens, texts and lines
// of hand-written snippets, and termination on every byte string (each call
// consumes input, so no input can make a reader loop).
#include "core/yaml_tokens.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "bowg/core/errors.h"

namespace bowg {
namespace {

using Kind = YamlTokens::Kind;

std::vector<YamlTokens::Token> tokensOf(const std::string& text) {
  const std::string path = "snippet.yml";
  YamlTokens tokens(text, path);
  std::vector<YamlTokens::Token> out;
  for (;;) {
    YamlTokens::Token t = tokens.next();
    if (t.kind == Kind::kEnd) break;
    out.push_back(t);
  }
  return out;
}

TEST(YamlTokens, OpenCvVocabularyLayout) {
  const std::string text =
      "%YAML:1.0\n"
      "---\n"
      "vocabulary:\n"
      "   k: 10  # branching\n"
      "   nodes:\n"
      "      - { nodeId:1, weight:-2.5e-01,\n"
      "          descriptor:dbw3 0 32 7  }\n"
      "   words: [ { wordId:0 }, 'it''s', \"a\\\"b\" ]\n";
  const std::vector<YamlTokens::Token> t = tokensOf(text);
  struct Expected {
    Kind kind;
    const char* text;
    std::size_t line;
  };
  const std::vector<Expected> expected = {
      {Kind::kScalar, "vocabulary", 3}, {Kind::kColon, "", 3},
      {Kind::kScalar, "k", 4},          {Kind::kColon, "", 4},
      {Kind::kScalar, "10", 4},         {Kind::kScalar, "nodes", 5},
      {Kind::kColon, "", 5},            {Kind::kDash, "", 6},
      {Kind::kOpenMap, "", 6},          {Kind::kScalar, "nodeId", 6},
      {Kind::kColon, "", 6},            {Kind::kScalar, "1", 6},
      {Kind::kComma, "", 6},            {Kind::kScalar, "weight", 6},
      {Kind::kColon, "", 6},            {Kind::kScalar, "-2.5e-01", 6},
      {Kind::kComma, "", 6},            {Kind::kScalar, "descriptor", 7},
      {Kind::kColon, "", 7},            {Kind::kScalar, "dbw3 0 32 7", 7},
      {Kind::kCloseMap, "", 7},         {Kind::kScalar, "words", 8},
      {Kind::kColon, "", 8},            {Kind::kOpenSeq, "", 8},
      {Kind::kOpenMap, "", 8},          {Kind::kScalar, "wordId", 8},
      {Kind::kColon, "", 8},            {Kind::kScalar, "0", 8},
      {Kind::kCloseMap, "", 8},         {Kind::kComma, "", 8},
      {Kind::kQuoted, "it's", 8},       {Kind::kComma, "", 8},
      {Kind::kQuoted, "a\"b", 8},       {Kind::kCloseSeq, "", 8},
  };
  ASSERT_EQ(t.size(), expected.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(t[i].kind, expected[i].kind);
    EXPECT_EQ(t[i].text, expected[i].text);
    EXPECT_EQ(t[i].line, expected[i].line);
  }
}

TEST(YamlTokens, PeekDoesNotConsumeAndEndIsForever) {
  const std::string text = "a: b", path = "p";
  YamlTokens tokens(text, path);
  EXPECT_EQ(tokens.peek().text, "a");
  EXPECT_EQ(tokens.peek().text, "a");
  EXPECT_EQ(tokens.next().text, "a");
  EXPECT_EQ(tokens.next().kind, Kind::kColon);
  EXPECT_EQ(tokens.next().text, "b");
  for (int i = 0; i < 3; ++i) EXPECT_EQ(tokens.next().kind, Kind::kEnd);
}

TEST(YamlTokens, UnterminatedQuoteIsAFormatErrorNamingFileAndLine) {
  const std::string text = "a:\n  \"never closed", path = "broken.yml";
  YamlTokens tokens(text, path);
  tokens.next();
  tokens.next();
  try {
    tokens.next();
    ADD_FAILURE() << "no error";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.yml': line 2"), std::string::npos) << e.what();
  }
}

TEST(YamlTokens, IntegersAreASignAndUpTo18Digits) {
  std::int64_t v = 0;
  EXPECT_TRUE(parseInteger("42", &v));
  EXPECT_EQ(v, 42);
  EXPECT_TRUE(parseInteger("-128", &v));
  EXPECT_EQ(v, -128);
  EXPECT_TRUE(parseInteger("+7", &v));
  EXPECT_EQ(v, 7);
  EXPECT_TRUE(parseInteger("999999999999999999", &v));  // 18 digits
  EXPECT_EQ(v, 999999999999999999LL);
  for (const char* bad : {"", "-", "1.5", "1e3", " 1", "0x10", "1000000000000000000", "12a"}) {
    EXPECT_FALSE(parseInteger(bad, &v)) << "'" << bad << "'";
  }
}

TEST(YamlTokens, EveryByteStringEndsWithinItsLength) {
  // Random bytes biased towards the characters the tokenizer acts on: at
  // most one token per byte, then kEnd (or a FormatError).
  std::mt19937 rng(5);
  const std::string alphabet = " \t\n\r:,{}[]#\"'-.%\\ab01";
  for (int round = 0; round < 2000; ++round) {
    std::string text(rng() % 64, ' ');
    for (char& c : text) {
      c = rng() % 4 == 0 ? static_cast<char>(rng() % 256) : alphabet[rng() % alphabet.size()];
    }
    const std::string path = "random.yml";
    YamlTokens tokens(text, path);
    std::size_t count = 0;
    try {
      while (tokens.next().kind != Kind::kEnd) {
        ++count;
        ASSERT_LE(count, text.size()) << "round " << round;
      }
    } catch (const FormatError&) {
    }
  }
}

}  // namespace
}  // namespace bowg
