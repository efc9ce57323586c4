// Atomic file replacement: write a temporary file in the destination's
// directory, fsync it, rename it over the destination, fsync the directory.
// A crash or a full disk leaves either the old file or the new one, never a
// half-written file (the databases and vocabularies are large and precious).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace bowg {

/// For writers that need a path of their own (e.g. cv::FileStorage): hands out
/// a temporary path in the destination's directory that keeps the
/// destination's file name as a suffix (so extensions such as ".yml.gz" that
/// select the writer's behaviour still apply). commit() publishes it; if the
/// object is destroyed without commit() the temporary file is removed.
class AtomicFileWriter {
 public:
  /// Throws IoError if `path` is empty or names a directory.
  explicit AtomicFileWriter(const std::string& path);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  const std::string& path() const { return path_; }
  const std::string& tempPath() const { return temp_path_; }

  /// fsyncs the temporary file, renames it onto path(), fsyncs the
  /// directory. Throws IoError naming the path on any failure (the
  /// temporary file is then removed).
  void commit();

 private:
  std::string path_;
  std::string temp_path_;
  bool committed_ = false;
};

/// A file written atomically piece by piece, for files too large to be
/// encoded in memory first (a network's archive): appended to, patched and
/// read back while it is the temporary file; commit() fsyncs it and
/// publishes it as AtomicFileWriter does. Destroyed without commit(), it
/// leaves the destination as it was. Every failure is an IoError naming the
/// destination and the system error.
class AtomicFileStream {
 public:
  explicit AtomicFileStream(const std::string& path);
  ~AtomicFileStream();
  AtomicFileStream(const AtomicFileStream&) = delete;
  AtomicFileStream& operator=(const AtomicFileStream&) = delete;

  const std::string& path() const { return writer_.path(); }
  /// Bytes written so far (the end of the file).
  std::uint64_t size() const { return size_; }
  /// Appends `n` bytes.
  void write(const void* data, std::size_t n);
  /// Overwrites `n` bytes at `offset` (within size()).
  void writeAt(const void* data, std::size_t n, std::uint64_t offset);
  /// Reads `n` bytes written before, at `offset`.
  void readAt(void* data, std::size_t n, std::uint64_t offset) const;
  void commit();

 private:
  AtomicFileWriter writer_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

/// Writes `size` bytes atomically to `path` (throws IoError with the path and
/// the system error on failure).
void writeFileAtomically(const std::string& path, const void* data, std::size_t size);
inline void writeFileAtomically(const std::string& path, const std::string& bytes) {
  writeFileAtomically(path, bytes.data(), bytes.size());
}

/// Removes the temporary files that writers of `path` (AtomicFileWriter,
/// writeFileAtomically) left in its directory when they died before their
/// commit (kill -9, power loss): ".tmp-<pid>-<n>-<base name>" whose process no
/// longer exists, and only regular files owned by this process's user, so that
/// nothing another user or program made is touched. Called by every new
/// writer of `path`, and by programs when they open a path they will save to,
/// so that an interrupted save does not leave its partial copy behind until
/// the next save. Returns how many were removed; never throws (an unreadable
/// directory is reported by the write itself).
std::size_t removeStaleTemporariesOf(const std::string& path);

}  // namespace bowg
