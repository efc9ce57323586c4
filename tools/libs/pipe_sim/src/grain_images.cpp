// loadGrainImages (declared in quilted_grain.h): the file-system side of the
// quilted grain, apart from the quilting itself.
#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "bowg_pipe_sim/quilted_grain.h"

namespace bowg {
namespace pipe_sim {
namespace {

bool isImageName(const std::string& name) {
  const std::size_t dot = name.rfind('.');
  if (dot == std::string::npos || name[0] == '.') return false;
  std::string ext = name.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == "png" || ext == "jpg" || ext == "jpeg";
}

// A texture image must be a regular file of at most kMaxTextureBytes before
// OpenCV opens it: a FIFO would hold the generator for ever, a device or a
// huge file would be read whole. (This library does not link the engine and
// its BoundedFile; texture images are small photographs.)
constexpr off_t kMaxTextureBytes = off_t{64} << 20;

void checkTextureFile(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    throw std::runtime_error("cannot read the texture image " + path + ": " + std::strerror(errno));
  }
  if (!S_ISREG(st.st_mode)) {
    throw std::runtime_error("cannot read the texture image " + path +
                             ": it is not a regular file");
  }
  if (st.st_size > kMaxTextureBytes) {
    throw std::runtime_error("the texture image " + path + " is " +
                             std::to_string(st.st_size >> 20) + " MiB, more than 64 MiB");
  }
}

}  // namespace

std::vector<cv::Mat> loadGrainImages(const std::string& dir, double crop) {
  if (!(crop >= 0 && crop <= 0.45)) {
    throw std::invalid_argument("texture crop must be in [0, 0.45], not " + std::to_string(crop));
  }
  DIR* d = ::opendir(dir.c_str());
  if (d == nullptr) {
    throw std::runtime_error("cannot read the texture image folder " + dir + ": " +
                             std::strerror(errno));
  }
  std::vector<std::string> names;
  while (const dirent* entry = ::readdir(d)) {
    if (isImageName(entry->d_name)) names.push_back(entry->d_name);
  }
  ::closedir(d);
  if (names.empty())
    throw std::runtime_error("no PNG or JPG image in the texture image folder " + dir);
  // readdir's order depends on the file system; the output must not.
  std::sort(names.begin(), names.end());
  std::vector<cv::Mat> images;
  for (const std::string& name : names) {
    const std::string path = dir + "/" + name;
    checkTextureFile(path);
    const cv::Mat grey = cv::imread(path, cv::IMREAD_GRAYSCALE);
    if (grey.empty()) throw std::runtime_error("cannot decode the texture image " + path);
    const int cut = static_cast<int>(std::lround(crop * grey.rows));
    const cv::Mat kept = grey.rowRange(cut, grey.rows - cut);
    if (kept.rows < QuiltedGrain::kPatch || kept.cols < QuiltedGrain::kPatch) {
      throw std::runtime_error("the texture image " + path + " is smaller than " +
                               std::to_string(QuiltedGrain::kPatch) + " px after the crop");
    }
    images.push_back(kept.clone());
  }
  return images;
}

}  // namespace pipe_sim
}  // namespace bowg
