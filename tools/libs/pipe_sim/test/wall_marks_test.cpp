// The unique marks and their change between two inspections of one network:
// the asked share replaced, the count kept, seeded, and drawn into the
// texture where they sit.
#include "bowg_pipe_sim/wall_marks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "bowg_pipe_sim/wall_texture.h"

namespace bowg {
namespace pipe_sim {
namespace {

bool sameMark(const WallMark& a, const WallMark& b) {
  return a.edge == b.edge && a.s == b.s && a.theta == b.theta && a.type == b.type &&
         a.size_m == b.size_m && a.shape_seed == b.shape_seed;
}

/// How many marks of `a` are also (identical) in `b`.
int common(const std::vector<WallMark>& a, const std::vector<WallMark>& b) {
  int n = 0;
  for (const WallMark& m : a) {
    for (const WallMark& o : b) {
      if (sameMark(m, o)) {
        ++n;
        break;
      }
    }
  }
  return n;
}

bool sortedByEdge(const std::vector<WallMark>& marks) {
  for (std::size_t i = 1; i < marks.size(); ++i) {
    if (marks[i].edge < marks[i - 1].edge) return false;
  }
  return true;
}

TEST(WallMarksTest, TheAskedShareIsReplacedAndTheCountKept) {
  const PipeNetwork n = PipeNetwork::figureEight();
  const std::vector<WallMark> before = placeMarks(n, 2.0, 1);
  ASSERT_GT(before.size(), 30u);  // 17 m of pipe
  for (double fraction : {0.0, 0.2, 0.5, 1.0}) {
    SCOPED_TRACE(fraction);
    const std::vector<WallMark> after = changeMarks(before, n, fraction, 7);
    ASSERT_EQ(after.size(), before.size());
    const int changed = static_cast<int>(std::lround(fraction * before.size()));
    EXPECT_EQ(common(before, after), static_cast<int>(before.size()) - changed);
    EXPECT_TRUE(sortedByEdge(after));
    for (const WallMark& m : after) {
      EXPECT_GE(m.s, 0);
      EXPECT_LT(m.s, n.edgeLength(m.edge));
    }
  }
}

TEST(WallMarksTest, TheChangeIsSeeded) {
  const PipeNetwork n = PipeNetwork::figureEight();
  const std::vector<WallMark> before = placeMarks(n, 1.0, 1);
  const std::vector<WallMark> a = changeMarks(before, n, 0.3, 5);
  const std::vector<WallMark> b = changeMarks(before, n, 0.3, 5);
  const std::vector<WallMark> c = changeMarks(before, n, 0.3, 6);
  EXPECT_EQ(common(a, b), static_cast<int>(a.size()));
  EXPECT_LT(common(a, c), static_cast<int>(a.size()));
}

TEST(WallMarksTest, BadFractionsAreRefused) {
  const PipeNetwork n = PipeNetwork::figureEight();
  const std::vector<WallMark> marks = placeMarks(n, 1.0, 1);
  EXPECT_THROW(changeMarks(marks, n, -0.1, 1), std::invalid_argument);
  EXPECT_THROW(changeMarks(marks, n, 1.1, 1), std::invalid_argument);
  EXPECT_THROW(changeMarks(marks, n, std::nan(""), 1), std::invalid_argument);
  WallTextureOptions o;
  o.marks_changed = 1.5;
  EXPECT_THROW(o.validate(), std::invalid_argument);
}

TEST(WallMarksTest, TheTextureOfTheSecondInspectionHasTheChangedMarks) {
  const PipeNetwork n = PipeNetwork::figureEight(2.0, 1.0);
  WallTextureOptions first;
  first.circumference_texels = 128;
  first.marks_per_metre = 3.0;
  WallTextureOptions again = first;
  again.marks_changed = 0.2;
  again.marks_change_seed = 1001;
  const WallTexture a(n, first), b(n, again);
  // The texture's marks are placeMarks' and then changeMarks', the share
  // asked replaced.
  const std::vector<WallMark> placed = placeMarks(n, 3.0, first.seed);
  ASSERT_EQ(a.marks().size(), placed.size());
  EXPECT_EQ(common(a.marks(), placed), static_cast<int>(placed.size()));
  ASSERT_EQ(b.marks().size(), a.marks().size());
  const int changed = static_cast<int>(std::lround(0.2 * placed.size()));
  EXPECT_EQ(common(a.marks(), b.marks()), static_cast<int>(placed.size()) - changed);
  // The wall differs where a mark was removed and not where one was kept
  // (a kept mark is drawn alike), but for the few a new mark covers.
  double kept = 0, kept_same = 0, removed = 0, removed_differs = 0;
  for (const WallMark& m : a.marks()) {
    if (m.type == WallMark::Type::kCrack) continue;  // thin: may miss the centre
    const double d = std::abs(a.albedo(m.edge, m.s, m.theta) - b.albedo(m.edge, m.s, m.theta));
    if (common({m}, b.marks()) == 1) {
      kept += 1;
      kept_same += d < 1e-6;
    } else {
      removed += 1;
      removed_differs += d > 0.02;
    }
  }
  ASSERT_GT(kept, 0);
  ASSERT_GT(removed, 0);
  EXPECT_GE(kept_same / kept, 0.9);
  // A removed blob may lie under a kept or a new mark.
  EXPECT_GE(removed_differs / removed, 0.7);
}

TEST(WallMarksTest, NoChangeIsTheFirstInspectionsTexture) {
  const PipeNetwork n = PipeNetwork::figureEight(2.0, 1.0);
  WallTextureOptions first;
  first.circumference_texels = 128;
  WallTextureOptions again = first;
  again.marks_change_seed = 1001;  // marks_changed 0: the seed is not used
  const WallTexture a(n, first), b(n, again);
  for (std::size_t e = 0; e < n.edges.size(); ++e) {
    EXPECT_EQ(cv::norm(a.texture(static_cast<int>(e), 0), b.texture(static_cast<int>(e), 0),
                       cv::NORM_INF),
              0);
  }
}

}  // namespace
}  // namespace pipe_sim
}  // namespace bowg
