// The database file (LoopDetector::load) against the synthetic vocabulary
// the seed files were written with. Documented outcomes: the file loads and
// the detector then processes a keyframe (whatever state was restored), or
// FormatError / IoError with the detector untouched.
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "bowg/core/checksum.h"
#include "bowg/core/errors.h"
#include "bowg/database/database.h"
#include "bowg/detection/loop_detector.h"
#include "fuzz_file.h"
#include "seed_world.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::shared_ptr<const bowg::Vocabulary> vocabulary = bowg::fuzz::seedVocabulary();
  // The payload size (bytes 20..27) and the trailing checksum are made to
  // match whatever the fuzzer wrote, so that the inputs reach the content
  // checks behind them (a forged or buggy writer's file) instead of stopping
  // at the checksum. Files shorter than header + trailer are taken as they are.
  std::vector<std::uint8_t> bytes(data, data + size);
  if (size >= 36) {
    const std::uint64_t payload = size - 36;
    for (int i = 0; i < 8; ++i) bytes[20 + i] = static_cast<std::uint8_t>(payload >> (8 * i));
    const std::uint64_t sum = bowg::checksum64(reinterpret_cast<const char*>(bytes.data()), size - 8);
    for (int i = 0; i < 8; ++i) bytes[size - 8 + i] = static_cast<std::uint8_t>(sum >> (8 * i));
  }
  const std::string path = bowg::fuzz::writeInput(bytes.data(), bytes.size(), ".bowgdb");
  bowg::LoopDetector detector(vocabulary, bowg::fuzz::seedOptions());
  try {
    detector.load(path);
  } catch (const bowg::FormatError&) {
    return 0;
  } catch (const bowg::IoError&) {
    return 0;
  }
  // A restored state must carry on: one more keyframe, after the last stamp.
  bowg::KeyframeInput kf = bowg::fuzz::seedKeyframe(1);
  if (!detector.database().empty()) kf.stamp = detector.database().entries().back().stamp + 1.0;
  if (!std::isfinite(kf.stamp)) return 0;
  const double last = detector.database().lastOdometer();
  kf.odometer = std::isfinite(last) ? last + 0.1 : 0.0;
  detector.process(kf);
  return 0;
}
