// Header parsers of the encoded formats read (see image_header.h). Every
// read is bounds-checked against the buffer: the input is untrusted.
#include "bowg/features/image_header.h"

#include <cstring>

namespace bowg {
namespace {

std::uint32_t be16(const std::uint8_t* p) { return (std::uint32_t(p[0]) << 8) | p[1]; }
std::uint32_t be32(const std::uint8_t* p) { return (be16(p) << 16) | be16(p + 2); }
std::uint32_t le16(const std::uint8_t* p) { return (std::uint32_t(p[1]) << 8) | p[0]; }
std::uint32_t le32(const std::uint8_t* p) { return (le16(p + 2) << 16) | le16(p); }

bool startsWith(const std::uint8_t* data, std::size_t size, const char* magic, std::size_t n) {
  return size >= n && std::memcmp(data, magic, n) == 0;
}

ImageCheck badHeader(const std::string& format, const std::string& what) {
  return imageRefusal(ImageProblem::kBadHeader, format + " header: " + what);
}

ImageCheck truncated(const std::string& what) {
  return imageRefusal(ImageProblem::kTruncated, what);
}

ImageCheck dimensions(const char* format, std::uint64_t width, std::uint64_t height,
                      ImageHeader* header) {
  if (width == 0 || height == 0) {
    return badHeader(format, "zero width or height (" + std::to_string(width) + " x " +
                                 std::to_string(height) + ")");
  }
  header->format = format;
  header->width = width;
  header->height = height;
  return ImageCheck();
}

// PNG: the signature, then the IHDR chunk first (length 13); a whole file
// ends with the IEND chunk (libpng ignores bytes after it).
ImageCheck readPng(const std::uint8_t* d, std::size_t n, ImageHeader* header) {
  if (n < 33 || be32(d + 8) != 13 || std::memcmp(d + 12, "IHDR", 4) != 0) {
    return badHeader("PNG", "no IHDR chunk after the signature");
  }
  const std::uint32_t width = be32(d + 16), height = be32(d + 20);
  if (width > 0x7fffffffu || height > 0x7fffffffu) {
    return badHeader("PNG", "width or height above 2^31 - 1");
  }
  const std::size_t tail = n < 1024 ? n : 1024;
  bool iend = false;
  for (std::size_t i = n - tail; i + 8 <= n && !iend; ++i) {
    iend = std::memcmp(d + i, "IEND", 4) == 0 && i >= 37;
  }
  if (!iend) return truncated("PNG without its IEND chunk");
  return dimensions("PNG", width, height, header);
}

bool isStartOfFrame(std::uint8_t marker) {
  // SOF0..SOF15 but DHT (C4), JPG (C8) and DAC (CC), which share the range.
  return marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc;
}

// JPEG: walks the marker segments from SOI to the first start-of-frame,
// which holds the dimensions; a whole file ends with EOI (FF D9), possibly
// followed by zero padding.
ImageCheck readJpeg(const std::uint8_t* d, std::size_t n, ImageHeader* header) {
  std::size_t end = n;
  while (end > 2 && d[end - 1] == 0x00) --end;
  if (end < 4 || d[end - 2] != 0xff || d[end - 1] != 0xd9) {
    return truncated("JPEG without its end-of-image marker (FF D9)");
  }
  std::size_t pos = 2;
  while (pos < end) {
    if (d[pos] != 0xff) return badHeader("JPEG", "no marker at byte " + std::to_string(pos));
    while (pos < end && d[pos] == 0xff) ++pos;  // fill bytes
    if (pos >= end) break;
    const std::uint8_t marker = d[pos++];
    if (marker == 0x01 || (marker >= 0xd0 && marker <= 0xd8)) continue;  // no length
    if (marker == 0xd9 || marker == 0xda) break;  // end of image or scan before a frame
    if (pos + 2 > end) break;
    const std::size_t length = be16(d + pos);
    if (length < 2 || pos + length > end) {
      return badHeader("JPEG", "segment at byte " + std::to_string(pos) + " runs past the data");
    }
    if (isStartOfFrame(marker)) {
      if (length < 8) return badHeader("JPEG", "start-of-frame segment too short");
      const std::uint32_t height = be16(d + pos + 3), width = be16(d + pos + 5);
      // A zero height would be given by a DNL marker after the first scan.
      return dimensions("JPEG", width, height, header);
    }
    pos += length;
  }
  return badHeader("JPEG", "no start-of-frame segment before the image data");
}

// BMP: the file header, then the info header (12 bytes: OS/2 core, 16-bit
// dimensions; 40 or more: Windows, signed 32-bit, a negative height is a
// top-down image). Uncompressed data is checked to be all there.
ImageCheck readBmp(const std::uint8_t* d, std::size_t n, ImageHeader* header) {
  if (n < 26) return badHeader("BMP", "shorter than its headers");
  const std::uint32_t info = le32(d + 14), offset = le32(d + 10);
  std::uint64_t width, height, bits, compression = 0;
  if (info == 12) {
    width = le16(d + 18);
    height = le16(d + 20);
    bits = le16(d + 24);
  } else if (info >= 40 && n >= 34) {
    const std::int32_t w = static_cast<std::int32_t>(le32(d + 18));
    const std::int32_t h = static_cast<std::int32_t>(le32(d + 22));
    if (w <= 0 || h == INT32_MIN) return badHeader("BMP", "invalid width or height");
    width = std::uint64_t(w);
    height = h < 0 ? std::uint64_t(-std::int64_t(h)) : std::uint64_t(h);
    bits = le16(d + 28);
    compression = le32(d + 30);
  } else {
    return badHeader("BMP", "unknown info header of " + std::to_string(info) + " bytes");
  }
  if (width == 0 || height == 0) return dimensions("BMP", width, height, header);
  if (compression == 0 && bits > 0 && bits <= 32) {
    // row * height > n - offset, without overflowing 64 bits.
    const std::uint64_t row = (width * bits + 31) / 32 * 4;
    if (offset > n || row > (n - offset) / height) {
      return truncated("BMP with less pixel data than its header declares");
    }
  }
  return dimensions("BMP", width, height, header);
}

// Binary PNM: "P4|P5|P6", width, height (and maxval but for P4) as decimal
// numbers separated by whitespace or comments, one whitespace, the data.
bool pnmNumber(const std::uint8_t* d, std::size_t n, std::size_t* pos, std::uint64_t* value) {
  for (;;) {
    while (*pos < n && std::strchr(" \t\r\n\v\f", d[*pos]) && d[*pos] != 0) ++*pos;
    if (*pos < n && d[*pos] == '#') {
      while (*pos < n && d[*pos] != '\n') ++*pos;
      continue;
    }
    break;
  }
  std::size_t digits = 0;
  *value = 0;
  while (*pos < n && d[*pos] >= '0' && d[*pos] <= '9') {
    if (++digits > 9) return false;  // no real image needs 10 digits
    *value = *value * 10 + (d[(*pos)++] - '0');
  }
  return digits > 0;
}

ImageCheck readPnm(const std::uint8_t* d, std::size_t n, ImageHeader* header) {
  const char kind = static_cast<char>(d[1]);
  std::size_t pos = 2;
  std::uint64_t width, height, maxval = 1;
  if (!pnmNumber(d, n, &pos, &width) || !pnmNumber(d, n, &pos, &height) ||
      (kind != '4' && !pnmNumber(d, n, &pos, &maxval))) {
    return badHeader("PNM", "no width, height and maximum value");
  }
  if (maxval == 0 || maxval > 65535) return badHeader("PNM", "maximum value out of range");
  if (width == 0 || height == 0) return dimensions("PNM", width, height, header);
  const std::uint64_t sample = maxval > 255 ? 2 : 1;
  const std::uint64_t row = kind == '4' ? (width + 7) / 8 : width * sample * (kind == '6' ? 3 : 1);
  if (pos + 1 + row * height > n) return truncated("PNM with less pixel data than its header");
  return dimensions("PNM", width, height, header);
}

// Formats OpenCV decodes that are not read here, named in the refusal.
const char* otherFormat(const std::uint8_t* d, std::size_t n) {
  if (startsWith(d, n, "II*\0", 4) || startsWith(d, n, "MM\0*", 4)) return "TIFF";
  if (startsWith(d, n, "RIFF", 4) && n >= 12 && std::memcmp(d + 8, "WEBP", 4) == 0) return "WebP";
  if (startsWith(d, n, "GIF8", 4)) return "GIF";
  if (startsWith(d, n, "\0\0\0\x0cjP  ", 8) || startsWith(d, n, "\xff\x4f\xff\x51", 4)) {
    return "JPEG 2000";
  }
  if (startsWith(d, n, "\x76\x2f\x31\x01", 4)) return "OpenEXR";
  if (startsWith(d, n, "#?RADIANCE", 10) || startsWith(d, n, "#?RGBE", 6)) return "Radiance HDR";
  if (startsWith(d, n, "\x59\xa6\x6a\x95", 4)) return "Sun raster";
  if (n >= 2 && d[0] == 'P' && std::strchr("1237Ff", d[1]) && d[1] != 0) {
    return "ASCII PNM, PAM or PFM";
  }
  return nullptr;
}

}  // namespace

ImageCheck readImageHeader(const std::uint8_t* data, std::size_t size, ImageHeader* header) {
  if (size == 0) return imageRefusal(ImageProblem::kEmpty, "no image data");
  if (startsWith(data, size, "\x89PNG\r\n\x1a\n", 8)) return readPng(data, size, header);
  if (startsWith(data, size, "\xff\xd8\xff", 3)) return readJpeg(data, size, header);
  if (startsWith(data, size, "BM", 2)) return readBmp(data, size, header);
  if (size >= 2 && data[0] == 'P' && data[1] >= '4' && data[1] <= '6') {
    return readPnm(data, size, header);
  }
  if (const char* other = otherFormat(data, size)) {
    return imageRefusal(ImageProblem::kUnsupportedFormat,
                        std::string(other) + " (read: PNG, JPEG, BMP, binary PNM)");
  }
  return imageRefusal(ImageProblem::kUnsupportedFormat,
                      "not a PNG, JPEG, BMP or binary PNM image (" + std::to_string(size) +
                          " bytes)");
}

}  // namespace bowg
