// Descriptors left on disk. A keyframe's 256-bit descriptors are 16 kB of
// the ~25 kB a database holds for it, and a query reads them only for the
// few candidates it verifies (Sec. III-D). A database loaded from a file
// (loadDetectorFile) therefore leaves them in that file, kept open, and
// reads an entry's back when it is verified or the database is saved: a
// network's archive of 10^6 keyframes then grows the resident set by
// 11.7 kB a keyframe instead of ~28 kB (docs/benchmarks.md). Each entry's
// block is checked on every read against the checksum taken when it was
// loaded, so a file changed in place since gives an error naming it, never
// other descriptors. A file replaced atomically (saved again, rename) or
// deleted stays readable: the open file is the one that was loaded.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bowg/core/bounded_file.h"
#include "bowg/core/types.h"

namespace bowg {

/// An open database file whose features are fixed-size records, each with
/// one descriptor (four little-endian u64) at the same offset.
class DescriptorFile {
 public:
  /// Throws std::invalid_argument when a descriptor does not fit a record.
  DescriptorFile(BoundedFile file, std::size_t record_bytes, std::size_t descriptor_offset);

  const std::string& path() const { return file_.path(); }
  /// The open file (its loader streams it from here).
  const BoundedFile& file() const { return file_; }
  std::size_t recordBytes() const { return record_bytes_; }

  /// The checksum an entry's block of `count` records is checked against
  /// (checksum64 of its bytes).
  static std::uint64_t blockChecksum(const char* records, std::size_t bytes);

  /// The descriptors of the `count` records at byte `offset`, into `out`
  /// (resized; its capacity reused). IoError when the file can no longer be
  /// read there; FormatError naming the file when the block's checksum is not
  /// `checksum` (the file was changed in place since it was loaded).
  void read(std::uint64_t offset, std::uint32_t count, std::uint64_t checksum,
            std::vector<Descriptor>* out) const;

 private:
  BoundedFile file_;
  std::size_t record_bytes_;
  std::size_t descriptor_offset_;
};

/// Where a database entry's descriptors are when they are not in its
/// `descriptors` vector: a block of `count` records of `file`.
struct DescriptorsOnDisk {
  std::shared_ptr<const DescriptorFile> file;  ///< null: in memory
  std::uint64_t offset = 0;
  std::uint64_t checksum = 0;
  std::uint32_t count = 0;
};

}  // namespace bowg
