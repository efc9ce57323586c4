// bowg_evaluate: runs the BoWG engine (the nodelet's code and parameter
// files) over a rosbag or an image folder as fast as the CPU allows and
// reports precision, recall, F1, the PR curve, recall at 100 % precision,
// per-stage timing and time versus database size; --ablation runs the four
// rows of the paper's ablation side by side. See docs/evaluation.md.
#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>

#include "bowg/core/atomic_file.h"
#include "bowg/core/errors.h"
#include "bowg/features/feature_extractor.h"
#include "bowg/parameters/parameter_table.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "bowg_evaluation/detector_run.h"
#include "bowg_evaluation/ground_truth.h"
#include "bowg_evaluation/image_file.h"
#include "bowg_evaluation/metrics.h"
#include "bowg_evaluation/odometry_file.h"
#include "bowg_evaluation/parallel_runs.h"
#include "bowg_evaluation/pr_report.h"
#include "bowg_ros/bag_images.h"
#include "bowg_ros/ros_conversions.h"

namespace {

using namespace bowg;
using namespace bowg::eval;

const char* kUsage =
    "usage: bowg_evaluate (--bag FILE | --images DIR) --vocabulary FILE [options]\n"
    "Input:\n"
    "  --bag FILE                 rosbag with the images\n"
    "  --image-topic T            sensor_msgs/Image or CompressedImage topic\n"
    "                             [/camera/image_raw]\n"
    "  --camera-info-topic T      sensor_msgs/CameraInfo topic, 'none' to ignore [/camera/camera_info]\n"
    "  --images DIR               image folder (png/jpg/jpeg/pgm/bmp, sorted by file name)\n"
    "  --rate HZ                  stamps of folder images: frame n at n / HZ s [1]\n"
    "  --max-frames N             use the first N images only [all]\n"
    "  --odometry FILE            metres driven per frame (CSV with 'frame' and 'odometer' or\n"
    "                             'distance' columns, e.g. the generator's poses.csv): the\n"
    "                             recent-exclusion window in metres (recent_exclusion_m)\n"
    "Engine:\n"
    "  --vocabulary FILE          any format bowg::loadVocabulary reads (required)\n"
    "  --config FILE              parameter file, e.g. config/pipe.yaml [engine defaults]\n"
    "Evaluation:\n"
    "  --gt FILE                  ground truth 'query: match,...' (0-based frame indices)\n"
    "  --output DIR               where CSVs, the PR plot and summary.txt go [bowg_evaluation]\n"
    "  --ablation                 run bow, word_groups, temporal, distribution side by side\n"
    "  --rows A,B,...             ablation rows to run instead (implies --ablation): bow,\n"
    "                             word_groups, temporal, distribution (each with the\n"
    "                             configuration's extensions), paper (the paper's method as\n"
    "                             written), paper_bow (its pipeline with pure bag of words:\n"
    "                             DBoW2 + DLoopDetector), configured (the configuration),\n"
    "                             without_floor, without_normaliser_distance,\n"
    "                             without_alignment, without_missed_queries,\n"
    "                             without_hypotheses, without_min_step, without_reranking\n"
    "                             (the configuration with one extension switched off)\n"
    "  --sweep rerun|score        PR curve: re-run the detector per threshold (exact, slower)\n"
    "                             or sweep the final score of one run at the lowest threshold\n"
    "                             [rerun]\n"
    "  --thresholds LO:STEP:HI|A,B,C   min_score values of the sweep [0.2:0.2:2]; the\n"
    "                             configured min_score is always one of them\n"
    "  --jobs N                   threads for the re-runs of the sweep (0 = one per core) [0];\n"
    "                             the timing runs at the configured threshold run alone\n"
    "  --quiet                    no progress bar\n"
    "Diagnosis:\n"
    "  --dump-candidates FILE     with --gt: one run of the configured detector (every score on,\n"
    "                             minimum normalisers 0) writing, per query with a revisit, the\n"
    "                             rank of the best true match under eta_w, eta_g, eta_d, eta_sim\n"
    "                             and eta, the normalisers and the feature count (CSV); prints\n"
    "                             the top-1 rates and median ranks, then stops\n";

struct Args {
  std::string bag, image_topic = "/camera/image_raw", info_topic = "/camera/camera_info";
  std::string images, vocabulary, config, gt, output = "bowg_evaluation", sweep = "rerun";
  std::string odometry;
  std::string dump_candidates;
  double rate = 1.0;
  long max_frames = 0;
  int jobs = 0;
  bool ablation = false, quiet = false;
  std::vector<std::string> rows{"bow", "word_groups", "temporal", "distribution"};
  std::vector<double> thresholds;
};

double toNumber(const std::string& flag, const std::string& v) {
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0' || !std::isfinite(x)) {
    throw std::invalid_argument(flag + ": '" + v + "' is not a number");
  }
  return x;
}

std::vector<double> parseThresholds(const std::string& v) {
  std::vector<double> out;
  if (v.find(':') != std::string::npos) {
    std::istringstream in(v);
    std::string a, b, c;
    if (!std::getline(in, a, ':') || !std::getline(in, b, ':') || !std::getline(in, c, ':')) {
      throw std::invalid_argument("--thresholds: expected LO:STEP:HI, got " + v);
    }
    const double lo = toNumber("--thresholds", a), step = toNumber("--thresholds", b),
                 hi = toNumber("--thresholds", c);
    if (!(step > 0) || hi < lo || (hi - lo) / step > 1000) {
      throw std::invalid_argument("--thresholds: need STEP > 0, HI >= LO, at most 1000 values");
    }
    for (int i = 0; lo + i * step <= hi + 1e-9; ++i) out.push_back(lo + i * step);
  } else {
    std::istringstream in(v);
    std::string item;
    while (std::getline(in, item, ',')) out.push_back(toNumber("--thresholds", item));
  }
  for (double t : out) {
    if (t < 0) throw std::invalid_argument("--thresholds: min_score values must be >= 0");
  }
  if (out.empty()) throw std::invalid_argument("--thresholds: no value");
  std::sort(out.begin(), out.end(), std::greater<double>());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<std::string> splitList(const std::string& v) {
  std::vector<std::string> out;
  std::istringstream in(v);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

Args parseArgs(int argc, char** argv) {
  Args a;
  a.thresholds = parseThresholds("0.2:0.2:2");
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "-h" || flag == "--help") {
      std::cout << kUsage;
      std::exit(0);
    }
    if (flag == "--ablation") { a.ablation = true; continue; }
    if (flag == "--quiet") { a.quiet = true; continue; }
    if (i + 1 >= argc) throw std::invalid_argument(flag + ": missing value (see --help)");
    const std::string v = argv[++i];
    if (flag == "--bag") a.bag = v;
    else if (flag == "--image-topic") a.image_topic = v;
    else if (flag == "--camera-info-topic") a.info_topic = v;
    else if (flag == "--images") a.images = v;
    else if (flag == "--rate") a.rate = toNumber(flag, v);
    else if (flag == "--max-frames") a.max_frames = static_cast<long>(toNumber(flag, v));
    else if (flag == "--vocabulary") a.vocabulary = v;
    else if (flag == "--config") a.config = v;
    else if (flag == "--gt") a.gt = v;
    else if (flag == "--output") a.output = v;
    else if (flag == "--sweep") a.sweep = v;
    else if (flag == "--thresholds") a.thresholds = parseThresholds(v);
    else if (flag == "--dump-candidates") a.dump_candidates = v;
    else if (flag == "--odometry") a.odometry = v;
    else if (flag == "--rows") {
      a.rows = splitList(v);
      if (a.rows.empty()) throw std::invalid_argument("--rows needs at least one row");
      for (const std::string& row : a.rows) LoopDetectorOptions::ablation(row, LoopDetectorOptions());
      a.ablation = true;
    }
    else if (flag == "--jobs") {
      const double j = toNumber(flag, v);
      if (j < 0 || j > 256 || j != static_cast<int>(j)) {
        throw std::invalid_argument("--jobs must be an integer in [0, 256]");
      }
      a.jobs = static_cast<int>(j);
    }
    else throw std::invalid_argument("unknown option " + flag + " (see --help)");
  }
  if (a.bag.empty() == a.images.empty()) {
    throw std::invalid_argument("give exactly one of --bag FILE and --images DIR (see --help)");
  }
  if (a.vocabulary.empty()) throw std::invalid_argument("--vocabulary FILE is required");
  if (a.sweep != "rerun" && a.sweep != "score") {
    throw std::invalid_argument("--sweep must be rerun or score, not " + a.sweep);
  }
  if (!(a.rate > 0)) throw std::invalid_argument("--rate must be > 0");
  if (a.max_frames < 0) throw std::invalid_argument("--max-frames must be >= 0");
  return a;
}

class ProgressBar {
 public:
  ProgressBar(std::string label, bool quiet) : label_(std::move(label)), quiet_(quiet) {}
  void operator()(std::size_t done, std::size_t total) {
    if (quiet_ || total == 0) return;
    const int percent = static_cast<int>(100 * done / total);
    if (percent == last_ && done != total) return;
    last_ = percent;
    const int width = 30, filled = width * percent / 100;
    std::fprintf(stderr, "\r%-22s [%s%s] %3d%% %zu/%zu", label_.c_str(),
                 std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(),
                 percent, done, total);
    if (done == total) std::fprintf(stderr, "\n");
  }

 private:
  std::string label_;
  bool quiet_;
  int last_ = -1;
};

std::vector<std::string> listImages(const std::string& dir) {
  DIR* d = ::opendir(dir.c_str());
  if (!d) throw IoError("cannot open the image folder " + dir);
  std::vector<std::string> files;
  while (dirent* e = ::readdir(d)) {
    std::string name = e->d_name, lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
    for (const char* ext : {".png", ".jpg", ".jpeg", ".pgm", ".bmp"}) {
      const std::string x(ext);
      if (lower.size() > x.size() && lower.compare(lower.size() - x.size(), x.size(), x) == 0) {
        files.push_back(dir + "/" + name);
        break;
      }
    }
  }
  ::closedir(d);
  std::sort(files.begin(), files.end());
  if (files.empty()) throw IoError("no png/jpg/jpeg/pgm/bmp image in " + dir);
  return files;
}

/// Extracts the features of every image once (shared by every run).
std::vector<FrameInput> loadFrames(const Args& a, const FeatureExtractor& extractor) {
  std::vector<FrameInput> frames;
  auto add = [&](const cv::Mat& grey, double stamp, const CameraIntrinsics& k) {
    FrameInput f;
    // rosbag stamps may repeat (several cameras, a replayed clock): keep
    // them strictly increasing as the detector requires.
    f.stamp = frames.empty() ? stamp : std::max(stamp, frames.back().stamp + 1e-6);
    f.intrinsics = k;
    const auto t0 = std::chrono::steady_clock::now();
    f.features = grey.empty() ? ImageFeatures() : extractor.extract(grey);
    f.feature_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    frames.push_back(std::move(f));
  };
  ProgressBar bar("features", a.quiet);
  if (!a.images.empty()) {
    std::vector<std::string> files = listImages(a.images);
    if (a.max_frames > 0 && files.size() > static_cast<std::size_t>(a.max_frames)) files.resize(a.max_frames);
    std::size_t skipped = 0;
    for (std::size_t i = 0; i < files.size(); ++i) {
      std::string why;
      const cv::Mat grey = eval::readGreyImage(files[i], &why);
      if (grey.empty()) {
        // Kept as a frame without features, so that frame i stays image i
        // of the folder (the ground truth's numbering).
        std::fprintf(stderr, "\nwarning: image %s skipped (%s): a frame without features\n",
                     files[i].c_str(), why.c_str());
        ++skipped;
      }
      add(grey, i / a.rate, CameraIntrinsics());
      bar(i + 1, files.size());
    }
    if (skipped > 0) {
      std::fprintf(stderr, "warning: %zu of %zu images skipped (unreadable)\n", skipped,
                   files.size());
    }
    if (skipped == files.size()) throw FormatError("no readable image in " + a.images);
    return frames;
  }
  rosbag::Bag bag;
  try {
    bag.open(a.bag, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw IoError("cannot open the bag " + a.bag + ": " + e.what());
  }
  std::vector<std::string> topics{a.image_topic};
  if (a.info_topic != "none") topics.push_back(a.info_topic);
  rosbag::View view(bag, rosbag::TopicQuery(topics));
  rosbag::View images_only(bag, rosbag::TopicQuery(a.image_topic));
  std::size_t total = images_only.size();
  if (total == 0) throw FormatError("the bag " + a.bag + " has no messages on " + a.image_topic);
  if (a.max_frames > 0) total = std::min<std::size_t>(total, a.max_frames);
  CameraIntrinsics intrinsics;
  for (const rosbag::MessageInstance& m : view) {
    if (frames.size() >= total) break;
    if (m.getTopic() == a.info_topic) {
      // The first valid camera_info, checked as the nodelet checks it.
      const sensor_msgs::CameraInfo::ConstPtr info = m.instantiate<sensor_msgs::CameraInfo>();
      if (info && !intrinsics.valid) intrinsics = bowg_ros::toIntrinsics(*info);
      continue;
    }
    const bowg_ros::BagImage image = bowg_ros::readBagImage(m, a.bag);
    add(image.grey, image.stamp.toSec(), intrinsics);
    bar(frames.size(), total);
  }
  return frames;
}

std::string fmt(const char* format, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), format, a, b, c, d);
  return buf;
}

// --dump-candidates: where the true revisit ranks among the candidates under
// each score of the method (paper eqs. 2, 4, 5/9, 7 and the distribution
// score), so that one sees which score separates revisits from look-alikes.
// Rank 1 = the best true match has the highest score of all candidates; 0 =
// no true match among the candidates (outside the database or sharing nothing).
int dumpCandidates(const Args& a, std::shared_ptr<const Vocabulary> vocabulary,
                   LoopDetectorOptions options, const std::vector<FrameInput>& frames,
                   const GroundTruth& gt) {
  options.word_groups.enabled = true;
  options.distribution.enabled = true;
  options.similarity.min_word_normaliser = 0;
  options.similarity.min_group_normaliser = 0;
  options.similarity.min_distribution_normaliser = 0;
  LoopDetector detector(vocabulary, options);
  std::ostringstream csv;
  csv << "frame,features,word_normaliser,group_normaliser,distribution_normaliser,candidates,"
         "rank_w,rank_g,rank_d,rank_sim,rank_eta,best_true_eta,best_false_eta\n";
  const char* names[] = {"eta_w", "eta_g", "eta_d", "eta_sim", "eta"};
  std::vector<std::vector<int>> ranks(5);
  std::vector<double> word_norm, group_norm, dist_norm, feature_counts;
  ProgressBar bar("dump-candidates", a.quiet);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    KeyframeInput input;
    input.stamp = frames[i].stamp;
    input.features = frames[i].features;
    input.intrinsics = frames[i].intrinsics;
    input.odometer = frames[i].odometer;
    const LoopResult r = detector.process(input);
    bar(i + 1, frames.size());
    feature_counts.push_back(static_cast<double>(frames[i].features.size()));
    if (r.status != LoopStatus::kDatabaseTooSmall && r.status != LoopStatus::kNoFeatures) {
      word_norm.push_back(r.word_normaliser);
      group_norm.push_back(r.group_normaliser);
      dist_norm.push_back(r.distribution_normaliser);
    }
    const auto it = gt.loops.find(static_cast<int>(i));
    if (it == gt.loops.end() || it->second.empty()) continue;
    const std::vector<CandidateScores>& c = detector.lastCandidates();
    int rank[5] = {0, 0, 0, 0, 0};
    double best_true = -1, best_false = -1;
    for (int s = 0; s < 5; ++s) {
      auto value = [s](const CandidateScores& x) {
        return s == 0 ? x.eta_w : s == 1 ? x.eta_g : s == 2 ? x.eta_d : s == 3 ? x.eta_sim : x.eta;
      };
      double true_best = -std::numeric_limits<double>::infinity();
      bool found = false;
      for (const CandidateScores& x : c) {
        if (gt.contains(static_cast<int>(i), static_cast<int>(x.entry))) {
          true_best = std::max(true_best, value(x));
          found = true;
        }
      }
      if (!found) continue;
      int better = 0;
      for (const CandidateScores& x : c) {
        if (!gt.contains(static_cast<int>(i), static_cast<int>(x.entry)) && value(x) > true_best) {
          ++better;
        }
      }
      rank[s] = better + 1;
      if (s == 4) {
        best_true = true_best;
        for (const CandidateScores& x : c) {
          if (!gt.contains(static_cast<int>(i), static_cast<int>(x.entry))) {
            best_false = std::max(best_false, x.eta);
          }
        }
      }
    }
    for (int s = 0; s < 5; ++s) ranks[s].push_back(rank[s]);
    csv << i << "," << frames[i].features.size() << "," << r.word_normaliser << ","
        << r.group_normaliser << "," << r.distribution_normaliser << "," << c.size();
    for (int s = 0; s < 5; ++s) csv << "," << rank[s];
    csv << "," << best_true << "," << best_false << "\n";
  }
  writeFileAtomically(a.dump_candidates, csv.str());
  auto quantiles = [](std::vector<double> v) {
    if (v.empty()) return std::string("-");
    std::sort(v.begin(), v.end());
    auto q = [&v](double f) { return v[static_cast<std::size_t>(f * (v.size() - 1))]; };
    return fmt("%.4g / %.4g / %.4g / %.4g", q(0.05), q(0.25), q(0.5), q(0.95));
  };
  std::printf("features per frame (p5 / p25 / median / p95): %s\n", quantiles(feature_counts).c_str());
  std::printf("word normaliser s_w(t, t-1):  %s\n", quantiles(word_norm).c_str());
  std::printf("group normaliser s_g(t, t-1): %s\n", quantiles(group_norm).c_str());
  std::printf("distribution normaliser:      %s\n", quantiles(dist_norm).c_str());
  std::printf("%zu queries with a revisit; rank of the best true match among the candidates:\n",
              ranks[0].size());
  std::printf("score     top-1   top-5  top-20  absent  median rank (when present)\n");
  for (int s = 0; s < 5; ++s) {
    int top1 = 0, top5 = 0, top20 = 0, absent = 0;
    std::vector<double> present;
    for (int x : ranks[s]) {
      if (x == 0) { ++absent; continue; }
      top1 += x == 1;
      top5 += x <= 5;
      top20 += x <= 20;
      present.push_back(x);
    }
    std::sort(present.begin(), present.end());
    const double n = std::max<std::size_t>(1, ranks[s].size());
    std::printf("%-8s %6.3f  %6.3f  %6.3f  %6.3f  %g\n", names[s], top1 / n, top5 / n, top20 / n,
                absent / n, present.empty() ? 0.0 : present[present.size() / 2]);
  }
  std::printf("per-query CSV: %s\n", a.dump_candidates.c_str());
  return 0;
}

struct RowResult {
  DetectorRun run;  // at the configured threshold
  PrPoint at_threshold;
  std::vector<PrPoint> curve;
  PrPoint full_precision;
};

int run(int argc, char** argv) {
  const Args a = parseArgs(argc, argv);
  PipelineOptions pipeline;
  if (!a.config.empty()) pipeline = loadParameterFile(a.config);
  pipeline.validate();
  std::shared_ptr<const Vocabulary> vocabulary =
      std::make_shared<const Vocabulary>(loadVocabulary(a.vocabulary));
  const FeatureExtractor extractor(pipeline.features);
  GroundTruth gt;
  const bool has_gt = !a.gt.empty();
  if (has_gt) gt = readGroundTruth(a.gt);
  ::mkdir(a.output.c_str(), 0755);
  struct stat st;
  if (::stat(a.output.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    throw IoError("cannot create the output folder " + a.output);
  }

  std::vector<FrameInput> frames = loadFrames(a, extractor);
  if (!a.odometry.empty()) {
    const std::vector<double> odometer = readOdometry(a.odometry);
    if (odometer.size() < frames.size()) {
      throw FormatError(a.odometry + ": odometers for " + std::to_string(odometer.size()) +
                        " frames, the input has " + std::to_string(frames.size()));
    }
    for (std::size_t i = 0; i < frames.size(); ++i) frames[i].odometer = odometer[i];
  }
  if (has_gt && !gt.loops.empty() && gt.loops.rbegin()->first >= static_cast<int>(frames.size()) &&
      a.max_frames == 0) {
    std::fprintf(stderr, "warning: the ground truth names frame %d but the input has %zu frames\n",
                 gt.loops.rbegin()->first, frames.size());
  }
  // Queries beyond the frames used do not count in the recall.
  GroundTruth used_gt;
  for (const auto& kv : gt.loops) {
    if (kv.first < static_cast<int>(frames.size())) used_gt.loops.insert(kv);
  }

  if (!a.dump_candidates.empty()) {
    if (!has_gt) throw std::invalid_argument("--dump-candidates needs --gt FILE");
    return dumpCandidates(a, vocabulary, pipeline.detector, frames, used_gt);
  }
  const std::vector<std::string> rows = a.ablation ? a.rows : std::vector<std::string>{"bowg"};
  const double threshold = pipeline.detector.islands.min_score;
  const auto sameThreshold = [threshold](double t) { return std::abs(t - threshold) < 1e-12; };
  // The configured operating point is a point of the curve: its run exists
  // anyway, and a grid that steps over it would hide the preset's own result.
  std::vector<double> thresholds = a.thresholds;
  if (std::none_of(thresholds.begin(), thresholds.end(), sameThreshold)) {
    thresholds.push_back(threshold);
    std::sort(thresholds.begin(), thresholds.end(), std::greater<double>());
  }
  std::vector<RowResult> results;
  std::vector<LoopDetectorOptions> row_options;
  // 1. One run per row at the configured threshold, alone on the machine:
  // its timings are the ones reported.
  for (const std::string& row : rows) {
    row_options.push_back(a.ablation ? LoopDetectorOptions::ablation(row, pipeline.detector)
                                     : pipeline.detector);
    RowResult r;
    ProgressBar bar(row + " @" + fmt("%.2f", threshold), a.quiet);
    r.run = runDetector(vocabulary, row_options.back(), frames, row, std::ref(bar));
    if (has_gt) r.at_threshold = operatingPoint(r.run, used_gt);
    results.push_back(std::move(r));
  }
  // 2. The exact PR curves: every (row, other threshold) run, side by side.
  std::vector<DetectorRun> sweep_runs;
  if (has_gt && a.sweep == "rerun") {
    std::vector<RunRequest> requests;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      for (double t : thresholds) {
        if (sameThreshold(t)) continue;
        RunRequest q{rows[i], row_options[i]};
        q.options.islands.min_score = t;
        requests.push_back(q);
      }
    }
    ProgressBar bar("sweep (" + std::to_string(requests.size()) + " runs)", a.quiet);
    sweep_runs = runDetectorsInParallel(vocabulary, requests, frames, a.jobs, std::ref(bar));
  }
  std::size_t next_sweep_run = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string& row = rows[i];
    const LoopDetectorOptions& options = row_options[i];
    RowResult& r = results[i];
    if (has_gt) {
      if (a.sweep == "rerun") {
        for (double t : thresholds) {
          r.curve.push_back(sameThreshold(t) ? r.at_threshold
                                             : operatingPoint(sweep_runs[next_sweep_run++], used_gt));
        }
      } else {
        LoopDetectorOptions o = options;
        o.islands.min_score = thresholds.back();  // the lowest
        ProgressBar b(row + " @" + fmt("%.2f", o.islands.min_score), a.quiet);
        const DetectorRun low = std::abs(o.islands.min_score - threshold) < 1e-12
                                    ? r.run
                                    : runDetector(vocabulary, o, frames, row, std::ref(b));
        r.curve = precisionRecallCurve(detectionsOf(low), used_gt);
      }
      r.full_precision = recallAtFullPrecision(r.curve);
    }
    writeFileAtomically(a.output + "/keyframes_" + row + ".csv",
                        keyframesCsv(r.run, has_gt ? &used_gt : nullptr));
    writeFileAtomically(a.output + "/detections_" + row + ".csv", detectionsToCsv(detectionsOf(r.run)));
  }

  // Summary.
  std::ostringstream s;
  s << "input: " << (a.bag.empty() ? a.images : a.bag) << " (" << frames.size() << " frames)\n"
    << "vocabulary: " << a.vocabulary << "  config: " << (a.config.empty() ? "(defaults)" : a.config)
    << "  min_score: " << threshold << "\n";
  if (has_gt) {
    s << "ground truth: " << a.gt << " (" << used_gt.positives() << " queries with a revisit)\n"
      << "PR sweep: " << (a.sweep == "rerun" ? "detector re-run per min_score" : "final score of one run at the lowest min_score")
      << ", " << thresholds.size() << " thresholds " << thresholds.back() << ".." << thresholds.front() << "\n\n";
    s << "at min_score " << threshold << "; R@100%P = recall at 100 % precision (its threshold)\n"
      << "row            precision  recall      F1   TP   FP  R@100%P (threshold)  loops\n";
    for (const RowResult& r : results) {
      char line[256];
      std::snprintf(line, sizeof(line), "%-14s %9.3f %7.3f %7.3f %4d %4d  %7.3f (%9s)  %5zu\n",
                    r.run.name.c_str(), r.at_threshold.precision, r.at_threshold.recall,
                    r.at_threshold.f1, r.at_threshold.true_positives, r.at_threshold.false_positives,
                    r.full_precision.recall,
                    std::isinf(r.full_precision.threshold) ? "none" : fmt("%.3f", r.full_precision.threshold).c_str(),
                    detectionsOf(r.run).size());
      s << line;
    }
    if (a.ablation) {
      // The comparison the ablation is for, in one line (rows: bow first,
      // the full method last).
      const PrPoint& bow = results.front().full_precision;
      const PrPoint& full = results.back().full_precision;
      s << "\nrecall at 100 % precision: full BoWG " << fmt("%.3f", full.recall)
        << ", pure bag of words " << fmt("%.3f", bow.recall);
      if (bow.recall > 0) s << " (" << fmt("%.1f", full.recall / bow.recall) << "x)";
      s << "\n";
    }
  } else {
    s << "\nno ground truth: counts only\n";
    for (const RowResult& r : results) {
      std::map<std::string, int> counts;
      for (const KeyframeRecord& k : r.run.keyframes) ++counts[toString(k.status)];
      s << r.run.name << ":";
      for (const auto& kv : counts) s << " " << kv.first << "=" << kv.second;
      s << "\n";
      for (const KeyframeRecord& k : r.run.keyframes) {
        if (k.match < 0) continue;
        s << "  loop " << k.frame << " -> " << k.match << "  score " << fmt("%.3f", k.candidate_score)
          << "  inliers " << k.inliers << "\n";
      }
    }
  }
  s << "\nper-keyframe timing (ms): mean / median / p95 / max\n";
  for (const RowResult& r : results) {
    s << r.run.name << " (" << fmt("%.1f", r.run.wall_seconds) << " s for the run):\n";
    for (const auto& kv : stageTimingStats(r.run)) {
      char line[160];
      std::snprintf(line, sizeof(line), "  %-15s %7.2f %7.2f %7.2f %7.2f\n", kv.first.c_str(),
                    kv.second.mean, kv.second.median, kv.second.p95, kv.second.max);
      s << line;
    }
  }
  s << "\ndetector time vs database size (ms, mean / max):\n";
  std::ostringstream size_csv;
  size_csv << "method,first_size,last_size,mean_ms,median_ms,p95_ms,max_ms\n";
  for (const RowResult& r : results) {
    s << r.run.name << ":";
    for (const TimeVsSize& t : timeVersusDatabaseSize(r.run, 5)) {
      s << "  [" << t.first << "-" << t.last << "] " << fmt("%.2f/%.2f", t.total_ms.mean, t.total_ms.max);
    }
    s << "\n";
    for (const TimeVsSize& t : timeVersusDatabaseSize(r.run, 20)) {
      size_csv << r.run.name << "," << t.first << "," << t.last << "," << t.total_ms.mean << ","
               << t.total_ms.median << "," << t.total_ms.p95 << "," << t.total_ms.max << "\n";
    }
  }
  writeFileAtomically(a.output + "/time_vs_database_size.csv", size_csv.str());
  if (has_gt) {
    std::vector<NamedCurve> curves;
    for (const RowResult& r : results) curves.push_back({r.run.name, r.curve});
    writePrCurvesCsv(a.output + "/pr_curves.csv", curves);
    writePrPlot(a.output + "/pr_curve.png", curves,
                "BoWG precision-recall (" + std::to_string(frames.size()) + " frames)");
  }
  s << "\noutputs in " << a.output << ": summary.txt, keyframes_<row>.csv, detections_<row>.csv, "
    << "time_vs_database_size.csv" << (has_gt ? ", pr_curves.csv, pr_curve.png" : "") << "\n";
  writeFileAtomically(a.output + "/summary.txt", s.str());
  std::cout << s.str();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bowg_evaluate: %s\n", e.what());
    return 1;
  }
}
