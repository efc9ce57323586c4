// Files every loader must refuse, quickly and cheaply: a FIFO (open() must
// not block), a directory, a device that never ends, and a sparse file far
// larger than any input (no blocks on disk). Shared by the loaders' tests.
#pragma once

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "bowg/core/errors.h"

namespace bowg {
namespace testing {

struct SpecialFile {
  std::string what;  ///< "FIFO", "directory", "device", "sparse file"
  std::string path;
  std::string reason;  ///< a part the refusal's message must hold
};

/// A sparse file of `bytes` at `path` (nothing written but its first byte).
inline void makeSparseFile(const std::string& path, std::uint64_t bytes, char first = 'x') {
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.put(first);
  }
  EXPECT_EQ(::truncate(path.c_str(), static_cast<off_t>(bytes)), 0) << path;
}

/// The four special files, named `<dir>/special_<what><suffix>` (the suffix
/// keeps an extension that format detection looks at). The sparse file is
/// `sparse_bytes` long and its refusal must mention `sparse_reason`.
inline std::vector<SpecialFile> makeSpecialFiles(const std::string& dir, const std::string& suffix,
                                                 std::uint64_t sparse_bytes,
                                                 const std::string& sparse_reason) {
  EXPECT_EQ(std::system(("mkdir -p '" + dir + "'").c_str()), 0);
  const std::string fifo = dir + "/special_fifo" + suffix;
  ::unlink(fifo.c_str());
  EXPECT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << fifo;
  const std::string directory = dir + "/special_directory" + suffix;
  EXPECT_EQ(std::system(("mkdir -p '" + directory + "'").c_str()), 0);
  const std::string sparse = dir + "/special_sparse" + suffix;
  makeSparseFile(sparse, sparse_bytes);
  return {{"FIFO", fifo, "FIFO"},
          {"directory", directory, "is a directory"},
          {"device", "/dev/zero", "device"},
          {"sparse file", sparse, sparse_reason}};
}

/// The process's peak resident memory so far, in kB.
inline long peakResidentKb() {
  struct rusage usage;
  ::getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

/// `load(path)` must throw IoError or FormatError whose message names the
/// path and holds `reason`, within 1 s and raising the peak resident memory
/// by less than 100 MB.
inline void expectRefusedFast(const std::string& path, const std::string& reason,
                              const std::function<void(const std::string&)>& load) {
  const long peak_before = peakResidentKb();
  const auto start = std::chrono::steady_clock::now();
  std::string message;
  try {
    load(path);
    ADD_FAILURE() << path << " was accepted";
  } catch (const IoError& e) {
    message = e.what();
  } catch (const FormatError& e) {
    message = e.what();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find(reason), std::string::npos)
      << "expected '" << reason << "' in: " << message;
  EXPECT_LT(seconds, 1.0) << message;
  EXPECT_LT(peakResidentKb() - peak_before, 100 * 1024) << message;
}

/// Every special file refused by `load` as expectRefusedFast() says.
inline void expectSpecialFilesRefused(const std::vector<SpecialFile>& files,
                                      const std::function<void(const std::string&)>& load) {
  for (const SpecialFile& f : files) {
    SCOPED_TRACE(f.what);
    expectRefusedFast(f.path, f.reason, load);
  }
  for (const SpecialFile& f : files) {
    if (f.what == "sparse file" || f.what == "FIFO") ::unlink(f.path.c_str());
  }
}

}  // namespace testing
}  // namespace bowg
