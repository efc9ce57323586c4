#include "bowg_evaluation/mission_file.h"

#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include "bowg/core/errors.h"
#include "bowg/database/missions.h"
#include "bowg_evaluation/csv_cells.h"
#include "bowg_evaluation/text_file.h"

namespace bowg {
namespace eval {
namespace {

// One line `first_frame,mission_id,name`; `where` prefixes messages.
MissionStart parseLine(const std::string& line, const std::string& where) {
  const std::size_t a = line.find(',');
  const std::size_t b = a == std::string::npos ? a : line.find(',', a + 1);
  if (b == std::string::npos) throw FormatError(where + ": expected first_frame,mission_id,name");
  double frame = 0, id = 0;
  if (!toDouble(line.substr(0, a), &frame) || frame < 0 || frame != static_cast<int>(frame)) {
    throw FormatError(where + ": first_frame is not a frame index");
  }
  if (!toDouble(line.substr(a + 1, b - a - 1), &id) || id < 0 || id > 4294967295.0 ||
      id != static_cast<double>(static_cast<std::uint32_t>(id))) {
    throw FormatError(where + ": mission_id is not an integer in [0, 2^32)");
  }
  MissionStart m;
  m.first_frame = static_cast<int>(frame);
  m.id = static_cast<std::uint32_t>(id);
  m.name = line.substr(b + 1);
  const std::string problem = missionNameProblem(m.name);
  if (!problem.empty()) throw FormatError(where + ": " + problem);
  return m;
}

}  // namespace

std::vector<MissionStart> parseMissionStarts(const std::string& text, const std::string& source) {
  std::vector<MissionStart> missions;
  std::set<std::uint32_t> ids;
  std::set<std::string> names;
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::string where = source + ":" + std::to_string(n);
    const MissionStart m = parseLine(line, where);
    if (missions.empty() ? m.first_frame != 0 : m.first_frame <= missions.back().first_frame) {
      throw FormatError(where + ": the first mission starts at frame 0, the others after it");
    }
    if (!ids.insert(m.id).second) throw FormatError(where + ": mission id twice");
    if (!names.insert(m.name).second) throw FormatError(where + ": mission name twice");
    missions.push_back(m);
  }
  if (missions.empty()) throw FormatError(source + ": no mission");
  return missions;
}

std::vector<MissionStart> readMissionStarts(const std::string& path) {
  return parseMissionStarts(readTextFile(path, "missions"), path);
}

void attachMissions(const std::vector<MissionStart>& missions, std::vector<FrameInput>* frames) {
  for (const MissionStart& m : missions) {
    if (m.first_frame >= static_cast<int>(frames->size())) {
      throw std::invalid_argument("mission " + std::to_string(m.id) + " starts at frame " +
                                  std::to_string(m.first_frame) + ", after the last frame (" +
                                  std::to_string(frames->size()) + " frames)");
    }
    FrameInput& f = (*frames)[m.first_frame];
    f.starts_mission = true;
    f.mission_id = m.id;
    f.mission_name = m.name;
  }
}

PrPoint crossMissionPoint(const DetectorRun& run, const GroundTruth& gt) {
  const auto mission = [&run](int entry) { return missionOfEntry(run, entry); };
  GroundTruth cross;
  for (const auto& q : gt.loops) {
    for (int m : q.second) {
      if (mission(m) != mission(q.first)) cross.loops[q.first].push_back(m);
    }
  }
  std::vector<Detection> detections;
  for (const Detection& d : detectionsOf(run)) {
    if (mission(d.match) != mission(d.query)) detections.push_back(d);
  }
  PrPoint p = evaluateAt(detections, cross, -std::numeric_limits<double>::infinity());
  p.threshold = appliedThreshold(run);
  return p;
}

}  // namespace eval
}  // namespace bowg
