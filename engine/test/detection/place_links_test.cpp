#include "bowg/detection/place_links.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "detection/island_fixture.h"

namespace bowg {
namespace {

using testing::island;

TEST(PlaceLinks, LoopsJoinPlacesTransitively) {
  PlaceLinks links;
  EXPECT_EQ(links.root(7), 7u);  // never linked: its own place
  // Lap 2 (entries 100-) closes loops to lap 1 (0-), lap 3 (200-) to lap 2.
  links.link(105, 5);
  links.link(206, 106);
  links.link(106, 6);
  EXPECT_EQ(links.root(105), 5u);
  EXPECT_EQ(links.root(206), 6u);
  EXPECT_EQ(links.root(106), 6u);
  EXPECT_NE(links.root(5), links.root(6));  // neighbours are not one place by themselves
  EXPECT_EQ(links.placeSize(105), 2u);      // 5, 105
  EXPECT_EQ(links.placeSize(6), 3u);        // 6, 106, 206
  EXPECT_EQ(links.placeSize(7), 1u);
  EXPECT_EQ(links.placeSize(300), 1u);  // beyond every link
  links.link(6, 5);
  EXPECT_EQ(links.root(206), 5u);  // the smallest id of the place
  EXPECT_EQ(links.placeSize(206), 5u);
  links.link(105, 206);  // already one place
  EXPECT_EQ(links.placeSize(5), 5u);
  // Islands: any member of one is one place with any member of the other.
  EXPECT_TRUE(links.linked(island(204, 207), island(4, 5)));
  EXPECT_TRUE(links.linked(island(3, 6), island(105, 105)));
  EXPECT_FALSE(links.linked(island(200, 204), island(100, 104)));
  EXPECT_FALSE(links.linked(island(300, 310), island(0, 4)));  // beyond every link
}

TEST(PlaceLinks, ParentsRoundTripAndAreChecked) {
  PlaceLinks links;
  links.link(4, 1);
  links.link(3, 4);
  const std::vector<EntryId> parents = links.parents(6);
  ASSERT_EQ(parents.size(), 6u);
  EXPECT_EQ(parents[0], 0u);
  EXPECT_EQ(parents[1], 1u);
  EXPECT_EQ(parents[3], 1u);
  EXPECT_EQ(parents[4], 1u);
  EXPECT_EQ(parents[5], 5u);  // beyond the largest linked id
  PlaceLinks restored;
  restored.restore(parents);
  EXPECT_EQ(restored.parents(6), parents);
  EXPECT_EQ(restored.root(3), 1u);
  EXPECT_EQ(restored.placeSize(4), 3u);  // 1, 3, 4
  EXPECT_EQ(restored.placeSize(0), 1u);
  EXPECT_EQ(restored.placeSize(5), 1u);
  try {
    restored.restore({0, 2, 2});
    ADD_FAILURE() << "a parent after its entry accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "place link of entry 1 points to a later entry (2)");
  }
  restored.clear();
  EXPECT_EQ(restored.root(3), 3u);
  EXPECT_EQ(restored.placeSize(4), 1u);
}

}  // namespace
}  // namespace bowg
