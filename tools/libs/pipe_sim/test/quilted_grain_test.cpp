#include "bowg_pipe_sim/quilted_grain.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "bowg_pipe_sim/random.h"
#include "bowg_pipe_sim/wall_texture.h"

namespace bowg {
namespace pipe_sim {
namespace {

/// Vertical stripes (period 8 columns) with a little hashed noise: a
/// texture whose origin is recognisable in the quilt (stripes stay vertical
/// under the mirror images the quilt uses).
cv::Mat stripes(int rows, int cols, std::uint64_t seed) {
  cv::Mat im(rows, cols, CV_8U);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      im.at<uchar>(r, c) = static_cast<uchar>(100 + 60 * std::sin(2 * M_PI * c / 8.0) +
                                              10 * toUnit(hashCombine(seed, r, c)));
    }
  }
  return im;
}

/// A fresh folder under the test output directory.
std::string freshDir(const std::string& name) {
  const std::string dir = std::string(BOWG_TEST_OUTPUT_DIR) + "/" + name;
  ::mkdir(dir.c_str(), 0755);
  return dir;
}

double correlation(const cv::Mat& a, const cv::Mat& b) {
  cv::Scalar ma, sa, mb, sb;
  cv::meanStdDev(a, ma, sa);
  cv::meanStdDev(b, mb, sb);
  return cv::mean((a - ma[0]).mul(b - mb[0]))[0] / (sa[0] * sb[0]);
}

TEST(QuiltedGrainTest, LoadsImagesSortedAndCropped) {
  const std::string dir = freshDir("quilt_load");
  // Written in reverse name order: the loader must sort.
  cv::imwrite(dir + "/b.png", cv::Mat(100, 90, CV_8U, cv::Scalar(200)));
  cv::Mat a(100, 90, CV_8U, cv::Scalar(50));
  a.rowRange(0, 10).setTo(255);  // a "text overlay" in the top rows
  cv::imwrite(dir + "/a.PNG", a);
  cv::imwrite(dir + "/c.jpg", cv::Mat(100, 90, CV_8UC3, cv::Scalar(10, 20, 30)));
  std::ofstream(dir + "/notes.txt") << "not an image";
  const std::vector<cv::Mat> images = loadGrainImages(dir, 0.15);
  ASSERT_EQ(images.size(), 3u);
  EXPECT_EQ(images[0].rows, 70);  // 15 rows cut at the top and the bottom
  EXPECT_EQ(images[0].cols, 90);
  EXPECT_EQ(images[0].type(), CV_8UC1);
  EXPECT_EQ(cv::norm(images[0], cv::NORM_INF), 50);  // a.PNG, overlay cut away
  EXPECT_EQ(images[1].at<uchar>(0, 0), 200);          // b.png
  EXPECT_EQ(loadGrainImages(dir, 0.0)[0].rows, 100);
}

TEST(QuiltedGrainTest, LoadErrorsNameTheFolderOrFile) {
  const std::string missing = std::string(BOWG_TEST_OUTPUT_DIR) + "/quilt_no_such_folder";
  try {
    loadGrainImages(missing, 0.15);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  const std::string empty = freshDir("quilt_empty");
  EXPECT_THROW(loadGrainImages(empty, 0.15), std::runtime_error);
  const std::string broken = freshDir("quilt_broken");
  std::ofstream(broken + "/x.png") << "not a png";
  try {
    loadGrainImages(broken, 0.15);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("x.png"), std::string::npos) << e.what();
  }
  const std::string small = freshDir("quilt_small");
  cv::imwrite(small + "/s.png", cv::Mat(60, 60, CV_8U, cv::Scalar(9)));
  EXPECT_THROW(loadGrainImages(small, 0.15), std::runtime_error);  // 42 rows left
  EXPECT_THROW(loadGrainImages(small, 0.5), std::invalid_argument);
}

// A FIFO, a folder or a huge sparse file named as an image is refused by
// name at once, never opened by OpenCV (a FIFO would hold the generator).
TEST(QuiltedGrainTest, SpecialAndHugeFilesAreRefusedBeforeOpening) {
  const std::string dir = freshDir("quilt_special");
  ASSERT_EQ(::mkfifo((dir + "/fifo.png").c_str(), 0600), 0);
  const auto refusal = [&dir]() -> std::string {
    try {
      loadGrainImages(dir, 0.15);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(refusal().find("fifo.png: it is not a regular file"), std::string::npos) << refusal();
  ::unlink((dir + "/fifo.png").c_str());
  ASSERT_EQ(::mkdir((dir + "/folder.jpg").c_str(), 0755), 0);
  EXPECT_NE(refusal().find("folder.jpg: it is not a regular file"), std::string::npos);
  ::rmdir((dir + "/folder.jpg").c_str());
  std::ofstream(dir + "/huge.png").put('x');
  ASSERT_EQ(::truncate((dir + "/huge.png").c_str(), 1ll << 30), 0);
  EXPECT_NE(refusal().find("huge.png is 1024 MiB, more than 64 MiB"), std::string::npos)
      << refusal();
  ::unlink((dir + "/huge.png").c_str());
}

TEST(QuiltedGrainTest, FieldIsNormalisedDeterministicAndFromTheImages) {
  const QuiltedGrain quilt({stripes(120, 160, 1), stripes(100, 100, 2)});
  const cv::Mat f = quilt.field(300, 512, 7);
  cv::Scalar mean, spread;
  cv::meanStdDev(f, mean, spread);
  EXPECT_NEAR(mean[0], 0, 1e-4);
  EXPECT_NEAR(spread[0], 1, 1e-4);
  EXPECT_EQ(cv::norm(f, quilt.field(300, 512, 7), cv::NORM_INF), 0);
  EXPECT_LT(std::abs(correlation(f, quilt.field(300, 512, 8))), 0.2);
  // The stripes survive quilting: neighbouring rows alike, columns half a
  // period apart opposite.
  EXPECT_GT(correlation(f.rowRange(0, 299), f.rowRange(1, 300)), 0.8);
  EXPECT_LT(correlation(f.colRange(0, 508), f.colRange(4, 512)), -0.3);
  EXPECT_THROW(QuiltedGrain(std::vector<cv::Mat>{cv::Mat(40, 100, CV_8U)}), std::invalid_argument);
  EXPECT_THROW(QuiltedGrain(std::vector<cv::Mat>{}), std::invalid_argument);
}

/// Correlation of the bare grain of two 0.5 m sections (rows after the
/// joint, columns away from the seam), as in wall_texture_test.cpp.
double grainCorrelation(const WallTexture& tex, int edge_a, double s_a, int edge_b, double s_b) {
  const double margin = tex.options().margin_m, texel = tex.options().texel_m;
  const int ra = static_cast<int>(std::lround((s_a + margin) / texel));
  const int rb = static_cast<int>(std::lround((s_b + margin) / texel));
  cv::Mat a, b;
  tex.texture(edge_a, 0).rowRange(ra + 40, ra + 500).colRange(140, 500).convertTo(a, CV_64F);
  tex.texture(edge_b, 0).rowRange(rb + 40, rb + 500).colRange(140, 500).convertTo(b, CV_64F);
  return correlation(a, b);
}

TEST(QuiltedGrainTest, WallTextureMixesSharedAndOwnQuiltLikeTheProcedural) {
  const PipeNetwork n = PipeNetwork::figureEight();
  WallTextureOptions o;
  o.marks_per_metre = 0;
  const WallTexture procedural(n, o);
  o.grain_images = {stripes(120, 160, 1), stripes(100, 100, 2), stripes(90, 200, 3)};
  o.grain_repeat = 1;
  const WallTexture copy(n, o);
  EXPECT_GT(grainCorrelation(copy, 0, 0.0, 2, 1.0), 0.999);
  o.grain_repeat = 0.5;
  const WallTexture half(n, o);
  for (double s_b : {0.5, 1.5}) {
    const double rho = grainCorrelation(half, 0, 0.0, 0, s_b);
    EXPECT_GT(rho, 0.35);
    EXPECT_LT(rho, 0.65);
  }
  o.grain_repeat = 0;
  const WallTexture own(n, o);
  EXPECT_LT(std::abs(grainCorrelation(own, 0, 0.0, 0, 0.5)), 0.15);
  // The grain's mean and spread are the procedural grain's; joints and seam
  // are the same texels.
  const auto stats = [](const WallTexture& t) {
    cv::Scalar m, s;
    cv::meanStdDev(t.texture(1, 0).rowRange(200, 1600).colRange(140, 500), m, s);
    return cv::Vec2d(m[0], s[0]) / 255.0;
  };
  EXPECT_NEAR(stats(half)[0], stats(procedural)[0], 0.03);
  EXPECT_NEAR(stats(half)[1], stats(procedural)[1], 0.03);
  for (double theta = 0; theta < 2 * M_PI; theta += 0.1) {
    EXPECT_EQ(half.albedo(1, 0.5 + 0.003, theta), procedural.albedo(1, 0.5 + 0.003, theta));
    EXPECT_EQ(half.albedo(3, 1.0 + 0.0185, theta), procedural.albedo(3, 1.0 + 0.0185, theta));
  }
  for (double s = 0.06; s < 0.45; s += 0.05) {
    EXPECT_EQ(half.albedo(0, s, M_PI / 2), procedural.albedo(0, s, M_PI / 2));  // the seam
  }
}

}  // namespace
}  // namespace pipe_sim
}  // namespace bowg
