// End-to-end tests of the bowg_evaluate command line: the configured
// min_score is always a point of the exact PR sweep, the sweep's result does
// not depend on how many threads ran it, and bad options are refused with a
// message and a non-zero exit code; bad images in a folder or a bag are
// skipped and counted by reason without ending the run.
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/CompressedImage.h>
#include <std_msgs/Float64.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "encoded_test_images.h"
#include "shell_command.h"

namespace bowg {
namespace {

using tool_test::readAll;
using tool_test::run;

const std::string kDir = std::string(BOWG_TEST_OUTPUT_DIR) + "/evaluate_cli_test";
const std::string kEvaluate = BOWG_EVALUATE_BIN;

class EvaluateCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_EQ(run("rm -rf " + kDir + " && mkdir -p " + kDir), 0);
    // 300 frames of 320 x 240, 10 cm apart: 30 m of the route, past the
    // first closed circuit, so there are revisits (and loops to compare).
    ASSERT_EQ(run(std::string(BOWG_GENERATOR_BIN) + " --images " + kDir +
                      "/frames --frames 300 --width 320 --height 240 --speed 1.0",
                  kDir + "/generate.log"),
              0)
        << readAll(kDir + "/generate.log");
    writeFile(kDir + "/config.yaml",
              "feature_detector: gftt\nmin_score: 0.7\nrecent_exclusion: 30\n"
              "direct_index_level: 2\n");
  }

  static void writeFile(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::trunc);
    out << text;
    ASSERT_TRUE(out.good()) << path;
  }

  // A fresh folder `dir` holding copies of the first `count` frames.
  static void copyFirstFrames(const std::string& dir, int count) {
    ASSERT_EQ(run("(rm -rf " + dir + " && mkdir -p " + dir + " && for i in $(seq -f %06g 0 " +
                  std::to_string(count - 1) + "); do cp " + kDir + "/frames/frame_$i.png " + dir +
                  "/; done)"),
              0);
  }

  // bowg_evaluate on the image folder `dir` without ground truth, at the
  // configuration's threshold only.
  static std::string evaluateFolder(const std::string& dir, const std::string& config,
                                    const std::string& out) {
    return kEvaluate + " --quiet --images " + dir + " --vocabulary " + BOWG_DEFAULT_VOCABULARY +
           " --config " + config + " --thresholds 0.7 --output " + out;
  }

  // The folder's frame i as a bag's PNG image, stamped 100 + i s.
  static sensor_msgs::CompressedImage compressedFrame(int i) {
    sensor_msgs::CompressedImage msg;
    msg.header.stamp = ros::Time(100 + i, 0);
    msg.format = "mono8; png compressed";
    char name[64];
    std::snprintf(name, sizeof name, "/frames/frame_%06d.png", i);
    const std::string png = readAll(kDir + name);
    msg.data.assign(png.begin(), png.end());
    return msg;
  }

  // The sum of the integer column `name` of a CSV with a header.
  static long columnSum(const std::string& csv, const std::string& name) {
    const tool_test::Table rows = tool_test::readCsv(csv);
    if (rows.empty()) {
      ADD_FAILURE() << csv << " is missing or empty";
      return 0;
    }
    const std::vector<std::string>& header = rows.front();
    const auto column = std::find(header.begin(), header.end(), name) - header.begin();
    EXPECT_LT(static_cast<std::size_t>(column), header.size()) << name << " not in " << csv;
    long sum = 0;
    for (std::size_t r = 1; r < rows.size(); ++r)
      if (static_cast<std::size_t>(column) < rows[r].size()) sum += std::stol(rows[r][column]);
    return sum;
  }

  static std::string evaluate(const std::string& extra, const std::string& out) {
    return kEvaluate + " --quiet --images " + kDir + "/frames --gt " + kDir +
           "/frames/ground_truth.txt --vocabulary " + BOWG_DEFAULT_VOCABULARY + " --config " +
           kDir + "/config.yaml --output " + kDir + "/" + out + " " + extra;
  }
};

TEST_F(EvaluateCli, TheConfiguredThresholdIsAlwaysAPointOfTheSweep) {
  ASSERT_EQ(run(evaluate("--thresholds 0.5,0.9 --jobs 2", "two"), kDir + "/two.log"), 0)
      << readAll(kDir + "/two.log");
  const std::string summary = readAll(kDir + "/two/summary.txt");
  EXPECT_NE(summary.find("min_score: 0.7"), std::string::npos) << summary;
  EXPECT_NE(summary.find("3 thresholds 0.5..0.9"), std::string::npos) << summary;
  const std::string curve = readAll(kDir + "/two/pr_curves.csv");
  EXPECT_NE(curve.find("\nbowg,0.9,"), std::string::npos) << curve;
  EXPECT_NE(curve.find("\nbowg,0.7,"), std::string::npos) << curve;  // the configured one
  EXPECT_NE(curve.find("\nbowg,0.5,"), std::string::npos) << curve;
}

// The run split into two missions where the route is driven again: the
// second mission's loops into the first are scored on their own, and a
// missions file that breaks the rules stops the run naming the file.
TEST_F(EvaluateCli, MissionsAreStartedAndTheLoopsAcrossThemScoredOnTheirOwn) {
  writeFile(kDir + "/missions.csv", "# first_frame,mission_id,name\n0,1,first\n150,2,second\n");
  ASSERT_EQ(run(evaluate("--thresholds 0.7 --missions " + kDir + "/missions.csv", "missions"),
                kDir + "/missions.log"),
            0)
      << readAll(kDir + "/missions.log");
  const std::string summary = readAll(kDir + "/missions/summary.txt");
  const std::size_t table = summary.find("across missions");
  ASSERT_NE(table, std::string::npos) << summary;
  int tp = -1, fp = -1, positives = -1;
  double precision = -1, recall = -1;
  const std::size_t row = summary.find("\nbowg ", table);
  ASSERT_NE(row, std::string::npos) << summary;
  ASSERT_EQ(std::sscanf(summary.c_str() + row, "\nbowg %lf %lf %d %d %d", &precision, &recall, &tp,
                        &fp, &positives),
            5)
      << summary;
  EXPECT_GT(positives, 0) << "the second mission revisits the first";
  EXPECT_GT(tp, 0) << summary;
  writeFile(kDir + "/bad_missions.csv", "0,1,first\n150,1,second\n");
  const std::string log = kDir + "/bad_missions.log";
  EXPECT_NE(run(evaluate("--thresholds 0.7 --missions " + kDir + "/bad_missions.csv", "bad"), log),
            0);
  EXPECT_NE(readAll(log).find("bad_missions.csv:2: mission id twice"), std::string::npos)
      << readAll(log);
}

// The "across missions" row of a summary ("" when it has none).
std::string acrossMissionsRow(const std::string& summary) {
  const std::size_t table = summary.find("across missions");
  if (table == std::string::npos) return "";
  const std::size_t row = summary.find("\nbowg ", table);
  if (row == std::string::npos) return "";
  return summary.substr(row + 1, summary.find('\n', row + 1) - row - 1);
}

// The first mission saved as a map and the second run on it (--skip-frames
// keeps the folder's numbering): the loops into the first mission are those
// of the run in one go.
TEST_F(EvaluateCli, TheFirstMissionAsAMapGivesTheLoopsOfOneRun) {
  writeFile(kDir + "/two_missions.csv", "0,1,first\n150,2,second\n");
  const std::string missions = " --thresholds 0.7 --missions " + kDir + "/two_missions.csv";
  ASSERT_EQ(run(evaluate(missions, "one_go"), kDir + "/one_go.log"), 0)
      << readAll(kDir + "/one_go.log");
  ASSERT_EQ(run(evaluate(missions + " --max-frames 150 --save-map " + kDir + "/first.map", "first"),
                kDir + "/first.log"),
            0)
      << readAll(kDir + "/first.log");
  ASSERT_EQ(run(evaluate(missions + " --skip-frames 150 --map " + kDir + "/first.map", "second"),
                kDir + "/second.log"),
            0)
      << readAll(kDir + "/second.log");
  const std::string one_go = acrossMissionsRow(readAll(kDir + "/one_go/summary.txt"));
  const std::string second = readAll(kDir + "/second/summary.txt");
  ASSERT_FALSE(one_go.empty());
  EXPECT_EQ(acrossMissionsRow(second), one_go) << second;
  EXPECT_NE(second.find("(150 frames)"), std::string::npos) << second;
  EXPECT_NE(second.find("reference maps: " + kDir +
                        "/first.map (150 keyframes, entries 0-149; "
                        "missions 1 'first' 150)"),
            std::string::npos)
      << second;
  int tp = 0;
  ASSERT_EQ(std::sscanf(one_go.c_str(), "bowg %*f %*f %d", &tp), 1) << one_go;
  EXPECT_GT(tp, 0) << one_go;
  // Without a ground truth: the loops into the maps are counted.
  ASSERT_EQ(run(evaluateFolder(kDir + "/frames", kDir + "/config.yaml", kDir + "/counts") +
                    " --skip-frames 150 --mission-name again --map " + kDir + "/first.map",
                kDir + "/counts.log"),
            0)
      << readAll(kDir + "/counts.log");
  EXPECT_NE(readAll(kDir + "/counts/summary.txt").find(" into the reference maps)"),
            std::string::npos)
      << readAll(kDir + "/counts/summary.txt");
}

// A new survey's odometer starts at 0 again, below the map's last keyframe's:
// it continues from the map's, as the nodelet's does after a load.
TEST_F(EvaluateCli, ANewSurveysOdometerContinuesTheMaps) {
  const std::string odometry = " --odometry " + kDir + "/frames/odometry.csv --odometry-poses " +
                               kDir + "/frames/odometry.csv";
  ASSERT_EQ(run(evaluate("--thresholds 0.7 --max-frames 150 --save-map " + kDir +
                             "/odometry_first.map" + odometry,
                         "odometry_first"),
                kDir + "/odometry_first.log"),
            0)
      << readAll(kDir + "/odometry_first.log");
  copyFirstFrames(kDir + "/again_frames", 100);
  const std::string log = kDir + "/odometry_again.log";
  ASSERT_EQ(
      run(evaluateFolder(kDir + "/again_frames", kDir + "/config.yaml", kDir + "/odometry_again") +
              odometry + " --map " + kDir + "/odometry_first.map",
          log),
      0)
      << readAll(log);
  EXPECT_NE(readAll(kDir + "/odometry_again/summary.txt").find("live odometers continue the maps'"),
            std::string::npos)
      << readAll(kDir + "/odometry_again/summary.txt");
}

TEST_F(EvaluateCli, BadMapOptionsAreRefusedNamingTheCause) {
  const std::string log = kDir + "/bad_map.log";
  EXPECT_NE(run(evaluate("--thresholds 0.7 --map " + kDir + "/no_such.map", "bad_map"), log), 0);
  EXPECT_NE(readAll(log).find("no_such.map"), std::string::npos) << readAll(log);
  EXPECT_NE(run(evaluate("--thresholds 0.7 --mission-id 4", "bad_map"), log), 0);
  EXPECT_NE(readAll(log).find("--mission-id needs --mission-name"), std::string::npos)
      << readAll(log);
  EXPECT_NE(run(evaluate("--thresholds 0.7 --skip-frames 300", "bad_map"), log), 0);
  EXPECT_NE(readAll(log).find("leaves none of the 300 frames"), std::string::npos) << readAll(log);
  EXPECT_NE(
      run(evaluate("--thresholds 0.7 --mission-name " + std::string(300, 'x'), "bad_map"), log), 0);
  EXPECT_NE(readAll(log).find("--mission-name"), std::string::npos) << readAll(log);
}

TEST_F(EvaluateCli, TheSweepDoesNotDependOnTheNumberOfThreads) {
  ASSERT_EQ(run(evaluate("--thresholds 0.3,0.5,0.9 --jobs 1", "one_thread")), 0);
  ASSERT_EQ(run(evaluate("--thresholds 0.3,0.5,0.9 --jobs 2", "two_threads")), 0);
  const std::string a = readAll(kDir + "/one_thread/pr_curves.csv");
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a, readAll(kDir + "/two_threads/pr_curves.csv"));
  // Loops found at the configured threshold, and points with loops on the
  // curve: the comparison is not between empty runs.
  const std::string loops = readAll(kDir + "/one_thread/detections_bowg.csv");
  EXPECT_NE(loops.find('\n'), loops.rfind('\n')) << "no loop at min_score 0.7";
  EXPECT_EQ(loops, readAll(kDir + "/two_threads/detections_bowg.csv"));
}

TEST_F(EvaluateCli, BadImagesAreSkippedCountedByReasonAndKeepTheirFrameNumber) {
  // A copy of the first 40 frames with frame 5 emptied, frame 9 replaced by
  // garbage, frame 12 by a JPEG cut short, frame 15 by a directory, frame 20
  // by a FIFO nobody writes (opening it would block) and frame 25 by a link
  // to /dev/zero (endless): the run goes on, says which images it skipped
  // and why, and frame 10 is still frame 10 (a frame without features).
  const std::string dir = kDir + "/damaged";
  copyFirstFrames(dir, 40);
  test::writeBytes(dir + "/frame_000012.png", test::truncatedJpeg());
  // In a subshell: run() redirects the command's output.
  ASSERT_EQ(run("(: > " + dir + "/frame_000005.png && echo garbage > " + dir +
                "/frame_000009.png && cd " + dir +
                " && rm frame_000015.png frame_000020.png frame_000025.png && mkdir "
                "frame_000015.png && mkfifo frame_000020.png && ln -s /dev/zero "
                "frame_000025.png)"),
            0);
  const std::string out = kDir + "/damaged_out";
  const std::string cmd = evaluateFolder(dir, kDir + "/config.yaml", out);
  ASSERT_EQ(run("timeout 300 " + cmd, kDir + "/damaged.log"), 0) << readAll(kDir + "/damaged.log");
  const std::string log = readAll(kDir + "/damaged.log");
  for (const char* expected :
       {"frame_000005.png skipped (empty: the file is empty)",
        "frame_000009.png skipped (unsupported_format: not a PNG, JPEG, BMP or binary PNM",
        "frame_000012.png skipped (truncated: JPEG without its end-of-image marker",
        "frame_000015.png skipped (file_refused: ", "frame_000020.png skipped (file_refused: ",
        "frame_000025.png skipped (file_refused: ",
        "6 of 40 images skipped (1 empty, 3 file_refused, 1 unsupported_format, 1 truncated)"}) {
    EXPECT_NE(log.find(expected), std::string::npos) << expected << "\n" << log;
  }
  const std::string keyframes = readAll(out + "/keyframes_bowg.csv");
  for (const char* row : {"\n5,5.000000,no_features,", "\n9,9.000000,no_features,",
                          "\n12,12.000000,no_features,", "\n25,25.000000,no_features,"}) {
    EXPECT_NE(keyframes.find(row), std::string::npos) << row << keyframes;
  }
  EXPECT_NE(keyframes.find("\n39,"), std::string::npos) << keyframes;
}

// The same bad images in a bag's CompressedImage messages are skipped with
// the same reasons as in a folder; an empty message does not end the run.
TEST_F(EvaluateCli, BadCompressedBagImagesAreSkippedWithTheFolderReasons) {
  const std::string bag_path = kDir + "/damaged.bag";
  {
    rosbag::Bag bag(bag_path, rosbag::bagmode::Write);
    for (int i = 0; i < 20; ++i) {
      sensor_msgs::CompressedImage msg = compressedFrame(i);
      if (i == 5) msg.data.clear();
      if (i == 9) msg.data = test::truncatedJpeg();
      if (i == 12) msg.data = test::pngDeclaring(30000, 30000);
      bag.write("/camera/image_raw/compressed", msg.header.stamp, msg);
    }
  }
  const std::string out = kDir + "/damaged_bag_out";
  const std::string cmd = kEvaluate + " --quiet --bag " + bag_path +
                          " --image-topic /camera/image_raw/compressed --vocabulary " +
                          BOWG_DEFAULT_VOCABULARY + " --config " + kDir +
                          "/config.yaml --thresholds 0.7 --output " + out;
  ASSERT_EQ(run("timeout 300 " + cmd, kDir + "/damaged_bag.log"), 0)
      << readAll(kDir + "/damaged_bag.log");
  const std::string log = readAll(kDir + "/damaged_bag.log");
  for (const char* expected :
       {"frame 5 skipped (empty: bag '", "frame 9 skipped (truncated: bag '",
        "at 109.000000: JPEG without its end-of-image marker", "frame 12 skipped (too_large: bag '",
        "at 112.000000: PNG 30000 x 30000 = 900000000 pixels",
        "3 of 20 images skipped (1 empty, 1 truncated, 1 too_large)"}) {
    EXPECT_NE(log.find(expected), std::string::npos) << expected << "\n" << log;
  }
  const std::string keyframes = readAll(out + "/keyframes_bowg.csv");
  EXPECT_NE(keyframes.find("\n9,109.000000,no_features,"), std::string::npos) << keyframes;
  EXPECT_NE(keyframes.find("\n19,"), std::string::npos) << keyframes;
}

TEST_F(EvaluateCli, ImagesAboveMaxImagePixelsAreSkippedAndKeepTheirFrameNumber) {
  // 20 frames of 320 x 240 with frame 7 replaced by a 321 x 240 render, and
  // max_image_pixels = 320 x 240 in the configuration.
  const std::string dir = kDir + "/oversize";
  copyFirstFrames(dir, 20);
  ASSERT_EQ(run(std::string(BOWG_GENERATOR_BIN) + " --images " + kDir +
                    "/wide --frames 8 --width 321 --height 240 --speed 1.0",
                kDir + "/wide.log"),
            0)
      << readAll(kDir + "/wide.log");
  ASSERT_EQ(run("cp " + kDir + "/wide/frame_000007.png " + dir + "/frame_000007.png"), 0);
  writeFile(kDir + "/small_limit.yaml",
            "feature_detector: gftt\nmin_score: 0.7\nrecent_exclusion: 30\n"
            "direct_index_level: 2\nmax_image_pixels: 76800\n");
  const std::string out = kDir + "/oversize_out";
  const std::string cmd = evaluateFolder(dir, kDir + "/small_limit.yaml", out);
  ASSERT_EQ(run(cmd, kDir + "/oversize.log"), 0) << readAll(kDir + "/oversize.log");
  const std::string log = readAll(kDir + "/oversize.log");
  // Refused from the PNG header, before decoding.
  EXPECT_NE(log.find("frame_000007.png skipped (too_large: PNG 321 x 240 = 77040 pixels, more "
                     "than max_image_pixels 76800)"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("1 of 20 images skipped (1 too_large)"), std::string::npos) << log;
  const std::string keyframes = readAll(out + "/keyframes_bowg.csv");
  EXPECT_NE(keyframes.find("\n7,7.000000,no_features,"), std::string::npos) << keyframes;
  EXPECT_EQ(keyframes.find("\n6,6.000000,no_features,"), std::string::npos) << keyframes;
}

TEST_F(EvaluateCli, BadOptionsAreRefusedWithAMessage) {
  const std::string log = kDir + "/bad.log";
  EXPECT_NE(run(evaluate("--jobs -1", "bad"), log), 0);
  EXPECT_NE(readAll(log).find("--jobs"), std::string::npos) << readAll(log);
  EXPECT_NE(run(evaluate("--jobs 1.5", "bad"), log), 0);
  EXPECT_NE(readAll(log).find("--jobs"), std::string::npos) << readAll(log);
  EXPECT_NE(run(evaluate("--thresholds 1:0:2", "bad"), log), 0);
  EXPECT_NE(readAll(log).find("--thresholds"), std::string::npos) << readAll(log);
  EXPECT_NE(run(evaluate("--sweep sideways", "bad"), log), 0);
  EXPECT_NE(readAll(log).find("--sweep"), std::string::npos) << readAll(log);
  // A missing intrinsics file is named.
  EXPECT_NE(run(evaluate("--intrinsics " + kDir + "/no_intrinsics.csv", "bad"), log), 0);
  EXPECT_NE(readAll(log).find(kDir + "/no_intrinsics.csv"), std::string::npos) << readAll(log);
  // Odometry positions for fewer frames than the input: the file is named.
  writeFile(kDir + "/short_odometry.csv", "frame,x,y,z\n0,0,0,0\n1,0.1,0,0\n");
  EXPECT_NE(run(evaluate("--odometry-poses " + kDir + "/short_odometry.csv", "bad"), log), 0);
  EXPECT_NE(readAll(log).find(kDir + "/short_odometry.csv: odometry positions for 2 frames"),
            std::string::npos)
      << readAll(log);
}

// --odom-topic reads nav_msgs/Odometry from a bag: a folder, a second source
// of the same path, or a topic of another type is refused, naming the cause.
TEST_F(EvaluateCli, BadOdomTopicsAreRefusedNamingTheCause) {
  const std::string log = kDir + "/bad_odom.log";
  EXPECT_NE(run(evaluate("--odom-topic /odom", "bad_odom"), log), 0);
  EXPECT_NE(readAll(log).find("--odom-topic is for --bag"), std::string::npos) << readAll(log);
  const std::string bag_path = kDir + "/float_odom.bag";
  {
    rosbag::Bag bag(bag_path, rosbag::bagmode::Write);
    for (int i = 0; i < 3; ++i) {
      const sensor_msgs::CompressedImage msg = compressedFrame(i);
      bag.write("/camera/image_raw/compressed", msg.header.stamp, msg);
      std_msgs::Float64 metres;
      metres.data = 0.1 * i;
      bag.write("/odom", msg.header.stamp, metres);
    }
  }
  const std::string cmd = kEvaluate + " --quiet --bag " + bag_path +
                          " --image-topic /camera/image_raw/compressed --vocabulary " +
                          BOWG_DEFAULT_VOCABULARY + " --config " + kDir + "/config.yaml --output " +
                          kDir + "/bad_odom --odom-topic /odom";
  EXPECT_NE(run("timeout 300 " + cmd, log), 0);
  EXPECT_NE(readAll(log).find(bag_path + ": /odom is not nav_msgs/Odometry"), std::string::npos)
      << readAll(log);
  writeFile(kDir + "/odometers.csv", "frame,odometer\n0,0\n1,0.1\n2,0.2\n");
  EXPECT_NE(run("timeout 300 " + cmd + " --odometry " + kDir + "/odometers.csv", log), 0);
  EXPECT_NE(readAll(log).find("give --odom-topic or --odometry/--odometry-poses, not both"),
            std::string::npos)
      << readAll(log);
}

// A bag's position whose orientation is not a unit quaternion (a driver's
// all-zero one) gives its keyframe no heading: said on stderr with the count
// and the first orientation, and the summary says how many frames have one.
TEST_F(EvaluateCli, BagPositionsWithoutAUnitOrientationAreCountedAndCarryNoHeading) {
  const std::string bag_path = kDir + "/zero_orientation.bag";
  {
    rosbag::Bag bag(bag_path, rosbag::bagmode::Write);
    for (int i = 0; i < 3; ++i) {
      const sensor_msgs::CompressedImage msg = compressedFrame(i);
      nav_msgs::Odometry odom;
      odom.header.stamp = msg.header.stamp;
      odom.pose.pose.position.x = 0.1 * i;
      odom.pose.pose.orientation.w = i == 2 ? 1.0 : 0.0;  // frames 0, 1: all zero
      bag.write("/odom", msg.header.stamp, odom);
      bag.write("/camera/image_raw/compressed", msg.header.stamp, msg);
    }
  }
  const std::string log = kDir + "/zero_orientation.log";
  ASSERT_EQ(run("timeout 300 " + kEvaluate + " --quiet --bag " + bag_path +
                    " --image-topic /camera/image_raw/compressed --vocabulary " +
                    BOWG_DEFAULT_VOCABULARY + " --config " + kDir + "/config.yaml --output " +
                    kDir + "/zero_orientation --odom-topic /odom",
                log),
            0)
      << readAll(log);
  EXPECT_NE(readAll(log).find("warning: 2 of 3 positions on /odom have an orientation that is "
                              "not a unit quaternion (the first: (0, 0, 0, 0))"),
            std::string::npos)
      << readAll(log);
  const std::string summary = readAll(kDir + "/zero_orientation/summary.txt");
  EXPECT_NE(summary.find("odometry: positions and odometer"), std::string::npos) << summary;
  EXPECT_NE(summary.find("a heading on 1 of 3 frames"), std::string::npos) << summary;
}

// Odometry positions reach the odometry gate: with the generator's drifting
// odometry the revisits are loops; with positions 1 km apart from frame to
// frame no candidate is within the gate.
TEST_F(EvaluateCli, OdometryPositionsFeedTheOdometryGate) {
  writeFile(kDir + "/gated.yaml",
            "feature_detector: gftt\nmin_score: 0.7\nrecent_exclusion: 30\n"
            "direct_index_level: 2\nodometry_gate_m: 0.5\nodometry_gate_drift: 0.05\n");
  std::string far = "frame,x,y,z\n";
  for (int i = 0; i < 300; ++i)
    far += std::to_string(i) + "," + std::to_string(1000 * i) + ",0,0\n";
  writeFile(kDir + "/far.csv", far);
  const std::string base = kEvaluate + " --quiet --images " + kDir + "/frames --gt " + kDir +
                           "/frames/ground_truth.txt --vocabulary " + BOWG_DEFAULT_VOCABULARY +
                           " --config " + kDir + "/gated.yaml --thresholds 0.7 --odometry " + kDir +
                           "/frames/odometry.csv --output " + kDir + "/";
  ASSERT_EQ(run(base + "near --odometry-poses " + kDir + "/frames/odometry.csv"), 0);
  ASSERT_EQ(run(base + "far --odometry-poses " + kDir + "/far.csv"), 0);
  const auto loops = [](const std::string& csv) {
    std::istringstream in(readAll(csv));
    std::string line;
    int n = -1;  // the header
    while (std::getline(in, line)) n += !line.empty();
    return n;
  };
  EXPECT_GT(loops(kDir + "/near/detections_bowg.csv"), 0);
  EXPECT_EQ(loops(kDir + "/far/detections_bowg.csv"), 0);
  // The keyframes CSV counts what the gates removed: the far positions
  // gate candidates, none of them by heading (this file has none).
  EXPECT_GT(columnSum(kDir + "/far/keyframes_bowg.csv", "candidates_gated"), 0);
  EXPECT_EQ(columnSum(kDir + "/far/keyframes_bowg.csv", "candidates_gated_heading"), 0);
}

// Headings reach the heading gate and its count: the odometry's positions
// with every odd frame facing the other way (yaw 180 deg), so a candidate
// of the other parity is refused by the heading gate alone.
TEST_F(EvaluateCli, OdometryHeadingsFeedTheHeadingGateAndItsCount) {
  writeFile(kDir + "/heading.yaml",
            "feature_detector: gftt\nmin_score: 0.7\nrecent_exclusion: 30\n"
            "direct_index_level: 2\nodometry_gate_m: 0.5\nodometry_gate_drift: 0.05\n"
            "heading_gate_deg: 30\n");
  std::istringstream in(readAll(kDir + "/frames/odometry.csv"));
  std::string line, flipped;
  std::getline(in, line);
  ASSERT_EQ(line, "frame,stamp,x,y,z,qx,qy,qz,qw");
  flipped = line + "\n";
  for (int frame = 0; std::getline(in, line); ++frame) {
    std::size_t at = 0;
    for (int commas = 0; commas < 5; ++commas) at = line.find(',', at) + 1;
    flipped += line.substr(0, at) + (frame % 2 == 0 ? "0,0,0,1" : "0,0,1,0") + "\n";
  }
  writeFile(kDir + "/flipped.csv", flipped);
  ASSERT_EQ(run(kEvaluate + " --quiet --images " + kDir + "/frames --gt " + kDir +
                "/frames/ground_truth.txt --vocabulary " + BOWG_DEFAULT_VOCABULARY + " --config " +
                kDir + "/heading.yaml --thresholds 0.7 --odometry " + kDir +
                "/frames/odometry.csv --odometry-poses " + kDir + "/flipped.csv --output " + kDir +
                "/flipped"),
            0);
  const long gated = columnSum(kDir + "/flipped/keyframes_bowg.csv", "candidates_gated");
  const long heading = columnSum(kDir + "/flipped/keyframes_bowg.csv", "candidates_gated_heading");
  EXPECT_GT(heading, 0);
  EXPECT_LE(heading, gated);
  EXPECT_NE(readAll(kDir + "/flipped/summary.txt").find("a heading on 300 of 300 frames"),
            std::string::npos);
}

// The shipped pipe presets, ORB (config/pipe.yaml) and GFTT
// (config/pipe_gftt.yaml), load and run with the bundled vocabulary on the
// rendered route, with the generator's drifting odometry and without any:
// loops at each preset's own threshold, none of them false. (On this route
// both find 0.5-0.9 of the revisits.)
TEST_F(EvaluateCli, TheShippedPipePresetsFindLoopsAndNoFalseOne) {
  for (const char* preset : {"pipe.yaml", "pipe_gftt.yaml"}) {
    for (const bool odometry : {true, false}) {
      const std::string name = std::string(preset) + (odometry ? "_odometry" : "_images");
      SCOPED_TRACE(name);
      const std::string odometry_csv = kDir + "/frames/odometry.csv";
      const std::string cmd =
          kEvaluate + " --quiet --images " + kDir + "/frames --gt " + kDir +
          "/frames/ground_truth.txt --vocabulary " + BOWG_DEFAULT_VOCABULARY + " --config " +
          BOWG_REPO_DIR + "/config/" + preset + " --sweep score --output " + kDir + "/" + name +
          (odometry ? " --odometry " + odometry_csv + " --odometry-poses " + odometry_csv : "");
      ASSERT_EQ(run(cmd, kDir + "/" + name + ".log"), 0) << readAll(kDir + "/" + name + ".log");
      // The summary's result row: precision, recall, F1, TP, FP at min_score.
      std::istringstream summary(readAll(kDir + "/" + name + "/summary.txt"));
      std::string line;
      while (std::getline(summary, line) && line.compare(0, 5, "bowg ") != 0) {
      }
      std::istringstream row(line);
      std::string method;
      double precision = 0, recall = 0, f1 = 0;
      int tp = 0, fp = -1;
      ASSERT_TRUE(row >> method >> precision >> recall >> f1 >> tp >> fp) << line;
      EXPECT_EQ(fp, 0) << line;
      EXPECT_GT(recall, 0.3) << line;
    }
  }
}

}  // namespace
}  // namespace bowg
