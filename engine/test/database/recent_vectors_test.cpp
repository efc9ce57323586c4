// The newest entries' vectors: kept in a ring by id, found only while they
// are among the database's entries and not replaced.
#include "bowg/database/recent_vectors.h"

#include <gtest/gtest.h>

#include "bowg/database/distribution_table.h"

namespace bowg {
namespace {

TEST(RecentVectors, KeepsTheNewestEntriesAndForgetsOlderOnes) {
  RecentVectors recent;
  EXPECT_EQ(recent.find(0, 1), nullptr);
  for (EntryId id = 0; id < RecentVectors::kEntries + 2; ++id) {
    recent.remember(id, BowVector{{id, 1.0}}, GroupVector{{id, 2}});
  }
  const std::size_t size = RecentVectors::kEntries + 2;
  EXPECT_EQ(recent.find(0, size), nullptr);  // replaced by entry kEntries
  EXPECT_EQ(recent.find(1, size), nullptr);
  const RecentVectors::Entry* r = recent.find(2, size);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->bow, (BowVector{{2, 1.0}}));
  EXPECT_EQ(r->raw_groups, (GroupVector{{2, 2}}));
  EXPECT_EQ(recent.find(9, 9), nullptr);  // not an entry of a database of 9
  recent.clear();
  EXPECT_EQ(recent.find(9, size), nullptr);
}

TEST(DistributionTable, RowsPerEntryAndAResetForAnotherM) {
  DistributionTable table(2);
  table.append({0.25, 0.75});
  table.append({1.0, 0.0});
  std::vector<double> row;
  table.copy(1, &row);
  EXPECT_EQ(row, (std::vector<double>{1.0, 0.0}));
  table.copy(0, &row);
  EXPECT_EQ(row, (std::vector<double>{0.25, 0.75}));
  table.reset(3);
  EXPECT_EQ(table.bins(), 3);
  table.append({0.1, 0.2, 0.7});
  table.copy(0, &row);
  EXPECT_EQ(row, (std::vector<double>{0.1, 0.2, 0.7}));
}

}  // namespace
}  // namespace bowg
