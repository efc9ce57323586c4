// Every file the engine, the nodelet and the tools read goes through here:
// it is opened without blocking (a FIFO or a device never holds open()),
// refused unless it is a regular file, and refused before a byte is read when
// it is larger than the limit of its kind. A refusal names the file, its
// size, the limit and the environment variable that raises it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace bowg {

/// The kinds of input file, each with its own size limit.
enum class FileKind {
  kVocabulary,  ///< vocabulary trees of every format (also their decompressed text)
  kDatabase,    ///< saved detector databases
  kImage,       ///< image files and feature masks (pixels are limited separately)
  kText,        ///< configs, ground truth, odometry, intrinsics, patterns
};

/// The limit of one kind: default, or the environment variable's value in
/// MiB (BOWG_MAX_VOCABULARY_MB, BOWG_MAX_DATABASE_MB, BOWG_MAX_IMAGE_FILE_MB,
/// BOWG_MAX_TEXT_MB). Throws InvalidParameter naming the variable when it is
/// set to anything but a positive whole number.
struct FileLimit {
  std::uint64_t max_bytes = 0;
  std::string variable;  ///< the environment variable that raises it
};
FileLimit fileLimit(FileKind kind);

/// Defaults in bytes: the largest real inputs with room to spare (ORB-SLAM's
/// ORBvoc.txt is 145 MB; a 10^6-keyframe archive is a few GB).
std::uint64_t defaultFileLimit(FileKind kind);

/// The name used in messages ("vocabulary", "database", "image", "file").
const char* fileKindName(FileKind kind);

/// "1.5 GiB", "300 kB", "12 bytes": sizes as a person reads them.
std::string formatBytes(std::uint64_t bytes);

/// "<kind> '<path>' is 3.0 GiB, more than the limit of 1.0 GiB (raise it
/// with the environment variable BOWG_MAX_VOCABULARY_MB)". `what_size`
/// replaces "is <size>" for limits on what a file decompresses to.
std::string limitMessage(FileKind kind, const std::string& path, const std::string& what_size,
                         const FileLimit& limit);
/// The same with `label` ("ground-truth file") in place of the kind's name.
std::string limitMessage(const std::string& label, const std::string& path,
                         const std::string& what_size, const FileLimit& limit);

/// An open regular file, closed with this object.
class BoundedFile {
 public:
  /// Opens `path` read-only without blocking and refuses (IoError naming the
  /// path and the reason) a missing or unreadable file, a FIFO, a device, a
  /// directory, a socket, and a file larger than fileLimit(kind).
  /// `label` names the file in messages ("ground-truth file"); empty:
  /// fileKindName(kind).
  BoundedFile(const std::string& path, FileKind kind, const std::string& label = std::string());
  ~BoundedFile();
  BoundedFile(BoundedFile&& other) noexcept;
  BoundedFile(const BoundedFile&) = delete;
  BoundedFile& operator=(const BoundedFile&) = delete;
  BoundedFile& operator=(BoundedFile&&) = delete;

  const std::string& path() const { return path_; }
  FileKind kind() const { return kind_; }
  std::uint64_t size() const { return size_; }
  int fd() const { return fd_; }

  /// Reads up to `n` bytes at the current position; returns how many (0 at
  /// the end). IoError naming the path on a read error.
  std::size_t readSome(void* dst, std::size_t n);
  /// Reads exactly `n` bytes or throws IoError ("ends after N bytes").
  void readExactly(void* dst, std::size_t n);
  /// The rest of the file from the current position.
  std::string readRest();
  /// Reads exactly `n` bytes at byte `offset` without moving the current
  /// position (pread: safe from several threads at once); IoError naming
  /// the path when the file ends before them (shrunk since it was opened).
  void readAt(void* dst, std::size_t n, std::uint64_t offset) const;

 private:
  std::string path_;
  FileKind kind_;
  std::string label_;
  std::uint64_t size_ = 0;
  int fd_ = -1;
};

/// The whole file, bounded as above.
std::string readBoundedFile(const std::string& path, FileKind kind,
                            const std::string& label = std::string());

}  // namespace bowg
