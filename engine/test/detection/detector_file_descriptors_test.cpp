// A loaded database leaves its descriptors in its file (descriptor_file.h):
// they are read back for verification and saving, the detector runs as the
// one that saved them, the memory they took is gone, and a file changed in
// place after the load is an error naming it, never other descriptors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "bowg/core/errors.h"
#include "detection/detector_file_runs.h"
#include "detection/verifier.h"

namespace bowg {
namespace {

using testing::expectSameCandidates;
using testing::expectSameResult;
using testing::keyframes;
using testing::options;
using testing::outPath;
using testing::readBytes;
using testing::vocabulary;
using testing::writeBytes;

// A detector run over the first 52 keyframes (mid-revisit) and its file.
struct Saved {
  std::shared_ptr<const Vocabulary> voc = vocabulary();
  std::vector<KeyframeInput> kfs = keyframes();
  LoopDetector a{voc, options()};
  std::string path;
  explicit Saved(const std::string& name) : path(outPath(name)) {
    for (int i = 0; i < 52; ++i) a.process(kfs[i]);
    a.save(path);
  }
};

std::string errorOf(const DatabaseEntry& e) {
  std::vector<Descriptor> read;
  try {
    e.descriptorsRead(&read);
  } catch (const std::exception& x) {
    return x.what();
  }
  return "";
}

TEST(DescriptorsOnDisk, ALoadedDatabaseReadsTheSavedDescriptorsBackAndHoldsNone) {
  Saved s("on_disk.bowgdb");
  LoopDetector b(s.voc, options());
  b.load(s.path);
  const Database& da = s.a.database();
  const Database& db = b.database();
  ASSERT_EQ(db.size(), da.size());
  std::size_t descriptor_bytes = 0;
  std::vector<Descriptor> read;
  for (EntryId id = 0; id < db.size(); ++id) {
    const DatabaseEntry& e = db.entry(id);
    ASSERT_TRUE(e.on_disk.file);
    EXPECT_TRUE(e.descriptors.empty());
    EXPECT_EQ(e.descriptorCount(), e.points.size());
    EXPECT_EQ(e.descriptorsRead(&read), da.entry(id).descriptors) << "entry " << id;
    descriptor_bytes += e.descriptorCount() * sizeof(Descriptor);
  }
  ASSERT_GT(descriptor_bytes, 0u);
  EXPECT_LE(db.memoryBytes() + descriptor_bytes, da.memoryBytes());
  // Saved again, it writes what the same bytes decoded in memory write.
  LoopDetector c(s.voc, options());
  c.adopt(LoopDetector::decode(readBytes(s.path), "the saved bytes", s.voc, options()));
  ASSERT_TRUE(c.database().entry(0).on_disk.file == nullptr);
  const std::string again = outPath("on_disk_again.bowgdb");
  const std::string in_memory = outPath("on_disk_in_memory.bowgdb");
  b.save(again);
  c.save(in_memory);
  EXPECT_TRUE(readBytes(again) == readBytes(in_memory)) << "the two saves differ";
  std::remove(again.c_str());
  std::remove(in_memory.c_str());
  std::remove(s.path.c_str());
}

// Replaced atomically (a save renames the new file over the old) or deleted,
// the file loaded stays the one read: the detector runs on as the saver.
TEST(DescriptorsOnDisk, AVerifiedCandidateIsReadFromDiskOnce) {
  Saved s("read_once.bowgdb");
  LoopDetector b(s.voc, options());
  b.load(s.path);
  const Database& db = b.database();
  const Database& da = s.a.database();
  query_steps::Verifier v(*s.voc, db, db.entry(0), CameraIntrinsics(), false);
  // Its correspondences, RANSAC and metric step: one read, the saved block.
  EXPECT_EQ(*v.match(30).descriptors, da.entry(30).descriptors);
  EXPECT_EQ(*v.features(30).descriptors, da.entry(30).descriptors);
  query_steps::EntryViewStorage storage;
  EXPECT_EQ(*v.entry(30, &storage).descriptors, da.entry(30).descriptors);
  EXPECT_EQ(v.blocksRead(), 1u);
  // Another candidate is read; the metric step's neighbours are read into
  // their own storage and leave the last candidate's block in place.
  EXPECT_EQ(*v.features(31).descriptors, da.entry(31).descriptors);
  EXPECT_EQ(v.blocksRead(), 2u);
  query_steps::EntryViewStorage neighbour;
  EXPECT_EQ(*v.entry(29, &neighbour).descriptors, da.entry(29).descriptors);
  EXPECT_EQ(v.blocksRead(), 3u);
  EXPECT_EQ(*v.match(31).descriptors, da.entry(31).descriptors);
  EXPECT_EQ(v.blocksRead(), 3u);
  std::remove(s.path.c_str());
}

TEST(DescriptorsOnDisk, AFileReplacedOrDeletedAfterTheLoadStaysTheOneRead) {
  Saved s("replaced.bowgdb");
  LoopDetector b(s.voc, options());
  b.load(s.path);
  const std::string other = outPath("replaced_other.bowgdb");
  writeBytes(other, std::string(4096, 'x'));
  ASSERT_EQ(std::rename(other.c_str(), s.path.c_str()), 0);
  int loops = 0;
  for (std::size_t i = 52; i < s.kfs.size(); ++i) {
    if (i == 58) ASSERT_EQ(std::remove(s.path.c_str()), 0);
    const LoopResult ra = s.a.process(s.kfs[i]);
    const LoopResult rb = b.process(s.kfs[i]);
    expectSameResult(ra, rb);
    expectSameCandidates(s.a, b);
    if (ra.status == LoopStatus::kLoopDetected && ra.match_id < 52) ++loops;
  }
  EXPECT_GT(loops, 0) << "the run should verify and accept loaded entries";
}

// Changed in place (cp over it, an editor) or shrunk: an error naming the
// file on the next read of the changed part; a save writes nothing.
TEST(DescriptorsOnDisk, AFileChangedInPlaceAfterTheLoadIsAnErrorNamingIt) {
  Saved s("changed.bowgdb");
  LoopDetector b(s.voc, options());
  b.load(s.path);
  const DatabaseEntry& first = b.database().entry(0);
  const DatabaseEntry& last = b.database().entry(b.database().size() - 1);
  std::string bytes = readBytes(s.path);
  // One descriptor byte of the first entry's first record, in place.
  const std::size_t at = static_cast<std::size_t>(first.on_disk.offset) + 6 * 4;
  bytes[at] = static_cast<char>(bytes[at] ^ 0x01);
  {
    std::FILE* f = std::fopen(s.path.c_str(), "r+b");
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(std::fseek(f, static_cast<long>(at), SEEK_SET), 0);
    ASSERT_EQ(std::fputc(bytes[at], f), static_cast<unsigned char>(bytes[at]));
    std::fclose(f);
  }
  const std::string changed = errorOf(first);
  EXPECT_NE(changed.find(s.path), std::string::npos) << changed;
  EXPECT_NE(changed.find("changed on disk"), std::string::npos) << changed;
  EXPECT_EQ(errorOf(last), "") << "an unchanged entry reads as loaded";
  const std::string out = outPath("changed_saved.bowgdb");
  std::remove(out.c_str());
  EXPECT_THROW(b.save(out), FormatError);
  EXPECT_NE(::access(out.c_str(), F_OK), 0) << "a failed save left a file";
  // Shrunk below the last entry's records: an I/O error naming the file.
  ASSERT_EQ(::truncate(s.path.c_str(), static_cast<off_t>(last.on_disk.offset)), 0);
  const std::string shrunk = errorOf(last);
  EXPECT_NE(shrunk.find(s.path), std::string::npos) << shrunk;
  EXPECT_NE(shrunk.find("shrunk"), std::string::npos) << shrunk;
  std::remove(s.path.c_str());
}

}  // namespace
}  // namespace bowg
