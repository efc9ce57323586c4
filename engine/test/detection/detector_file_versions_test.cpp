// LoopDetector::save / load across file versions: packed keypoint positions
// (version 5) against a version-4 file's floats, and version-1 files without
// the normaliser history; versions beyond the current one are refused.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "bowg/core/errors.h"
#include "bowg/database/packed_points.h"
#include "detection/detector_file_runs.h"
#include "detection/older_detector_files.h"

namespace bowg {
namespace {

using testing::asVersion;
using testing::expectSameCandidates;
using testing::expectSameResult;
using testing::fromVersion7Bytes;
using testing::keyframes;
using testing::options;
using testing::outPath;
using testing::readBytes;
using testing::vocabulary;
using testing::writeBytes;

// The corridor's keyframes with every keypoint moved onto a pyramid level's
// grid, as OpenCV's ORB places them: the database packs those positions.
std::vector<KeyframeInput> pyramidKeyframes() {
  std::vector<KeyframeInput> kfs = keyframes();
  for (KeyframeInput& kf : kfs) testing::placeOnOrbPyramid(&kf);
  return kfs;
}

void expectSamePositions(const Database& a, const Database& b) {
  ASSERT_EQ(a.size(), b.size());
  for (EntryId id = 0; id < a.size(); ++id) {
    const PackedPoints& pa = a.entry(id).points;
    const PackedPoints& pb = b.entry(id).points;
    ASSERT_EQ(pa.size(), pb.size());
    for (std::size_t i = 0; i < pa.size(); ++i) {
      EXPECT_EQ(pa[i].x, pb[i].x);
      EXPECT_EQ(pa[i].y, pb[i].y);
    }
  }
}

// Packed positions come back packed as they were (version 5), and a
// version-4 file, which has no scale factors, loads with the same positions
// kept as floats.
TEST(DatabaseIo, PackedPositionsRoundTrip) {
  const auto voc = vocabulary();
  const auto kfs = pyramidKeyframes();
  LoopDetector a(voc, options());
  for (int i = 0; i < 45; ++i) a.process(kfs[i]);
  std::size_t upper = 0;
  for (const DatabaseEntry& e : a.database().entries()) {
    EXPECT_EQ(e.points.exactCount(), 0u);
    EXPECT_EQ(e.points.scaleFactor(), 1.2f);
    upper += e.points.size();
  }
  ASSERT_GT(upper, 1000u);
  const std::string v5 = outPath("packed.bowgdb");
  a.save(v5);
  LoopDetector b(voc, options());
  b.load(v5);
  expectSamePositions(a.database(), b.database());
  for (const DatabaseEntry& e : b.database().entries()) {
    EXPECT_EQ(e.points.exactCount(), 0u);
    EXPECT_EQ(e.points.scaleFactor(), 1.2f);
  }

  // Version 4: the same bytes without the scale factors, the place links
  // and the odometry positions (u32 count + 45 f32, u32 count + 45 u32,
  // fromVersion7Bytes before the checksum).
  const std::string v4 = outPath("packed_v4.bowgdb");
  writeBytes(v4, asVersion(readBytes(v5), 2 * (4 + 45 * 4) + fromVersion7Bytes(45), 4));
  LoopDetector c(voc, options());
  c.load(v4);
  expectSamePositions(a.database(), c.database());
  std::size_t exact = 0;
  for (const DatabaseEntry& e : c.database().entries()) exact += e.points.exactCount();
  EXPECT_GT(exact, 0u);  // levels above 0 are not integers
  for (std::size_t i = 45; i < kfs.size(); ++i) {
    const LoopResult r = a.process(kfs[i]);
    expectSameResult(r, b.process(kfs[i]));
    expectSameResult(r, c.process(kfs[i]));
  }
  std::remove(v5.c_str());
  std::remove(v4.c_str());
}

// A version-1 file (written before the normaliser history existed) still
// loads: the same file without the history, its version, payload size and
// checksum rewritten as version 1 wrote them. Without the floor it behaves
// exactly like the version-2 file.
TEST(DatabaseIo, VersionOneFilesLoadWithAnEmptyHistory) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  LoopDetector a(voc, options());
  for (int i = 0; i < 45; ++i) a.process(kfs[i]);
  const std::string v2 = outPath("v2.bowgdb");
  a.save(v2);
  const std::string bytes = readBytes(v2);
  // The history closes the version-2 payload: u32 count + count x 3 f64;
  // version 3 adds two i32 missed-query counters, the odometers (u32
  // count + 45 f64) and two query odometers (f64), version 4 the other
  // temporal hypotheses (u32 count, 0 with one hypothesis), version 5 the
  // entries' scale factors (u32 count + 45 f32), version 6 the place links
  // (u32 count + 45 u32), version 7 the odometry positions, version 8 the
  // searchable flags, version 9 the missions, version 10 the headings, then
  // the u64
  // checksum. 44 keyframes had a previous one; the window is 50.
  const std::size_t history = 4 + 44 * 24 + 2 * 4 + 4 + 45 * 8 + 2 * 8 + 4 + 4 + 45 * 4 + 4 +
                              45 * 4 + fromVersion7Bytes(45);
  const std::string v1 = outPath("v1.bowgdb");
  writeBytes(v1, asVersion(bytes, history, 1));
  LoopDetector b(voc, options());
  b.load(v1);
  EXPECT_EQ(b.database().size(), 45u);
  for (std::size_t i = 45; i < kfs.size(); ++i) {
    expectSameResult(a.process(kfs[i]), b.process(kfs[i]));
    expectSameCandidates(a, b);
  }
  // Versions beyond the current one are refused by number.
  writeBytes(v1, asVersion(bytes, history, 11));
  try {
    b.load(v1);
    ADD_FAILURE() << "version 11 accepted";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("unsupported version 11"), std::string::npos) << e.what();
  }
  std::remove(v1.c_str());
  std::remove(v2.c_str());
}

}  // namespace
}  // namespace bowg
