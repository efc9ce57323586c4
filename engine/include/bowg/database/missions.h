// The missions a database holds: every keyframe belongs to one survey of the
// network (a mission), named by the user (for example the survey date), so
// that a loop into an earlier inspection says which one it is from.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace bowg {

/// Longest mission name in bytes (UTF-8; control characters refused).
constexpr std::size_t kMaxMissionNameBytes = 255;

/// One mission: its id (stable across saves and merges) and its name.
struct Mission {
  std::uint32_t id = 0;
  std::string name;
  /// Keyframes of the database that belong to it.
  std::size_t entries = 0;
};

/// Why `name` cannot name a mission (empty string: it can). The empty name
/// is a mission's too: the unnamed mission of a run started without one.
std::string missionNameProblem(const std::string& name);

/// The missions of one database, in the order they were added. Ids and
/// names are unique: a name finds its mission again when a robot continues
/// it after a restart.
class MissionTable {
 public:
  /// The unnamed mission 0, without keyframes: a new database's.
  MissionTable();

  const std::vector<Mission>& all() const { return missions_; }
  std::size_t size() const { return missions_.size(); }
  /// Null when no mission has that id / name.
  const Mission* find(std::uint32_t id) const;
  const Mission* findByName(const std::string& name) const;
  /// One past the largest id held (std::length_error when that is 2^32).
  std::uint32_t nextId() const;

  /// Adds a mission without keyframes. Throws std::invalid_argument when the
  /// id or the name is taken or the name is invalid (missionNameProblem).
  void add(std::uint32_t id, const std::string& name);
  /// Gives a mission that has no keyframe yet (a run's default mission,
  /// named once the user's id and name are known) a new id and name. Throws
  /// std::invalid_argument as add() (its own id and name are free for it),
  /// and std::logic_error when the mission has keyframes.
  void reassign(std::uint32_t id, std::uint32_t new_id, const std::string& name);
  /// Counts one more keyframe of mission `id`; std::invalid_argument when
  /// the table does not hold it.
  void countEntry(std::uint32_t id);
  /// Replaces the table with `missions` (their entry counts taken as 0).
  /// Throws std::invalid_argument, keeping the table, on an empty list, an
  /// invalid name or an id or name twice.
  void restore(const std::vector<Mission>& missions);
  /// Back to the unnamed mission 0 alone.
  void clear();

 private:
  Mission* findMutable(std::uint32_t id);
  // Throws std::invalid_argument when `name` is invalid or the name or the
  // id `new_id` is another mission's than `own` (null: any mission's).
  void checkFree(const Mission* own, std::uint32_t new_id, const std::string& name) const;
  std::vector<Mission> missions_;
};

}  // namespace bowg
