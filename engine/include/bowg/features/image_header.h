// The dimensions of an encoded image read from its header, before anything
// is decoded: a 850 kB PNG can declare 30000 x 30000 pixels, and a decoder
// allocates them before it reads the first row. Also tells a file that was
// cut short (its end marker missing) from a whole one.
//
// Formats read: PNG, JPEG, BMP and binary PNM (P4, P5, P6): what cameras,
// image folders and image_transport's compressed topic carry. Everything
// else OpenCV's imdecode would take (TIFF, WebP, GIF, JPEG 2000, OpenEXR,
// HDR, PFM, Sun raster, ASCII PNM, PAM) is refused as unsupported_format:
// each would need its own header parser, and no camera stream uses them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "bowg/features/image_check.h"

namespace bowg {

struct ImageHeader {
  std::string format;  ///< "PNG", "JPEG", "BMP", "PNM"
  std::uint64_t width = 0;
  std::uint64_t height = 0;
};

/// Reads the header of `size` bytes at `data`: kEmpty, kUnsupportedFormat,
/// kBadHeader (no readable dimensions, or a zero one) or kTruncated (the
/// format's end marker or pixel data missing); ok with `*header` filled.
ImageCheck readImageHeader(const std::uint8_t* data, std::size_t size, ImageHeader* header);

}  // namespace bowg
