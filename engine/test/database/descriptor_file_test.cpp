// Descriptors left on disk: an entry's block of feature records read back,
// its descriptors assembled little-endian as the file is written, and the
// block checked against the checksum taken at load.
#include "bowg/database/descriptor_file.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

#include "bowg/core/errors.h"

namespace bowg {
namespace {

// 3 prefix bytes, then two records of 40 bytes: 4 bytes of other fields
// (0xee), a descriptor whose byte j is `first + j`, 4 more bytes (0xdd).
const std::size_t kRecord = 40;
const std::size_t kAt = 4;

std::string records() {
  std::string bytes = "xyz";
  for (int r = 0; r < 2; ++r) {
    bytes += std::string(4, '\xee');
    for (int j = 0; j < 32; ++j) bytes += static_cast<char>(1 + 32 * r + j);
    bytes += std::string(4, '\xdd');
  }
  return bytes;
}

std::string writeRecords(const std::string& name) {
  const std::string dir = std::string(BOWG_TEST_OUTPUT_DIR) + "/descriptor_file_test";
  EXPECT_EQ(std::system(("mkdir -p '" + dir + "'").c_str()), 0);
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << records();
  return path;
}

DescriptorFile open(const std::string& path) {
  return DescriptorFile(BoundedFile(path, FileKind::kDatabase), kRecord, kAt);
}

TEST(DescriptorFile, ReadsABlocksDescriptorsLittleEndian) {
  const std::string path = writeRecords("two.bin");
  const std::string bytes = records();
  const std::uint64_t sum = DescriptorFile::blockChecksum(bytes.data() + 3, 2 * kRecord);
  std::vector<Descriptor> read;
  open(path).read(3, 2, sum, &read);
  ASSERT_EQ(read.size(), 2u);
  // Bytes 1..8 of the first record: 0x0807060504030201; the second record
  // starts at 33 = 0x21.
  EXPECT_EQ(read[0].bits[0], 0x0807060504030201ull);
  EXPECT_EQ(read[0].bits[3], 0x201f1e1d1c1b1a19ull);
  EXPECT_EQ(read[1].bits[0], 0x2827262524232221ull);
  // One record alone, at its own offset and checksum.
  open(path).read(3 + kRecord, 1,
                  DescriptorFile::blockChecksum(bytes.data() + 3 + kRecord, kRecord), &read);
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].bits[0], 0x2827262524232221ull);
}

TEST(DescriptorFile, ABlockThatIsNotTheOneLoadedIsAnErrorNamingTheFile) {
  const std::string path = writeRecords("changed.bin");
  const std::string bytes = records();
  const std::uint64_t sum = DescriptorFile::blockChecksum(bytes.data() + 3, 2 * kRecord);
  const DescriptorFile file = open(path);
  {
    std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(3 + kRecord + kAt);
    f.put('\x7f');  // one descriptor byte of the second record, in place
  }
  std::vector<Descriptor> read;
  try {
    file.read(3, 2, sum, &read);
    FAIL() << "a changed block was read";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("changed on disk"), std::string::npos) << e.what();
  }
  // The first record alone is unchanged.
  file.read(3, 1, DescriptorFile::blockChecksum(bytes.data() + 3, kRecord), &read);
  EXPECT_EQ(read[0].bits[0], 0x0807060504030201ull);
  // Past the end: the file cannot be read there.
  EXPECT_THROW(file.read(3 + kRecord, 2, sum, &read), IoError);
}

TEST(DescriptorFile, RefusesARecordTheDescriptorDoesNotFit) {
  const std::string path = writeRecords("layout.bin");
  EXPECT_THROW(DescriptorFile(BoundedFile(path, FileKind::kDatabase), 35, 4),
               std::invalid_argument);
  EXPECT_NO_THROW(DescriptorFile(BoundedFile(path, FileKind::kDatabase), 36, 4));
}

}  // namespace
}  // namespace bowg
