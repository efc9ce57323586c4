#include "bowg_evaluation/ground_truth.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "bowg/core/atomic_file.h"
#include "bowg/core/errors.h"
#include "bowg_evaluation/text_file.h"

namespace bowg {
namespace eval {
namespace {

std::string trim(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

/// A non-negative decimal integer, nothing else (no sign, no spaces inside).
bool parseIndex(const std::string& token, int* value) {
  if (token.empty() || token.size() > 9) return false;
  for (char c : token) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  }
  *value = std::stoi(token);
  return true;
}

}  // namespace

bool GroundTruth::contains(int query, int match) const {
  const auto it = loops.find(query);
  return it != loops.end() && std::binary_search(it->second.begin(), it->second.end(), match);
}

bool GroundTruth::hasLoop(int query) const {
  const auto it = loops.find(query);
  return it != loops.end() && !it->second.empty();
}

int GroundTruth::positives() const {
  int n = 0;
  for (const auto& kv : loops) n += kv.second.empty() ? 0 : 1;
  return n;
}

GroundTruth parseGroundTruth(const std::string& text, const std::string& source) {
  GroundTruth gt;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string where = source + ":" + std::to_string(number) + ": ";
    const std::size_t hash = line.find('#');
    const std::string content = trim(hash == std::string::npos ? line : line.substr(0, hash));
    if (content.empty()) continue;
    const std::size_t colon = content.find(':');
    if (colon == std::string::npos) {
      throw FormatError(where + "expected '<query>: <match>,<match>,...', got '" + content + "'");
    }
    int query = 0;
    if (!parseIndex(trim(content.substr(0, colon)), &query)) {
      throw FormatError(where + "the query '" + trim(content.substr(0, colon)) +
                        "' is not a non-negative integer");
    }
    if (gt.loops.count(query)) {
      throw FormatError(where + "query " + std::to_string(query) + " appears twice");
    }
    std::vector<int>& matches = gt.loops[query];
    const std::string rest = trim(content.substr(colon + 1));
    if (!rest.empty()) {
      std::istringstream items(rest);
      std::string item;
      while (std::getline(items, item, ',')) {
        int match = 0;
        if (!parseIndex(trim(item), &match)) {
          throw FormatError(where + "the match '" + trim(item) +
                            "' is not a non-negative integer (matches are separated by commas)");
        }
        if (match >= query) {
          throw FormatError(where + "match " + std::to_string(match) +
                            " is not an earlier frame than query " + std::to_string(query));
        }
        matches.push_back(match);
      }
      if (rest.back() == ',') throw FormatError(where + "trailing comma");
    }
    std::sort(matches.begin(), matches.end());
    matches.erase(std::unique(matches.begin(), matches.end()), matches.end());
  }
  return gt;
}

GroundTruth readGroundTruth(const std::string& path) {
  return parseGroundTruth(readTextFile(path, "ground-truth"), path);
}

void writeGroundTruth(const std::string& path, const GroundTruth& gt, const std::string& header) {
  std::ostringstream out;
  std::istringstream lines(header);
  std::string line;
  while (std::getline(lines, line)) out << "# " << line << "\n";
  for (const auto& kv : gt.loops) {
    if (kv.second.empty()) continue;
    out << kv.first << ":";
    for (std::size_t i = 0; i < kv.second.size(); ++i) out << (i ? "," : " ") << kv.second[i];
    out << "\n";
  }
  writeFileAtomically(path, out.str());
}

void GroundTruthOptions::validate() const {
  if (!(max_distance_m > 0)) throw std::invalid_argument("GroundTruthOptions.max_distance_m must be > 0");
  if (!(max_heading_deg > 0) || max_heading_deg > 180) {
    throw std::invalid_argument("GroundTruthOptions.max_heading_deg must be in (0, 180]");
  }
  if (!(exclude_recent_m >= 0)) {
    throw std::invalid_argument("GroundTruthOptions.exclude_recent_m must be >= 0");
  }
}

GroundTruth groundTruthFromPoses(const std::vector<TravelPose>& poses,
                                 const GroundTruthOptions& options) {
  options.validate();
  GroundTruth gt;
  const double d2 = options.max_distance_m * options.max_distance_m;
  const double min_cos = std::cos(options.max_heading_deg * M_PI / 180.0);
  for (std::size_t q = 0; q < poses.size(); ++q) {
    const TravelPose& a = poses[q];
    std::vector<int> matches;
    for (std::size_t m = 0; m < q; ++m) {
      const TravelPose& b = poses[m];
      if (a.distance - b.distance < options.exclude_recent_m) break;  // distance grows with m
      const double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
      if (dx * dx + dy * dy + dz * dz >= d2) continue;
      if (a.hx * b.hx + a.hy * b.hy + a.hz * b.hz <= min_cos) continue;
      matches.push_back(static_cast<int>(m));
    }
    if (!matches.empty()) gt.loops[static_cast<int>(q)] = matches;
  }
  return gt;
}

}  // namespace eval
}  // namespace bowg
