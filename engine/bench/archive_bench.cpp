// A network operator's archive as the reference map: one database of many
// keyframes of pipe (10^6 = 40 km at 4 cm), loaded by a robot that then
// revisits its places. Three figures, each in the process that matters:
//
//   bowg_archive_bench build --keyframes N --dir DIR
//     builds the map's database directly (transform, word groups,
//     Database::addToGroupTable + Database::add per keyframe: what
//     LoopDetector::process stores for a survey that closed no loop, without
//     its queries) and writes DIR/archive.bowgdb (saveDetectorFile) and the
//     vocabulary, DIR/archive.bowgvoc. The map's descriptors go to a scratch
//     file as they are made (DIR/descriptors.scratch, removed after the
//     save) and are left there, as a loaded map leaves them in its file: the
//     map is built in its loaded size, ~10 GB at 10^6 keyframes.
//   bowg_archive_bench query --dir DIR [--live 400]
//     in a fresh process: LoopDetector::load of the map (load time), the
//     loaded map's memory per keyframe (Database::memoryBytes() / size, its
//     parts, and the resident set's growth over the load), then the time of
//     LoopDetector::process per live keyframe (features given: transform,
//     word groups, query, islands, verification) on stretches that revisit
//     the map.
//
// The keyframes: a straight corridor of landmarks (synthetic_corridor.h) of
// ~500 features a keyframe (the pipe preset's orb_max_features), one every
// 4 cm; a k=10 L=6 vocabulary trained on its first 2 km (~10^6 descriptors,
// ~740,000 words), so that every map size has a vocabulary of one size and
// most places of a large map are ones the vocabulary never saw, as a network
// is to a vocabulary trained elsewhere. Options: the pipe preset's (config/pipe.yaml)
// with a wider recent-exclusion window (below). Output: one "name value"
// line per figure (scripts/archive_benchmark.sh reads them).
#include <sys/stat.h>
#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>

#include "bowg/core/heap_bytes.h"
#include "bowg/core/resident_memory.h"
#include "bowg/database/database.h"
#include "bowg/detection/detector_file.h"
#include "bowg/detection/detector_state.h"
#include "bowg/detection/loop_detector.h"
#include "bowg/scoring/word_groups.h"
#include "bowg/vocabulary/vocabulary.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "corridor_keyframes.h"

namespace bowg {
namespace {

using Clock = std::chrono::steady_clock;

const double kSpacing = 0.04;       // metres between keyframes (a pipe survey)
const int kLandmarksPerMetre = 63;  // ~500 features a keyframe
const double kTrainedMetres = 2000.0;
const double kMapStart = 5.0;  // first keyframe: a full view of the wall
const double kSecondsPerKeyframe = 0.1;
const std::uint64_t kCorridorSeed = 5;

// The corridor of a map of n keyframes: at least the 2 km the vocabulary is
// trained on, so that small maps get a vocabulary as large as large maps
// (the landmarks are spread over the whole length, so maps longer than
// 2 km get a vocabulary of the same size, not the same one).
testing::Corridor mapCorridor(std::size_t n) {
  const double length = std::max(kTrainedMetres, n * kSpacing) + 2 * kMapStart;
  return testing::makeCorridor(length, kLandmarksPerMetre, kCorridorSeed);
}

// The pipe preset with the corridor's threshold and a recent-exclusion window
// of 250 keyframes: a corridor view holds 8 m of wall, 200 keyframes at
// 4 cm, so the live keyframes of a stretch would otherwise match each other
// instead of the map (a pipe camera sees less far; the preset's 75 covers it).
LoopDetectorOptions archiveOptions() { return bench::corridorPresetOptions(250); }

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The resident set after glibc has handed its free memory back.
double trimmedResidentBytes() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
  return residentBytes();
}

// The process's peak resident set (VmHWM), bytes; 0 where unknown.
double peakResidentBytes() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmHWM:") {
      double kb = 0;
      status >> kb;
      return kb * 1024.0;
    }
  }
  return 0;
}

void print(const char* name, double value) { std::printf("%s %.6g\n", name, value); }

// The map's descriptors, appended to a scratch file of 32-byte records
// (little-endian words) and read back through a DescriptorFile.
class DescriptorSpill {
 public:
  explicit DescriptorSpill(const std::string& path)
      : path_(path), out_(path, std::ios::binary | std::ios::trunc) {
    if (!out_) throw std::runtime_error("cannot write " + path);
    file_ = std::make_shared<DescriptorFile>(BoundedFile(path, FileKind::kDatabase),
                                             sizeof(Descriptor), 0);
  }
  ~DescriptorSpill() { std::remove(path_.c_str()); }
  DescriptorsOnDisk add(const std::vector<Descriptor>& descriptors) {
    std::string bytes;
    bytes.reserve(descriptors.size() * sizeof(Descriptor));
    for (const Descriptor& d : descriptors) {
      for (std::uint64_t word : d.bits) {
        for (int b = 0; b < 8; ++b) bytes.push_back(static_cast<char>((word >> (8 * b)) & 0xff));
      }
    }
    DescriptorsOnDisk on_disk;
    on_disk.file = file_;
    on_disk.offset = written_;
    on_disk.count = static_cast<std::uint32_t>(descriptors.size());
    on_disk.checksum = DescriptorFile::blockChecksum(bytes.data(), bytes.size());
    out_.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    written_ += bytes.size();
    return on_disk;
  }
  /// Everything written is readable.
  void flush() {
    out_.flush();
    if (!out_) throw std::runtime_error("cannot write " + path_);
  }

 private:
  std::string path_;
  std::ofstream out_;
  std::shared_ptr<const DescriptorFile> file_;
  std::uint64_t written_ = 0;
};

// One map keyframe as LoopDetector::process stores it, without its query,
// its descriptors in `spill`.
void addMapKeyframe(Database* db, const LoopDetectorOptions& o, const KeyframeInput& kf,
                    DescriptorSpill* spill) {
  const ImageFeatures& f = kf.features;
  DatabaseEntry e;
  e.stamp = kf.stamp;
  e.points = PackedPoints::fromKeypoints(f.keypoints, f.pyramid_scale_factor);
  e.on_disk = spill->add(f.descriptors);
  e.intrinsics = kf.intrinsics;
  e.centre_x = kf.intrinsics.cx;  // the fan centre of a calibrated camera
  e.centre_y = kf.intrinsics.cy;
  BowVector bow;
  std::vector<WordId> words;
  db->vocabulary().transform(f.descriptors, &bow, nullptr, 0, &words);
  e.words = PackedWords(words);
  CountedGroups counted = db->addToGroupTable(buildWordGroups(f.keypoints, words, o.word_groups));
  db->add(std::move(e), std::move(counted));
}

// Fills `db` with n keyframes along `corridor`; returns features a keyframe.
double fillMap(Database* db, const testing::Corridor& corridor, std::size_t n,
               const LoopDetectorOptions& o, DescriptorSpill* spill) {
  std::mt19937_64 rng(41);
  double features = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const KeyframeInput kf =
        bench::corridorKeyframe(corridor, kMapStart + i * kSpacing, i * kSecondsPerKeyframe, rng);
    features += kf.features.size();
    addMapKeyframe(db, o, kf, spill);
    if ((i + 1) % 100000 == 0) std::fprintf(stderr, "  %zu keyframes\n", i + 1);
  }
  return features / std::max<std::size_t>(1, n);
}

double fileBytes(const std::string& path) {
  struct stat s;
  return stat(path.c_str(), &s) == 0 ? static_cast<double>(s.st_size) : 0.0;
}

int build(std::size_t n, const std::string& dir) {
  const testing::Corridor corridor = mapCorridor(n);
  auto t0 = Clock::now();
  auto vocabulary = std::make_shared<const Vocabulary>(
      bench::trainCorridorVocabulary(corridor, kMapStart + kTrainedMetres));
  print("vocabulary_words", static_cast<double>(vocabulary->wordCount()));
  print("train_s", secondsSince(t0));
  saveVocabulary(*vocabulary, dir + "/archive.bowgvoc");
  const LoopDetectorOptions o = archiveOptions();
  Database db(vocabulary, o.scoring, o.geometric.direct_index_level, o.distribution.fan_bins);
  DescriptorSpill spill(dir + "/descriptors.scratch");
  t0 = Clock::now();
  print("features_per_keyframe", fillMap(&db, corridor, n, o, &spill));
  print("keyframes", static_cast<double>(db.size()));
  print("build_s", secondsSince(t0));
  spill.flush();
  t0 = Clock::now();
  saveDetectorFile(dir + "/archive.bowgdb", db, DetectorState());
  print("save_s", secondsSince(t0));
  print("file_bytes", fileBytes(dir + "/archive.bowgdb"));
  print("build_peak_rss_bytes", peakResidentBytes());
  return 0;
}

// Database::memoryBytes() per keyframe and its parts: what each entry holds
// (descriptors, packed words and positions, the entry record in the deque),
// the word-group table, the distribution table and odometers (fan_bins + 1
// doubles an entry) and the rest: the inverse index (postings and list
// headers) and the newest entries' vectors.
void printMemory(const Database& db) {
  double descriptors = 0, words = 0, points = 0;
  for (const DatabaseEntry& e : db.entries()) {
    descriptors += vectorHeapBytes(e.descriptors);
    words += e.words.heapBytes();
    points += e.points.heapBytes();
  }
  const double records = dequeHeapBytes(db.entries());
  const double groups = db.groupTable().heapBytes();
  const double n = std::max<std::size_t>(1, db.size());
  const double per_entry_doubles = n * (db.fanBins() + 1) * sizeof(double);
  const double total = db.memoryBytes();
  print("memory_bytes_per_keyframe", total / n);
  print("descriptor_bytes_per_keyframe", descriptors / n);
  print("word_bytes_per_keyframe", words / n);
  print("point_bytes_per_keyframe", points / n);
  print("entry_record_bytes_per_keyframe", records / n);
  print("group_table_bytes_per_keyframe", groups / n);
  print("distribution_and_odometer_bytes_per_keyframe", per_entry_doubles / n);
  print("inverse_index_bytes_per_keyframe",
        (total - descriptors - words - points - records - groups - per_entry_doubles) / n);
}

// Where live stretch `s` of `stretches` is centred on a map of n keyframes,
// metres along the corridor: spread over the map.
double stretchCentre(std::size_t n, int s, int stretches) {
  return kMapStart + n * kSpacing * (s + 0.5) / stretches;
}

// Live keyframes: `stretches` drives of `per_stretch` keyframes at 4 cm,
// 2 cm off the map's keyframes, stamped after it.
std::vector<KeyframeInput> liveKeyframes(const testing::Corridor& corridor, std::size_t map_size,
                                         double first_stamp, int stretches, int per_stretch) {
  std::mt19937_64 rng(97);
  std::vector<KeyframeInput> live;
  for (int s = 0; s < stretches; ++s) {
    const double start = stretchCentre(map_size, s, stretches) - per_stretch * kSpacing / 2;
    for (int i = 0; i < per_stretch; ++i) {
      const double stamp = first_stamp + live.size() * kSecondsPerKeyframe;
      live.push_back(
          bench::corridorKeyframe(corridor, start + i * kSpacing + kSpacing / 2, stamp, rng));
    }
  }
  return live;
}

// Sums of the per-keyframe figures of LoopDetector::process.
struct QueryTotals {
  StageTimings sum;
  double max_ms = 0, loops = 0, candidates = 0, n = 0;

  void add(const LoopResult& r) {
    bench::addStageTimes(r.timings, &sum);
    max_ms = std::max(max_ms, r.timings.total_ms);
    loops += r.status == LoopStatus::kLoopDetected ? 1 : 0;
    candidates += r.candidates_scored;
    n += 1;
  }
};

void printTotals(const QueryTotals& t) {
  const double k = 1.0 / std::max(1.0, t.n);
  print("live_keyframes", t.n);
  print("query_mean_ms", t.sum.total_ms * k);
  print("query_max_ms", t.max_ms);
  print("transform_ms", t.sum.transform_ms * k);
  print("word_groups_ms", t.sum.word_groups_ms * k);
  print("query_stage_ms", t.sum.query_ms * k);
  print("islands_ms", t.sum.islands_ms * k);
  print("verification_ms", t.sum.verification_ms * k);
  print("candidates", t.candidates * k);
  print("loops", t.loops * k);
}

// Processes the live keyframes, stretch by stretch; prints each stretch's
// line ("#": not a figure) and the totals.
void timeQueries(LoopDetector* detector, const std::vector<KeyframeInput>& live, int stretches) {
  const std::size_t map_size = detector->database().size();
  const std::size_t per_stretch = live.size() / stretches;
  QueryTotals all;
  for (int s = 0; s < stretches; ++s) {
    QueryTotals stretch;
    for (std::size_t i = s * per_stretch; i < (s + 1) * per_stretch; ++i) {
      const LoopResult r = detector->process(live[i]);
      all.add(r);
      stretch.add(r);
    }
    std::printf("# stretch at %.0f m: %.2f ms mean, %.2f max, %.0f candidates, %.0f%% loops\n",
                stretchCentre(map_size, s, stretches), stretch.sum.total_ms / stretch.n,
                stretch.max_ms, stretch.candidates / stretch.n, 100 * stretch.loops / stretch.n);
  }
  printTotals(all);
}

int query(const std::string& dir, int live_count) {
  auto vocabulary = std::make_shared<const Vocabulary>(loadVocabulary(dir + "/archive.bowgvoc"));
  LoopDetector detector(vocabulary, archiveOptions());
  const double rss_before = trimmedResidentBytes();
  const auto t0 = Clock::now();
  detector.load(dir + "/archive.bowgdb");
  print("load_s", secondsSince(t0));
  print("load_peak_rss_bytes", peakResidentBytes());
  const Database& db = detector.database();
  print("keyframes", static_cast<double>(db.size()));
  print("rss_growth_per_keyframe",
        (trimmedResidentBytes() - rss_before) / std::max<std::size_t>(1, db.size()));
  printMemory(db);
  const int stretches = 4;
  const testing::Corridor corridor = mapCorridor(db.size());
  timeQueries(&detector,
              liveKeyframes(corridor, db.size(), db.entries().back().stamp + 1.0, stretches,
                            std::max(1, live_count / stretches)),
              stretches);
  return 0;
}

int usage() {
  std::fprintf(stderr,
               "usage: bowg_archive_bench build --keyframes N --dir DIR\n"
               "       bowg_archive_bench query --dir DIR [--live 400]\n");
  return 2;
}

// The value after `flag` in argv, or `fallback`.
std::string option(int argc, char** argv, const char* flag, const std::string& fallback) {
  for (int i = 2; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], flag) == 0) return argv[i + 1];
  }
  return fallback;
}

}  // namespace
}  // namespace bowg

int main(int argc, char** argv) {
  if (argc < 2) return bowg::usage();
  const std::string mode = argv[1];
  const std::string dir = bowg::option(argc, argv, "--dir", "");
  if (dir.empty()) return bowg::usage();
  try {
    if (mode == "build") {
      const long n = std::atol(bowg::option(argc, argv, "--keyframes", "10000").c_str());
      if (n < 1000) return bowg::usage();
      return bowg::build(static_cast<std::size_t>(n), dir);
    }
    if (mode == "query") {
      return bowg::query(dir, std::atoi(bowg::option(argc, argv, "--live", "400").c_str()));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bowg_archive_bench: %s\n", e.what());
    return 1;
  }
  return bowg::usage();
}
