// The missions of a database (missions.h).
#include "bowg/database/missions.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace bowg {

std::string missionNameProblem(const std::string& name) {
  if (name.size() > kMaxMissionNameBytes) {
    return "mission name of " + std::to_string(name.size()) + " bytes (at most " +
           std::to_string(kMaxMissionNameBytes) + ")";
  }
  for (unsigned char c : name) {
    // Names go into logs, messages and file listings one line each.
    if (c < 0x20 || c == 0x7f) return "mission name with a control character";
  }
  return std::string();
}

MissionTable::MissionTable() { clear(); }

const Mission* MissionTable::find(std::uint32_t id) const {
  for (const Mission& m : missions_) {
    if (m.id == id) return &m;
  }
  return nullptr;
}

Mission* MissionTable::findMutable(std::uint32_t id) {
  return const_cast<Mission*>(static_cast<const MissionTable&>(*this).find(id));
}

const Mission* MissionTable::findByName(const std::string& name) const {
  for (const Mission& m : missions_) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

std::uint32_t MissionTable::nextId() const {
  std::uint32_t largest = 0;
  for (const Mission& m : missions_) largest = std::max(largest, m.id);
  if (largest == std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("mission ids exhausted (mission " + std::to_string(largest) + " held)");
  }
  return missions_.empty() ? 0 : largest + 1;
}

void MissionTable::checkFree(const Mission* own, std::uint32_t new_id,
                             const std::string& name) const {
  const std::string problem = missionNameProblem(name);
  if (!problem.empty()) {
    throw std::invalid_argument("mission " + std::to_string(new_id) + ": " + problem);
  }
  const Mission* named = findByName(name);
  if (named != nullptr && named != own) {
    throw std::invalid_argument("mission name '" + name + "' is taken (mission " +
                                std::to_string(named->id) + ")");
  }
  const Mission* numbered = find(new_id);
  if (numbered != nullptr && numbered != own) {
    throw std::invalid_argument("mission id " + std::to_string(new_id) + " is taken (mission '" +
                                numbered->name + "')");
  }
}

void MissionTable::add(std::uint32_t id, const std::string& name) {
  checkFree(nullptr, id, name);
  Mission m;
  m.id = id;
  m.name = name;
  missions_.push_back(m);
}

void MissionTable::reassign(std::uint32_t id, std::uint32_t new_id, const std::string& name) {
  Mission* m = findMutable(id);
  if (m == nullptr) throw std::invalid_argument("no mission " + std::to_string(id));
  if (m->id == new_id && m->name == name) return;
  if (m->entries > 0) {
    throw std::logic_error("mission " + std::to_string(id) +
                           " has keyframes: its id and name stay");
  }
  checkFree(m, new_id, name);
  m->id = new_id;
  m->name = name;
}

void MissionTable::countEntry(std::uint32_t id) {
  Mission* m = findMutable(id);
  if (m == nullptr) throw std::invalid_argument("no mission " + std::to_string(id));
  ++m->entries;
}

void MissionTable::restore(const std::vector<Mission>& missions) {
  if (missions.empty()) throw std::invalid_argument("no mission (a table holds at least one)");
  MissionTable restored;
  restored.missions_.clear();
  for (const Mission& m : missions) restored.add(m.id, m.name);
  missions_.swap(restored.missions_);
}

void MissionTable::clear() { missions_.assign(1, Mission()); }

}  // namespace bowg
