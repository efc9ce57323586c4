// Every vocabulary loader: the first byte picks the format (0: detection
// from the content, as loadVocabulary(path) does; 1..7 one format each), the
// rest is the file. Documented outcomes: a valid Vocabulary, FormatError or
// IoError. Anything else (another exception, a crash, a hang, a sanitizer
// report) is a finding.
#include <cstddef>
#include <cstdint>

#include "bowg/core/errors.h"
#include "bowg/vocabulary/vocabulary.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int selector = data[0] % 8;
  const std::string path = bowg::fuzz::writeInput(data + 1, size - 1, ".voc");
  try {
    const bowg::Vocabulary v =
        selector == 0 ? bowg::loadVocabulary(path)
                      : bowg::loadVocabulary(path, static_cast<bowg::VocabularyFormat>(selector - 1));
    // A vocabulary that loads must be usable.
    bowg::BowVector bow;
    v.transform(std::vector<bowg::Descriptor>(3), &bow);
  } catch (const bowg::FormatError&) {
  } catch (const bowg::IoError&) {
  }
  return 0;
}
