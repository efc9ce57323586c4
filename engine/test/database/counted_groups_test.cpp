// The per-keyframe order as a type: makeQuery and add take the CountedGroups
// that only addToGroupTable makes; a token adds one entry, in its own
// database, and queries may still use it after.
#include "bowg/database/counted_groups.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "bowg/database/database.h"
#include "database_fixture.h"

namespace bowg {
namespace {

using namespace database_fixture;

// Calling makeQuery or add without the counting step does not compile: no
// token can be made or copied outside the database, only moved.
static_assert(!std::is_default_constructible<CountedGroups>::value,
              "a token comes from Database::addToGroupTable only");
static_assert(!std::is_constructible<CountedGroups, GroupVector>::value,
              "a token comes from Database::addToGroupTable only");
static_assert(!std::is_copy_constructible<CountedGroups>::value, "a token is not copied");
static_assert(!std::is_copy_assignable<CountedGroups>::value, "a token is not copied");
static_assert(std::is_nothrow_move_constructible<CountedGroups>::value, "a token moves");
static_assert(!std::is_convertible<const GroupVector&, const CountedGroups&>::value,
              "raw groups are not a token");

TEST(CountedGroups, CountingFillsTheTableAndTheTokenKeepsTheGroups) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  const GroupVector raw{{1, 2}, {4, 3}};
  const CountedGroups counted = db.addToGroupTable(raw);
  EXPECT_EQ(counted.raw(), raw);
  EXPECT_FALSE(counted.added());
  EXPECT_EQ(db.groupTable().cumulative(1), 2.0);
  EXPECT_EQ(db.groupTable().cumulative(4), 3.0);
  EXPECT_EQ(db.groupTable().total(), 5.0);
  // No groups (a keyframe without features): the table stays as it was.
  const std::uint64_t version = db.groupTable().version();
  db.addToGroupTable(GroupVector());
  EXPECT_EQ(db.groupTable().version(), version);
  EXPECT_EQ(db.groupTable().total(), 5.0);
}

TEST(CountedGroups, ATokenAddsOneEntryOnly) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  const GroupVector raw{{1, 2}, {4, 3}};
  CountedGroups counted = db.addToGroupTable(raw);
  EXPECT_EQ(db.add(entryOfGroups(raw, 1), std::move(counted)), 0u);
  EXPECT_TRUE(counted.added());
  EXPECT_EQ(db.rawGroups(0), raw);
  // The second keyframe with the first one's token: refused, nothing added.
  EXPECT_THROW(db.add(entryOfGroups(raw, 2), std::move(counted)), std::logic_error);
  EXPECT_EQ(db.size(), 1u);
  EXPECT_EQ(db.groupTable().total(), 5.0);
  // Its groups are still counted: a query may still be made with it.
  const DatabaseQuery q = db.makeQuery(db.bow(0), counted, {}, 0, 0, false);
  EXPECT_EQ(q.refined_groups.size(), 2u);
}

TEST(CountedGroups, AFailedAddLeavesTheTokenToAddWith) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  const GroupVector raw{{1, 2}};
  CountedGroups counted = db.addToGroupTable(raw);
  DatabaseEntry bad = entryOfGroups(raw, 1);
  bad.descriptors.clear();  // sizes differ
  EXPECT_THROW(db.add(bad, std::move(counted)), std::invalid_argument);
  EXPECT_FALSE(counted.added());
  EXPECT_EQ(db.add(entryOfGroups(raw, 1), std::move(counted)), 0u);
}

TEST(CountedGroups, MovedFromAndForeignTokensAreRefused) {
  Database db(vocabulary(), ScoringType::kL1, 2, 8), other(vocabulary(), ScoringType::kL1, 2, 8);
  const GroupVector raw{{1, 2}};
  CountedGroups counted = db.addToGroupTable(raw);
  CountedGroups moved = std::move(counted);
  EXPECT_THROW(db.makeQuery(BowVector(), counted, {}, 0, 0, false), std::logic_error);
  EXPECT_THROW(db.add(entryOfGroups(raw, 1), std::move(counted)), std::logic_error);
  // Counted in db's table, not in other's.
  EXPECT_THROW(other.makeQuery(BowVector(), moved, {}, 0, 0, false), std::logic_error);
  EXPECT_THROW(other.add(entryOfGroups(raw, 1), std::move(moved)), std::logic_error);
  EXPECT_TRUE(other.empty());
  EXPECT_EQ(db.add(entryOfGroups(raw, 1), std::move(moved)), 0u);
  // Move assignment carries the state along.
  CountedGroups assigned = db.addToGroupTable(raw);
  assigned = std::move(moved);
  EXPECT_TRUE(assigned.added());
  EXPECT_THROW(db.add(entryOfGroups(raw, 2), std::move(assigned)), std::logic_error);
}

}  // namespace
}  // namespace bowg
