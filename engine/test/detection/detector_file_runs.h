// Shared by the detector file tests: a vocabulary, options with every
// extension on, a short corridor run, whole-file reads and writes, and
// comparisons of two detectors' results.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <random>
#include <string>

#include "bowg/core/checksum.h"
#include "bowg/core/errors.h"
#include "bowg/database/database.h"
#include "bowg/detection/loop_detector.h"
#include "bowg/vocabulary/vocabulary.h"
#include "synthetic_corridor.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace testing {

inline std::shared_ptr<const Vocabulary> vocabulary(std::uint64_t seed = 7) {
  return std::make_shared<Vocabulary>(testing::makeSyntheticVocabulary(10, 4, seed));
}

inline LoopDetectorOptions options() {
  LoopDetectorOptions o;
  o.geometric.direct_index_level = 2;
  o.islands.recent_exclusion = 10;
  o.distribution.enabled = true;
  o.similarity.lambda_1 = 0.4;
  o.similarity.lambda_2 = 0.4;
  return o;
}

inline std::string outPath(const std::string& name) {
  return std::string(BOWG_TEST_OUTPUT_DIR) + "/detector_file_test_" + name;
}

inline std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Keyframes: forward over 40 m, then back over the first metres (revisits).
inline std::vector<KeyframeInput> keyframes() {
  const testing::Corridor c = testing::makeCorridor(50, 40, 31);
  std::mt19937_64 rng(8);
  std::vector<KeyframeInput> out;
  for (int i = 0; i < 40; ++i) out.push_back(testing::observeCorridor(c, i, 1.0 + i, rng, 2, 0.5));
  for (int i = 0; i < 25; ++i) {
    out.push_back(testing::observeCorridor(c, 39.5 - i, 41.0 + i, rng, 2, 0.5));
  }
  return out;
}

inline void expectSameResult(const LoopResult& a, const LoopResult& b) {
  EXPECT_EQ(a.query_id, b.query_id);
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.match_id, b.match_id);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.best.entry, b.best.entry);
  EXPECT_DOUBLE_EQ(a.best.eta, b.best.eta);
  EXPECT_DOUBLE_EQ(a.word_normaliser, b.word_normaliser);
  EXPECT_DOUBLE_EQ(a.group_normaliser, b.group_normaliser);
}

inline void expectSameCandidates(const LoopDetector& a, const LoopDetector& b) {
  ASSERT_EQ(a.lastCandidates().size(), b.lastCandidates().size());
  for (std::size_t i = 0; i < a.lastCandidates().size(); ++i) {
    const CandidateScores &x = a.lastCandidates()[i], &y = b.lastCandidates()[i];
    EXPECT_EQ(x.entry, y.entry);
    EXPECT_DOUBLE_EQ(x.eta_w, y.eta_w);
    EXPECT_DOUBLE_EQ(x.eta_g, y.eta_g);
    EXPECT_DOUBLE_EQ(x.eta_d, y.eta_d);
    EXPECT_DOUBLE_EQ(x.eta, y.eta);
  }
}

}  // namespace testing
}  // namespace bowg
