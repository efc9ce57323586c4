// The classification of bad images: stable reason names, counts by reason,
// and the raw-buffer layout check (a mono16 image with an odd step is
// malformed, not a processing error).
#include "bowg/features/image_check.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace bowg {
namespace {

TEST(ImageCheck, EveryReasonHasItsOwnStableName) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < kImageProblemCount; ++i) {
    names.insert(imageProblemName(static_cast<ImageProblem>(i)));
  }
  EXPECT_EQ(names.size(), kImageProblemCount);
  EXPECT_STREQ(imageProblemName(ImageProblem::kTruncated), "truncated");
  EXPECT_STREQ(imageProblemName(ImageProblem::kTooLarge), "too_large");
  EXPECT_STREQ(imageProblemName(ImageProblem::kMalformed), "malformed");
  EXPECT_STREQ(imageProblemName(ImageProblem::kFileRefused), "file_refused");
}

TEST(ImageCheck, MessagesAndExceptionsCarryTheReason) {
  const ImageCheck c = imageRefusal(ImageProblem::kTruncated, "JPEG without EOI");
  EXPECT_FALSE(c.ok());
  EXPECT_EQ(c.message(), "truncated: JPEG without EOI");
  const BadImage e(c);
  EXPECT_EQ(e.problem(), ImageProblem::kTruncated);
  EXPECT_STREQ(e.what(), "truncated: JPEG without EOI");
  EXPECT_TRUE(ImageCheck().ok());
}

TEST(ImageCheck, CountsByReason) {
  ImageProblemCounts counts;
  EXPECT_EQ(counts.summary(), "");
  counts.add(ImageProblem::kTruncated);
  counts.add(ImageProblem::kTooLarge);
  counts.add(ImageProblem::kTruncated);
  EXPECT_EQ(counts.count(ImageProblem::kTruncated), 2u);
  EXPECT_EQ(counts.total(), 3u);
  EXPECT_EQ(counts.summary(), "2 truncated, 1 too_large");
}

TEST(ImageCheck, RawLayoutOfAGoodImageIsAccepted) {
  EXPECT_TRUE(checkRawLayout(64, 48, 64, 64 * 48, 1, 1).ok());
  EXPECT_TRUE(checkRawLayout(64, 48, 130, 130 * 48, 2, 2).ok());  // padded mono16 rows
  EXPECT_TRUE(checkRawLayout(64, 48, 193, 193 * 48, 3, 1).ok());  // odd step, 8-bit channels
}

TEST(ImageCheck, Mono16WithAnOddStepIsMalformed) {
  const ImageCheck c = checkRawLayout(64, 48, 129, 129 * 48, 2, 2);
  EXPECT_EQ(c.problem, ImageProblem::kMalformed) << c.message();
  EXPECT_NE(c.detail.find("step 129"), std::string::npos) << c.detail;
}

TEST(ImageCheck, ShortStepsShortDataAndEmptyImagesAreRefused) {
  EXPECT_EQ(checkRawLayout(64, 48, 63, 64 * 48, 1, 1).problem, ImageProblem::kMalformed);
  EXPECT_EQ(checkRawLayout(64, 48, 64, 100, 1, 1).problem, ImageProblem::kMalformed);
  EXPECT_EQ(checkRawLayout(0, 48, 64, 64 * 48, 1, 1).problem, ImageProblem::kBadHeader);
  // 32-bit fields at their maximum: no overflow, just refused.
  EXPECT_EQ(checkRawLayout(0xffffffffu, 0xffffffffu, 0xffffffffu, 10, 4, 1).problem,
            ImageProblem::kMalformed);
}

}  // namespace
}  // namespace bowg
