// A load in two halves (LoopDetector::read, then adopt): reading touches no
// detector, a failed read changes nothing, adopt swaps the read file in and
// the detector then runs as one that load()ed it. A save's bytes
// (serialize) apart from their writing.
#include "bowg/core/atomic_file.h"
#include "detector_file_runs.h"

namespace bowg {
namespace {

using testing::keyframes;
using testing::options;
using testing::outPath;
using testing::vocabulary;

// A detector saved after 40 keyframes (the forward pass).
std::string savedForwardPass(const std::shared_ptr<const Vocabulary>& voc,
                             const std::vector<KeyframeInput>& kfs, const std::string& name) {
  LoopDetector a(voc, options());
  for (int i = 0; i < 40; ++i) a.process(kfs[i]);
  const std::string path = outPath(name);
  a.save(path);
  return path;
}

TEST(SavedDetector, ReadTouchesNoDetectorAndAdoptSwapsItIn) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  const std::string path = savedForwardPass(voc, kfs, "split.bowgdb");
  LoopDetector running(voc, options());
  for (int i = 0; i < 10; ++i) running.process(kfs[i]);

  SavedDetector saved = LoopDetector::read(path, voc, running.options());
  EXPECT_EQ(saved.size(), 40u);
  // The running detector still has its own keyframes and keeps processing.
  EXPECT_EQ(running.database().size(), 10u);
  running.process(kfs[10]);
  EXPECT_EQ(running.database().size(), 11u);

  running.adopt(std::move(saved));
  EXPECT_EQ(running.database().size(), 40u);
  // From here it runs as a detector that load()ed the file.
  LoopDetector loaded(voc, options());
  loaded.load(path);
  for (std::size_t i = 40; i < kfs.size(); ++i) {
    testing::expectSameResult(running.process(kfs[i]), loaded.process(kfs[i]));
  }
  std::remove(path.c_str());
}

// decode: the file's bytes read once serve detectors that each start on
// them, as read() of the file would; bad bytes are a FormatError naming
// their source.
TEST(SavedDetector, DecodedBytesRunAsTheReadFile) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  const std::string path = savedForwardPass(voc, kfs, "split_decode.bowgdb");
  const std::string bytes = testing::readBytes(path);
  std::remove(path.c_str());  // the bytes are all it takes
  LoopDetector first(voc, options()), second(voc, options());
  first.adopt(LoopDetector::decode(bytes, "the map", voc, options()));
  second.adopt(LoopDetector::decode(bytes, "the map", voc, options()));
  EXPECT_EQ(first.database().size(), 40u);
  LoopDetector loaded(voc, options());
  testing::writeBytes(path, bytes);
  loaded.load(path);
  std::remove(path.c_str());
  for (std::size_t i = 40; i < kfs.size(); ++i) {
    const LoopResult want = loaded.process(kfs[i]);
    testing::expectSameResult(first.process(kfs[i]), want);
    testing::expectSameResult(second.process(kfs[i]), want);
  }
  try {
    LoopDetector::decode(bytes.substr(0, bytes.size() - 9), "the map", voc, options());
    FAIL() << "truncated bytes decoded";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("the map"), std::string::npos) << e.what();
  }
}

TEST(SavedDetector, AFailedReadChangesNothing) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  const std::string path = savedForwardPass(voc, kfs, "split_corrupt.bowgdb");
  std::string bytes = testing::readBytes(path);
  bytes[bytes.size() / 2] ^= 0x5a;
  testing::writeBytes(path, bytes);
  LoopDetector running(voc, options());
  for (int i = 0; i < 10; ++i) running.process(kfs[i]);

  EXPECT_THROW(LoopDetector::read(path, voc, running.options()), FormatError);
  EXPECT_THROW(LoopDetector::read(outPath("split_missing.bowgdb"), voc, running.options()),
               IoError);
  EXPECT_EQ(running.database().size(), 10u);
  running.process(kfs[10]);  // the stamps continue from its own keyframes
  EXPECT_EQ(running.database().size(), 11u);
  std::remove(path.c_str());
}

TEST(SavedDetector, AdoptRefusesAFileReadForAnotherVocabularyAndKeepsTheState) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  const std::string path = savedForwardPass(voc, kfs, "split_other.bowgdb");
  LoopDetector running(voc, options());
  for (int i = 0; i < 10; ++i) running.process(kfs[i]);

  // The same words in another object: the file reads, but the detector's
  // entries would point at a vocabulary it does not use.
  const auto twin = vocabulary();
  SavedDetector other = LoopDetector::read(path, twin, running.options());
  EXPECT_THROW(running.adopt(std::move(other)), InvalidParameter);
  EXPECT_EQ(running.database().size(), 10u);

  SavedDetector saved = LoopDetector::read(path, voc, running.options());
  SavedDetector moved = std::move(saved);
  EXPECT_THROW(running.adopt(std::move(saved)), InvalidParameter);  // NOLINT: moved-from
  EXPECT_EQ(running.database().size(), 10u);
  running.adopt(std::move(moved));
  EXPECT_EQ(running.database().size(), 40u);
  std::remove(path.c_str());
}

TEST(SavedDetector, OptionsChangedBetweenReadAndAdoptApply) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  const std::string path = savedForwardPass(voc, kfs, "split_options.bowgdb");
  LoopDetectorOptions changed = options();
  changed.scoring = ScoringType::kBhattacharyya;
  changed.distribution.fan_bins = options().distribution.fan_bins + 2;

  LoopDetector running(voc, options());
  SavedDetector saved = LoopDetector::read(path, voc, running.options());
  running.setOptions(changed);  // live tuning while the file was read
  running.adopt(std::move(saved));
  LoopDetector loaded(voc, changed);
  loaded.load(path);
  for (std::size_t i = 40; i < kfs.size(); ++i) {
    testing::expectSameResult(running.process(kfs[i]), loaded.process(kfs[i]));
    testing::expectSameCandidates(running, loaded);
  }
  std::remove(path.c_str());
}

// serialize() is save() without the file: the same bytes, written later.
TEST(SavedDetector, SerializeGivesTheBytesSaveWrites) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  LoopDetector a(voc, options());
  for (int i = 0; i < 45; ++i) a.process(kfs[i]);
  const std::string saved = outPath("serialize_saved.bowgdb");
  a.save(saved);
  const std::string bytes = a.serialize();
  EXPECT_EQ(bytes, testing::readBytes(saved));
  const std::string written = outPath("serialize_written.bowgdb");
  writeFileAtomically(written, bytes);
  LoopDetector b(voc, options());
  b.load(written);
  EXPECT_EQ(b.database().size(), 45u);
  std::remove(saved.c_str());
  std::remove(written.c_str());
}

}  // namespace
}  // namespace bowg
