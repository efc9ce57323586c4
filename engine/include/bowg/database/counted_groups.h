// The raw word groups of one keyframe once they are in the database's group
// table: the proof of the counting step that the query and the insertion
// need (database.h, "Per-keyframe order").
#pragma once

#include <utility>

#include "bowg/scoring/word_groups.h"

namespace bowg {

class Database;

/// One keyframe's raw groups w_{g,t}^(i), counted into a Database's group
/// table. Only Database::addToGroupTable makes one, so that makeQuery and
/// add, which take it, cannot run before the counting. Move-only, and add()
/// marks it added: a keyframe's groups enter the inverse index once (a
/// token added already, or moved from, is refused at run time). Queries
/// may still be made with an added one: its groups stay in the table.
/// Holds the groups themselves, moved in: no copy, no allocation of its own.
class CountedGroups {
 public:
  CountedGroups(CountedGroups&& other) noexcept
      : owner_(other.owner_), added_(other.added_), raw_(std::move(other.raw_)) {
    other.owner_ = nullptr;
  }
  CountedGroups& operator=(CountedGroups&& other) noexcept {
    owner_ = other.owner_;
    added_ = other.added_;
    raw_ = std::move(other.raw_);
    other.owner_ = nullptr;
    return *this;
  }
  CountedGroups(const CountedGroups&) = delete;
  CountedGroups& operator=(const CountedGroups&) = delete;

  /// The raw groups as counted (sorted by id).
  const GroupVector& raw() const { return raw_; }
  /// Whether Database::add has taken them.
  bool added() const { return added_; }

 private:
  friend class Database;
  CountedGroups(const Database* owner, GroupVector raw) : owner_(owner), raw_(std::move(raw)) {}

  const Database* owner_;  ///< the database whose table counted them; null once moved from
  bool added_ = false;
  GroupVector raw_;
};

}  // namespace bowg
