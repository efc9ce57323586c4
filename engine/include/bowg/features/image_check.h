// The one classification of a bad input image, shared by every path that
// reads images: the nodelet's raw and compressed topics, image folders and
// bags of the offline tools, the vocabulary trainer. Each reason has a stable
// short name (counters, diagnostics, warnings) and every refusal a message
// saying what is wrong, so the same bad frame is counted the same way
// wherever it arrives.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace bowg {

/// Why an image is refused.
enum class ImageProblem {
  kNone,
  kEmpty,              ///< "empty": no data at all (empty file or message)
  kFileRefused,        ///< "file_refused": missing, not a regular file, over the file limit
  kUnsupportedFormat,  ///< "unsupported_format": an encoding or file format not read here
  kBadHeader,          ///< "bad_header": the header cannot be read (no dimensions)
  kTruncated,          ///< "truncated": JPEG without EOI, PNG without IEND, short BMP/PNM
  kTooLarge,           ///< "too_large": width x height over max_image_pixels
  kUndecodable,        ///< "undecodable": the header is fine, the decoder refuses the rest
  kMalformed,          ///< "malformed": a raw image whose step, size or type does not fit
};
constexpr std::size_t kImageProblemCount = 9;

/// The stable short name ("truncated"; "ok" for kNone).
const char* imageProblemName(ImageProblem problem);

/// The verdict on one image: a reason and what exactly is wrong.
struct ImageCheck {
  ImageProblem problem = ImageProblem::kNone;
  std::string detail;  ///< "JPEG without its end-of-image marker (FF D9)"

  bool ok() const { return problem == ImageProblem::kNone; }
  /// "truncated: JPEG without its end-of-image marker (FF D9)".
  std::string message() const;
};

/// A refusal as an exception, for code paths that throw.
class BadImage : public std::invalid_argument {
 public:
  BadImage(ImageProblem problem, const std::string& detail);
  explicit BadImage(const ImageCheck& check) : BadImage(check.problem, check.detail) {}
  ImageProblem problem() const { return check_.problem; }
  /// The refusal as a verdict (what() is its message()).
  const ImageCheck& check() const { return check_; }

 private:
  ImageCheck check_;
};

/// A refusal of `problem` with `detail`.
inline ImageCheck imageRefusal(ImageProblem problem, const std::string& detail) {
  ImageCheck c;
  c.problem = problem;
  c.detail = detail;
  return c;
}

/// Refusals counted by reason.
class ImageProblemCounts {
 public:
  void add(ImageProblem problem);
  std::size_t count(ImageProblem problem) const;
  std::size_t total() const;
  /// "2 truncated, 1 too_large" ("" when nothing was counted).
  std::string summary() const;

 private:
  std::array<std::size_t, kImageProblemCount> counts_{};
};

/// The layout of a raw (uncompressed) image buffer: kMalformed when a row is
/// longer than the step, the step is not a whole number of channel values
/// (a mono16 image with an odd step), or the data is shorter than height x
/// step; kBadHeader for a zero width or height. `pixel_bytes` and
/// `channel_bytes` come from the encoding (mono16: 2 and 2, rgb8: 3 and 1).
ImageCheck checkRawLayout(std::uint64_t width, std::uint64_t height, std::uint64_t step,
                          std::uint64_t data_size, int pixel_bytes, int channel_bytes);

}  // namespace bowg
