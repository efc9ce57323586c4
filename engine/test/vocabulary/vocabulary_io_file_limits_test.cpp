// Vocabulary files refused before they are read, whatever their format: a
// FIFO, a directory, a device, a huge sparse file; a gzip bomb; headers that
// do not match the file's size; k and L outside the ranges every loader
// accepts. Each refusal names the file and the reason, within 1 s and
// 100 MB (special_files.h).
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "bowg/core/errors.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "core/resealed_checksum.h"
#include "core/special_files.h"
#include "synthetic_vocabulary.h"
#include "vocabulary/vocabulary_files.h"

namespace bowg {
namespace {

using testing::expectRefusedFast;
using testing::kCases;
using testing::outPath;
using testing::readAll;
using testing::writeAll;

const std::uint64_t kGiB = 1ull << 30;

std::string dir() { return std::string(BOWG_TEST_OUTPUT_DIR) + "/vocabulary_file_limits"; }

TEST(VocabularyFileLimits, SpecialFilesAreRefusedByEveryLoader) {
  for (const auto& c : kCases) {
    SCOPED_TRACE(c.file);
    const std::string suffix = std::string("_") + c.file;
    const auto files = testing::makeSpecialFiles(dir(), suffix, 3 * kGiB, "more than the limit");
    testing::expectSpecialFilesRefused(
        files, [&](const std::string& path) { loadVocabulary(path, c.format); });
  }
  // Format detection opens the file first: it refuses them as well.
  const auto files = testing::makeSpecialFiles(dir(), ".bin", 3 * kGiB, "more than the limit");
  testing::expectSpecialFilesRefused(files, [](const std::string& path) { loadVocabulary(path); });
}

// A gzip file of `members` copies of one member that inflates to 16 MiB of
// `fill`: small on disk (gzip readers read concatenated members as one).
std::string gzipBomb(const std::string& name, char fill, int members) {
  std::string plain(16u << 20, fill);
  plain.replace(0, 12, "vocabulary:\n");
  uLongf size = compressBound(static_cast<uLong>(plain.size())) + 64;
  std::string member(size, '\0');
  z_stream z;
  std::memset(&z, 0, sizeof z);
  EXPECT_EQ(deflateInit2(&z, 9, Z_DEFLATED, 15 + 16 /* gzip */, 9, Z_RLE), Z_OK);
  z.next_in = reinterpret_cast<Bytef*>(&plain[0]);
  z.avail_in = static_cast<uInt>(plain.size());
  z.next_out = reinterpret_cast<Bytef*>(&member[0]);
  z.avail_out = static_cast<uInt>(member.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  member.resize(z.total_out);
  deflateEnd(&z);
  std::string bytes;
  for (int i = 0; i < members; ++i) bytes += member;
  const std::string path = outPath(name);
  writeAll(path, bytes);
  return path;
}

TEST(VocabularyFileLimits, GzipBombsAreRefusedWhileInflating) {
  // 1.5 GiB of blanks in 1.5 MB: refused by its ratio, long before the
  // decompressed-size limit.
  const std::string blanks = gzipBomb("bomb_blanks.yml.gz", ' ', 96);
  EXPECT_LT(readAll(blanks).size(), 4u << 20);
  expectRefusedFast(blanks, "compression bomb", [](const std::string& p) { loadVocabulary(p); });
  // Zeros (head -c 3G /dev/zero | gzip): not text, refused at the first chunk.
  const std::string zeros = gzipBomb("bomb_zeros.yml.gz", '\0', 96);
  expectRefusedFast(zeros, "NUL byte", [](const std::string& p) { loadVocabulary(p); });
  // The decompressed size is bounded by the limit, named with its variable.
  ::setenv("BOWG_MAX_VOCABULARY_MB", "8", 1);
  expectRefusedFast(blanks,
                    "more than the limit of 8.0 MiB (raise it with the environment "
                    "variable BOWG_MAX_VOCABULARY_MB",
                    [](const std::string& p) { loadVocabulary(p); });
  ::unsetenv("BOWG_MAX_VOCABULARY_MB");
}

TEST(VocabularyFileLimits, RealGzippedVocabulariesInflateWellBelowTheBombRatio) {
  // A DBoW3 YAML written by us, gzipped: the ratio guard must never refuse
  // an honest vocabulary (the shared ones are checked in the shared tests).
  const Vocabulary v = testing::makeSyntheticVocabulary(10, 4, 3);
  for (const auto format : {VocabularyFormat::kDbow3Yaml, VocabularyFormat::kDbow2BriefYaml}) {
    const std::string path = outPath("ratio_" + toString(format) + ".yml.gz");
    saveVocabulary(v, path, format);
    EXPECT_EQ(loadVocabulary(path).fingerprint(), v.fingerprint());
  }
}

// `header` followed by zeros up to `size` bytes (sparse: nothing on disk).
std::string headerThenHole(const std::string& name, const std::string& header, std::uint64_t size) {
  const std::string path = outPath(name);
  writeAll(path, header);
  EXPECT_EQ(::truncate(path.c_str(), static_cast<off_t>(size)), 0);
  return path;
}

std::string le32(std::uint32_t v) {
  std::string s;
  for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>(v >> (8 * i)));
  return s;
}

TEST(VocabularyFileLimits, HeadersThatDoNotMatchTheFileSizeAreRefusedBeforeTheBody) {
  const std::uint64_t size = 900ull << 20;  // under the 1 GiB limit
  const auto load = [](const std::string& p) { loadVocabulary(p); };
  // VINS: k 10, L 6, 10 nodes and 10 words, then 900 MB of nothing.
  std::string vins = le32(10) + le32(6) + le32(0) + le32(0) + le32(10) + le32(10);
  expectRefusedFast(headerThenHole("hole_brief.bin", vins, size), "does not match the header",
                    load);
  // DBoW3: magic, uncompressed, 11 nodes, k 10, L 6.
  std::string dbow3;
  for (int i = 0; i < 8; ++i) dbow3.push_back(static_cast<char>(88877711233ull >> (8 * i)));
  dbow3 += std::string(1, '\0') + le32(11) + le32(10) + le32(6) + le32(0) + le32(0);
  expectRefusedFast(headerThenHole("hole.dbow3", dbow3, size), "does not fit the file size", load);
  // Text formats: a valid first line, then zeros.
  expectRefusedFast(headerThenHole("hole_ORBvoc.txt", "10 6 0 0\n", size), "NUL byte", load);
  expectRefusedFast(headerThenHole("hole.yml", "vocabulary:\n", size), "NUL byte", load);
  // A k out of range is refused from the header alone.
  expectRefusedFast(headerThenHole("k_ORBvoc.txt", "1001 6 0 0\n", size), "k = 1001", load);
}

TEST(VocabularyFileLimits, BowgvocKAndLOutsideTheLoadableRangesAreNeitherReadNorWritten) {
  const Vocabulary v = testing::makeSyntheticVocabulary(2, 2);
  saveVocabulary(v, outPath("range.bowgvoc"));
  const std::string good = readAll(outPath("range.bowgvoc"));
  struct Field {
    std::size_t offset;
    std::uint32_t value;
    const char* reason;
  };
  for (const Field& f : {Field{12, 1001, "k = 1001 out of range [2, 1000]"},
                         Field{16, 101, "L = 101 out of range [1, 100]"}}) {
    std::string bytes = good;
    const std::string v32 = le32(f.value);
    bytes.replace(f.offset, 4, v32);
    testing::resealChecksum(&bytes);
    writeAll(outPath("range_bad.bowgvoc"), bytes);
    expectRefusedFast(outPath("range_bad.bowgvoc"), f.reason,
                      [](const std::string& p) { loadVocabulary(p); });
  }
  // What no loader reads is not written either, in any format.
  const Vocabulary wide = testing::makeSyntheticVocabulary(1001, 1);
  for (const auto& c : kCases) {
    EXPECT_THROW(saveVocabulary(wide, outPath(std::string("wide_") + c.file), c.format),
                 std::invalid_argument)
        << c.file;
  }
}

TEST(VocabularyFileLimits, NumbersInMessagesAreReadable) {
  saveVocabulary(testing::makeSyntheticVocabulary(2, 2), outPath("weight_brief.bin"),
                 VocabularyFormat::kVinsBinary);
  std::string bytes = readAll(outPath("weight_brief.bin"));
  const double weight = -1e300;
  std::memcpy(&bytes[24 + 8], &weight, 8);  // node 1's weight
  writeAll(outPath("weight_brief.bin"), bytes);
  try {
    loadVocabulary(outPath("weight_brief.bin"));
    FAIL() << "a negative weight was accepted";
  } catch (const FormatError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("negative weight (-1e+300)"), std::string::npos) << message;
    EXPECT_LT(message.size(), 200u) << message;
  }
}

}  // namespace
}  // namespace bowg
