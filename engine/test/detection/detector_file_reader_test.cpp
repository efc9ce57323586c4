// The detector file's Reader streamed from a file through a small window:
// the values, offsets and errors of the same bytes read in memory, across
// refills and for a need() larger than the window.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "bowg/core/errors.h"
#include "detection/detector_file_format.h"

namespace bowg {
namespace {

using detector_file::Reader;
using detector_file::Writer;

// 5 prefix bytes, then: u32 7, text "pipe", f64 -2.5, 3 pairs, 40 bytes of
// a block, u64 0x0102030405060708.
std::string content() {
  Writer w;
  w.bytes("head!", 5);
  w.u32(7);
  w.text("pipe");
  w.f64(-2.5);
  w.pairs({{1, 0.25}, {4, 0.5}, {9, 0.25}});
  for (int i = 0; i < 40; ++i) w.u8(static_cast<std::uint8_t>(i));
  w.u64(0x0102030405060708ull);
  return w.str();
}

std::string writeContent() {
  const std::string dir = std::string(BOWG_TEST_OUTPUT_DIR) + "/detector_file_reader_test";
  EXPECT_EQ(std::system(("mkdir -p '" + dir + "'").c_str()), 0);
  const std::string path = dir + "/content.bin";
  std::ofstream(path, std::ios::binary) << content();
  return path;
}

// Reads the content after the prefix; offsets are those of the file.
void readAll(Reader* r, std::uint64_t base) {
  EXPECT_EQ(r->u32("u32"), 7u);
  EXPECT_EQ(r->text("text"), "pipe");
  EXPECT_EQ(r->f64("f64"), -2.5);
  const auto pairs = r->pairs("pairs");
  ASSERT_EQ(pairs.size(), 3u);
  EXPECT_EQ(pairs[1].first, 4u);
  EXPECT_EQ(pairs[1].second, 0.5);
  // 5 + 4 + (4 + 4) + 8 + (4 + 3 * 12) = 65: the block's offset.
  EXPECT_EQ(r->offset(), base + 60);
  r->need(40, "block");  // larger than the streamed window: all at once
  const char* block = r->position();
  for (int i = 0; i < 40; ++i) ASSERT_EQ(block[i], static_cast<char>(i)) << i;
  r->skip(40, "block");
  EXPECT_EQ(r->u64("u64"), 0x0102030405060708ull);
  EXPECT_EQ(r->left(), 0u);
  EXPECT_THROW(r->u8("past the end"), FormatError);
}

TEST(DetectorFileReader, StreamedThroughASmallWindowReadsAsInMemory) {
  const std::string bytes = content();
  Reader in_memory("bytes", bytes.data() + 5, bytes.size() - 5);
  readAll(&in_memory, 0);
  const std::string path = writeContent();
  const BoundedFile file(path, FileKind::kDatabase);
  for (std::size_t window : {1, 3, 7, 16, 4096}) {
    SCOPED_TRACE("window " + std::to_string(window));
    Reader streamed(file, 5, bytes.size() - 5, window);
    readAll(&streamed, 5);
  }
}

TEST(DetectorFileReader, AStreamedRangeEndsWhereItIsToldAndNamesTheFile) {
  const std::string path = writeContent();
  const BoundedFile file(path, FileKind::kDatabase);
  Reader r(file, 5, 6, 4);  // u32 7, then 2 of the text's count bytes
  EXPECT_EQ(r.u32("u32"), 7u);
  try {
    r.text("text");
    FAIL() << "read past the range";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("truncated while reading text"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace bowg
