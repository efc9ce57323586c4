// The detector file's missions section (version 9, detector_file_format.h).
#include <map>
#include <set>
#include <string>
#include <vector>

#include "detection/detector_file_format.h"

namespace bowg {
namespace detector_file {

void writeMissions(Writer* w, const Database& database, const DetectorState& state) {
  w->u32(state.mission);
  const std::vector<Mission>& missions = database.missions().all();
  w->u32(static_cast<std::uint32_t>(missions.size()));
  for (const Mission& m : missions) {
    w->u32(m.id);
    w->text(m.name);
  }
  w->u32(static_cast<std::uint32_t>(database.size()));
  for (const DatabaseEntry& e : database.entries()) w->u32(e.mission);
}

namespace {

// The mission table as stored: ids and names unique and valid.
std::vector<Mission> readMissionTable(Reader* p) {
  const std::size_t n = p->count(8, "missions");
  if (n == 0) p->fail("no mission (a database holds at least one)");
  std::vector<Mission> missions(n);
  std::set<std::uint32_t> ids;
  std::set<std::string> names;
  for (Mission& m : missions) {
    m.id = p->u32("mission id");
    m.name = p->text("mission name");
    const std::string problem = missionNameProblem(m.name);
    if (!problem.empty()) p->fail("mission " + std::to_string(m.id) + ": " + problem);
    if (!ids.insert(m.id).second) p->fail("mission id " + std::to_string(m.id) + " twice");
    if (!names.insert(m.name).second) p->fail("mission name '" + m.name + "' twice");
  }
  return missions;
}

}  // namespace

void readMissions(Reader* p, std::vector<DatabaseEntry>* entries, DetectorState* state,
                  std::vector<Mission>* missions) {
  state->mission = p->u32("current mission");
  *missions = readMissionTable(p);
  std::set<std::uint32_t> by_id;
  for (const Mission& m : *missions) by_id.insert(m.id);
  if (by_id.count(state->mission) == 0) {
    p->fail("the current mission " + std::to_string(state->mission) + " is not in the file");
  }
  if (p->count(4, "entry missions") != entries->size()) {
    p->fail("entry mission count differs from the entry count");
  }
  // A mission's odometry positions are in its own frames: a run is one
  // mission's.
  std::map<std::uint32_t, std::uint32_t> run_mission;
  for (std::size_t i = 0; i < entries->size(); ++i) {
    DatabaseEntry& e = (*entries)[i];
    e.mission = p->u32("entry mission");
    if (by_id.count(e.mission) == 0) {
      p->fail("entry " + std::to_string(i) + " belongs to mission " + std::to_string(e.mission) +
              ", which the file does not list");
    }
    const auto run = run_mission.emplace(e.odometry_run, e.mission);
    if (run.first->second != e.mission) {
      p->fail("odometry run " + std::to_string(e.odometry_run) + " spans missions " +
              std::to_string(run.first->second) + " and " + std::to_string(e.mission));
    }
  }
  const auto current = run_mission.find(state->odometry_run);
  if (current != run_mission.end() && current->second != state->mission) {
    p->fail("the current odometry run " + std::to_string(state->odometry_run) +
            " belongs to mission " + std::to_string(current->second) +
            ", not to the current mission " + std::to_string(state->mission));
  }
}

}  // namespace detector_file
}  // namespace bowg
