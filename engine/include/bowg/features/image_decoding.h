// Encoded image -> 8-bit grey, checked before it is decoded: the header's
// dimensions against max_image_pixels, the end marker (truncation), the
// format (image_header.h). The decoder runs only for an image that passed,
// so a refusal costs no more memory than the encoded bytes. Used for the
// compressed topic, bag messages and image files alike.
#pragma once

#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

#include "bowg/features/feature_options.h"
#include "bowg/features/image_check.h"
#include "bowg/features/image_header.h"

namespace bowg {

/// The header check alone: readImageHeader, then the header's width x height
/// against options.max_image_pixels (kTooLarge). Fills `*header` when given.
ImageCheck checkEncodedImage(const std::uint8_t* data, std::size_t size,
                             const FeatureOptions& options, ImageHeader* header = nullptr);

/// The grey image, or an empty Mat with `*check` saying why: the header
/// check, then kUndecodable when OpenCV fails or gives another size than the
/// header declared (a JPEG's EXIF orientation may swap the two).
cv::Mat decodeGreyImage(const std::uint8_t* data, std::size_t size, const FeatureOptions& options,
                        ImageCheck* check);

/// The image file at `path` as grey, read through BoundedFile (kImage): a
/// missing file, a directory, FIFO, device or a file over
/// BOWG_MAX_IMAGE_FILE_MB is kFileRefused (never blocks, never reads an
/// endless device), an empty file kEmpty, then decodeGreyImage.
cv::Mat readGreyImageFile(const std::string& path, const FeatureOptions& options,
                          ImageCheck* check);

}  // namespace bowg
