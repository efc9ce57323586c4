// The mission table (missions.h) and the database's check that every entry
// belongs to one of its missions.
#include "bowg/database/missions.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "bowg/database/database.h"
#include "database/database_fixture.h"

namespace bowg {
namespace {

TEST(MissionTable, ANewTableHoldsTheUnnamedMissionZero) {
  const MissionTable t;
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t.all()[0].id, 0u);
  EXPECT_EQ(t.all()[0].name, "");
  EXPECT_EQ(t.all()[0].entries, 0u);
  EXPECT_EQ(t.nextId(), 1u);
  EXPECT_EQ(t.findByName("")->id, 0u);
  EXPECT_EQ(t.find(1), nullptr);
}

TEST(MissionTable, IdsAndNamesAreUnique) {
  MissionTable t;
  t.add(7, "2025-11-02 Hauptstrasse");
  EXPECT_EQ(t.nextId(), 8u);
  EXPECT_EQ(t.findByName("2025-11-02 Hauptstrasse")->id, 7u);
  EXPECT_THROW(t.add(7, "other"), std::invalid_argument);
  EXPECT_THROW(t.add(8, "2025-11-02 Hauptstrasse"), std::invalid_argument);
  EXPECT_THROW(t.add(8, ""), std::invalid_argument);  // mission 0's
  EXPECT_EQ(t.size(), 2u);
}

TEST(MissionTable, NamesWithControlCharactersOrTooLongAreRefused) {
  EXPECT_EQ(missionNameProblem("Kanal 7 \xc3\xbc"), "");  // UTF-8 is a name
  EXPECT_NE(missionNameProblem("two\nlines"), "");
  EXPECT_NE(missionNameProblem(std::string("a\x7f", 2)), "");
  EXPECT_EQ(missionNameProblem(std::string(kMaxMissionNameBytes, 'a')), "");
  EXPECT_NE(missionNameProblem(std::string(kMaxMissionNameBytes + 1, 'a')), "");
  MissionTable t;
  EXPECT_THROW(t.add(1, "tab\there"), std::invalid_argument);
  EXPECT_EQ(t.size(), 1u);
}

TEST(MissionTable, OnlyAMissionWithoutKeyframesIsGivenAnotherIdAndName) {
  MissionTable t;
  t.add(4, "2025");
  t.reassign(0, 0, "2026-12-05");
  EXPECT_EQ(t.find(0)->name, "2026-12-05");
  EXPECT_THROW(t.reassign(0, 4, "x"), std::invalid_argument);     // mission 4's id
  EXPECT_THROW(t.reassign(0, 9, "2025"), std::invalid_argument);  // mission 4's name
  t.reassign(0, 9, "2026-12-05");
  ASSERT_NE(t.find(9), nullptr);
  EXPECT_EQ(t.find(0), nullptr);
  t.countEntry(9);
  EXPECT_EQ(t.find(9)->entries, 1u);
  EXPECT_THROW(t.reassign(9, 9, "another"), std::logic_error);
  t.reassign(9, 9, "2026-12-05");  // its own id and name: nothing to do
  EXPECT_THROW(t.reassign(3, 3, "x"), std::invalid_argument);
  EXPECT_THROW(t.countEntry(3), std::invalid_argument);
}

TEST(MissionTable, RestoreReplacesTheTableOrKeepsIt) {
  MissionTable t;
  Mission a, b;
  a.id = 4;
  a.name = "a";
  a.entries = 9;  // counts are the database's to make again
  b.id = 2;
  b.name = "b";
  t.restore({a, b});
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.all()[0].id, 4u);  // the order given
  EXPECT_EQ(t.all()[0].entries, 0u);
  EXPECT_EQ(t.nextId(), 5u);
  EXPECT_THROW(t.restore({a, a}), std::invalid_argument);
  EXPECT_THROW(t.restore({}), std::invalid_argument);
  EXPECT_EQ(t.size(), 2u);
  t.clear();
  EXPECT_EQ(t.size(), 1u);
  EXPECT_EQ(t.all()[0].id, 0u);
}

TEST(MissionTable, TheLastIdHasNoNext) {
  MissionTable t;
  t.add(0xffffffffu, "last");
  EXPECT_THROW(t.nextId(), std::length_error);
}

TEST(Database, EveryEntryBelongsToOneOfItsMissions) {
  using namespace database_fixture;
  Database db(vocabulary(), ScoringType::kL1, 2, 8);
  std::mt19937_64 rng(3);
  const testing::Corridor c = testing::makeCorridor(20, 10, 4);
  BowVector bow;
  BuiltEntry b = entryFromKeyframe(*vocabulary(), testing::observeCorridor(c, 1, 1.0, rng), &bow);
  b.entry.mission = 5;
  EXPECT_THROW(db.add(b.entry, db.addToGroupTable(b.raw_groups)), std::invalid_argument);
  EXPECT_TRUE(db.empty());
  db.addMission(5, "2027");
  db.add(b.entry, db.addToGroupTable(b.raw_groups));
  EXPECT_EQ(db.missions().find(5)->entries, 1u);
  EXPECT_EQ(db.entry(0).mission, 5u);
  EXPECT_THROW(db.restoreMissions(db.missions().all()), std::logic_error);
  db.clear();
  EXPECT_EQ(db.missions().size(), 1u);
  EXPECT_EQ(db.missions().all()[0].id, 0u);
}

}  // namespace
}  // namespace bowg
