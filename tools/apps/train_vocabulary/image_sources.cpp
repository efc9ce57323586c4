// Finding bowg_train_vocabulary's images (image_sources.h): the recursive
// folder walk, the bag's messages on the image topic, the even thinning.
#include "image_sources.h"

#include <dirent.h>
#include <rosbag/view.h>
#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

#include "bowg/core/errors.h"

namespace bowg {
namespace train_vocabulary_app {
namespace {

bool isImage(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* ext : {".png", ".jpg", ".jpeg"}) {
    const std::string e(ext);
    if (lower.size() > e.size() && lower.compare(lower.size() - e.size(), e.size(), e) == 0)
      return true;
  }
  return false;
}

void findImages(const std::string& dir, std::vector<std::string>* out, int depth = 0) {
  if (depth > 64) return;  // symlink loops
  DIR* d = ::opendir(dir.c_str());
  if (d == nullptr)
    throw bowg::IoError("cannot open folder '" + dir + "': " + std::strerror(errno));
  std::vector<std::string> entries;
  while (dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    if (name != "." && name != "..") entries.push_back(name);
  }
  ::closedir(d);
  for (const std::string& name : entries) {
    const std::string path = dir + "/" + name;
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) continue;
    if (S_ISDIR(st.st_mode)) {
      findImages(path, out, depth + 1);
    } else if (S_ISREG(st.st_mode) && isImage(name)) {
      out->push_back(path);
    }
  }
}

}  // namespace

rosbag::Bag openBag(const std::string& path) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw bowg::IoError("cannot open the bag '" + path + "': " + e.what());
  }
  return bag;
}

std::vector<ImageSource> gatherImageSources(const Args& a) {
  std::vector<std::string> files;
  for (const std::string& f : a.folders) findImages(f, &files);
  std::sort(files.begin(), files.end());
  std::vector<ImageSource> images;
  for (const std::string& f : files) images.push_back({f, -1, 0});
  for (std::size_t b = 0; b < a.bags.size(); ++b) {
    rosbag::Bag bag = openBag(a.bags[b]);
    rosbag::View view(bag, rosbag::TopicQuery(a.image_topic));
    if (view.size() == 0) {
      throw bowg::FormatError("the bag '" + a.bags[b] + "' has no message on " + a.image_topic +
                              " (see --image-topic)");
    }
    for (std::size_t i = 0; i < view.size(); i += static_cast<std::size_t>(a.every)) {
      images.push_back({"", static_cast<int>(b), i});
    }
  }
  return images;
}

std::vector<ImageSource> pickEvenly(std::vector<ImageSource> images, long max_images) {
  if (max_images > 0 && images.size() > static_cast<std::size_t>(max_images)) {
    std::vector<ImageSource> picked;
    for (long i = 0; i < max_images; ++i) {
      picked.push_back(images[static_cast<std::size_t>(i) * images.size() /
                              static_cast<std::size_t>(max_images)]);
    }
    images.swap(picked);
  }
  return images;
}

}  // namespace train_vocabulary_app
}  // namespace bowg
