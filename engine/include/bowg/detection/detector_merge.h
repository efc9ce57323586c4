// Merging detector files: one database of several missions (for example the
// yearly surveys of one sewer network) to load as a reference map or to
// continue.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace bowg {

class Database;
class Vocabulary;
struct DetectorState;

/// The detector file (detector_file.h) of the union of the files at
/// `paths`, each read for `vocabulary`:
///  - the parts in the order of their first keyframe's stamp (parts without
///    keyframes first, in the order given), so that the stamps increase;
///  - every mission with its id and name, entries renumbered in that order,
///    place links and searchable flags kept;
///  - odometry runs renumbered after the previous part's (a part's positions
///    stay in frames of their own) and odometers continued from the previous
///    part's last (metres driven, non-decreasing over the database);
///  - no memory of previous queries (an archive, not a run to continue
///    mid-loop); the current mission the last part's.
/// The merge of a merge gives the bytes of the merge of the parts. Throws
/// FormatError/IoError naming the file that cannot be read (truncated, other
/// vocabulary), and std::invalid_argument when the parts do not go together:
/// fewer than two, a mission id or name in two parts (a file merged with
/// itself), BoW vectors saved for different scorings, keyframes overlapping
/// in time.
std::string mergeDetectorFiles(const std::vector<std::string>& paths,
                               std::shared_ptr<const Vocabulary> vocabulary);
/// The same merge as a database and the detector's memory for it (a
/// detector starting on several reference maps: LoopDetector::readMerged).
std::unique_ptr<Database> mergeDetectorFiles(const std::vector<std::string>& paths,
                                             std::shared_ptr<const Vocabulary> vocabulary,
                                             DetectorState* state);

/// The reference maps at `paths` merged with a running detector's database
/// (`running`: its LoopDetector::serialize() bytes, named "the running
/// database" in errors), as mergeDetectorFiles merges files: the running
/// keyframes come after the maps' (their stamps are later), keep their
/// mission as the current one and their place links, and lose the memory
/// of previous queries. Throws as mergeDetectorFiles (no map: std::invalid_argument).
std::unique_ptr<Database> mergeWithRunningDetector(const std::vector<std::string>& paths,
                                                   const std::string& running,
                                                   std::shared_ptr<const Vocabulary> vocabulary,
                                                   DetectorState* state);

}  // namespace bowg
