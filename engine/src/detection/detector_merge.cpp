// Merging detector files (detector_merge.h).
#include "bowg/detection/detector_merge.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "bowg/database/database.h"
#include "bowg/detection/detection_options.h"
#include "bowg/detection/detector_file.h"

namespace bowg {

namespace {

struct Part {
  std::string path;
  std::unique_ptr<Database> database;
  DetectorState state;
  ScoringType scoring = ScoringType::kL1;
};

// A part from its file, or from bytes in memory when `bytes` is given.
Part readPart(const std::string& path, const std::shared_ptr<const Vocabulary>& vocabulary,
              const std::string* bytes = nullptr) {
  // The options-dependent parts are rebuilt from the words: any level and
  // fan size reads the file; the merged file keeps only the words.
  const LoopDetectorOptions defaults;
  Part part;
  part.path = path;
  const int level = defaults.geometric.direct_index_level;
  const int fans = defaults.distribution.fan_bins;
  part.database = bytes ? decodeDetectorFile(*bytes, path, vocabulary, ScoringType::kL1, level,
                                             fans, &part.state, &part.scoring)
                        : loadDetectorFile(path, vocabulary, ScoringType::kL1, level, fans,
                                           &part.state, &part.scoring);
  return part;
}

// Mission ids and names are unique in a database.
void checkDistinctMissions(const Part& q, const Part& p) {
  for (const Mission& m : p.database->missions().all()) {
    const Mission* numbered = q.database->missions().find(m.id);
    const Mission* named = q.database->missions().findByName(m.name);
    if (numbered == nullptr && named == nullptr) continue;
    throw std::invalid_argument(
        "'" + q.path + "' and '" + p.path + "' both hold " +
        (numbered != nullptr ? "mission " + std::to_string(m.id) + " ('" + numbered->name +
                                   "' and '" + m.name + "')"
                             : "a mission named '" + m.name + "'") +
        ": mission ids and names are unique in a merge (a file merged with itself?)");
  }
}

// The parts in stamp order, checked to go together.
void orderAndCheck(std::vector<Part>* parts) {
  std::stable_sort(parts->begin(), parts->end(), [](const Part& a, const Part& b) {
    const double ta = a.database->empty() ? -1.0 : a.database->entries().front().stamp;
    const double tb = b.database->empty() ? -1.0 : b.database->entries().front().stamp;
    return ta < tb;
  });
  const Part* previous = nullptr;
  for (std::size_t i = 0; i < parts->size(); ++i) {
    const Part& p = (*parts)[i];
    for (std::size_t j = 0; j < i; ++j) {
      checkDistinctMissions((*parts)[j], p);
    }
    if (p.scoring != parts->front().scoring) {
      throw std::invalid_argument("'" + p.path + "' was saved scoring with " + toString(p.scoring) +
                                  ", '" + parts->front().path + "' with " +
                                  toString(parts->front().scoring) +
                                  ": merge files of one configuration");
    }
    if (p.database->empty()) continue;
    if (previous != nullptr &&
        !(p.database->entries().front().stamp > previous->database->entries().back().stamp)) {
      throw std::invalid_argument("the keyframes of '" + previous->path + "' and '" + p.path +
                                  "' overlap in time: a database's stamps increase");
    }
    previous = &p;
  }
}

// Appends `part`'s entries to `merged`, renumbering runs from `run_offset`
// and continuing the odometers; appends their place links to `parents`.
void appendPart(const Part& part, std::uint32_t run_offset, Database* merged,
                std::vector<EntryId>* parents) {
  const EntryId id_offset = static_cast<EntryId>(merged->size());
  const double odometer_offset = std::max(0.0, merged->lastOdometer());
  for (EntryId p : part.state.place_links.parents(part.database->size())) {
    parents->push_back(p + id_offset);
  }
  for (const DatabaseEntry& source : part.database->entries()) {
    DatabaseEntry e = source;
    if (!std::isnan(e.odometer)) e.odometer += odometer_offset;
    e.odometry_run += run_offset;
    merged->add(std::move(e), merged->addToGroupTable(part.database->rawGroups(source.id)));
  }
}

std::unique_ptr<Database> mergeParts(std::vector<Part> parts,
                                     std::shared_ptr<const Vocabulary> vocabulary,
                                     DetectorState* state) {
  orderAndCheck(&parts);

  const LoopDetectorOptions defaults;
  std::unique_ptr<Database> merged(new Database(vocabulary, parts.front().scoring,
                                                defaults.geometric.direct_index_level,
                                                defaults.distribution.fan_bins));
  std::vector<Mission> missions;
  for (const Part& p : parts) {
    for (const Mission& m : p.database->missions().all()) missions.push_back(m);
  }
  merged->restoreMissions(missions);
  *state = DetectorState();
  std::vector<EntryId> parents;
  std::uint32_t runs = 0;
  for (const Part& p : parts) {
    appendPart(p, runs, merged.get(), &parents);
    state->odometry_run = runs + p.state.odometry_run;
    state->mission = p.state.mission;
    runs += p.state.odometry_run + 1;
  }
  state->place_links.restore(std::move(parents));
  return merged;
}

}  // namespace

std::unique_ptr<Database> mergeDetectorFiles(const std::vector<std::string>& paths,
                                             std::shared_ptr<const Vocabulary> vocabulary,
                                             DetectorState* state) {
  if (paths.size() < 2) throw std::invalid_argument("a merge takes two files or more");
  std::vector<Part> parts;
  for (const std::string& path : paths) parts.push_back(readPart(path, vocabulary));
  return mergeParts(std::move(parts), std::move(vocabulary), state);
}

std::unique_ptr<Database> mergeWithRunningDetector(const std::vector<std::string>& paths,
                                                   const std::string& running,
                                                   std::shared_ptr<const Vocabulary> vocabulary,
                                                   DetectorState* state) {
  if (paths.empty()) throw std::invalid_argument("no reference map given");
  std::vector<Part> parts;
  for (const std::string& path : paths) parts.push_back(readPart(path, vocabulary));
  parts.push_back(readPart("the running database", vocabulary, &running));
  return mergeParts(std::move(parts), std::move(vocabulary), state);
}

std::string mergeDetectorFiles(const std::vector<std::string>& paths,
                               std::shared_ptr<const Vocabulary> vocabulary) {
  DetectorState state;
  const std::unique_ptr<Database> merged = mergeDetectorFiles(paths, std::move(vocabulary), &state);
  return encodeDetectorFile(*merged, state);
}

}  // namespace bowg
