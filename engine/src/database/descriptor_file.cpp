#include "bowg/database/descriptor_file.h"

#include <stdexcept>
#include <utility>

#include "bowg/core/checksum.h"
#include "bowg/core/errors.h"
#include "core/little_endian.h"

namespace bowg {

DescriptorFile::DescriptorFile(BoundedFile file, std::size_t record_bytes,
                               std::size_t descriptor_offset)
    : file_(std::move(file)), record_bytes_(record_bytes), descriptor_offset_(descriptor_offset) {
  if (descriptor_offset + sizeof(Descriptor) > record_bytes) {
    throw std::invalid_argument("DescriptorFile: a 32-byte descriptor at byte " +
                                std::to_string(descriptor_offset) + " does not fit a record of " +
                                std::to_string(record_bytes) + " bytes");
  }
}

std::uint64_t DescriptorFile::blockChecksum(const char* records, std::size_t bytes) {
  return checksum64(records, bytes);
}

void DescriptorFile::read(std::uint64_t offset, std::uint32_t count, std::uint64_t checksum,
                          std::vector<Descriptor>* out) const {
  std::vector<char> block(static_cast<std::size_t>(count) * record_bytes_);
  file_.readAt(block.data(), block.size(), offset);
  if (blockChecksum(block.data(), block.size()) != checksum) {
    throw FormatError("database file '" + path() + "' changed on disk since it was loaded: the " +
                      std::to_string(count) + " features at byte " + std::to_string(offset) +
                      " are not the ones loaded (replace a loaded database atomically, or "
                      "load it again)");
  }
  out->resize(count);
  for (std::uint32_t f = 0; f < count; ++f) {
    const auto* p = reinterpret_cast<const unsigned char*>(block.data()) +
                    static_cast<std::size_t>(f) * record_bytes_ + descriptor_offset_;
    for (std::uint64_t& word : (*out)[f].bits) {
      word = loadLittleEndian<std::uint64_t>(p);
      p += 8;
    }
  }
}

}  // namespace bowg
