// The detector file: a database with the detector's memory, saved and loaded
// as one file, checked on load so that nothing invalid is restored.
#pragma once

#include <memory>
#include <string>

#include "bowg/database/database.h"
#include "bowg/detection/detector_state.h"
#include "bowg/vocabulary/bow_vector.h"

namespace bowg {

class Vocabulary;

/// Persistence. One versioned little-endian binary file:
///   magic "BOWGDB\0\0" | u32 version | u64 vocabulary fingerprint |
///   u64 payload size | payload (u32 scoring type of the stored BoW
///   vectors, entries, then the detector state; version 2 adds the
///   normaliser history, version 3 the missed-query counters and the
///   odometers, version 4 the temporal verification's other hypotheses;
///   older files load without them) |
///   u64 Checksum64 of every preceding byte.
/// Entries carry everything the indexes, the group table and the caches are
/// rebuilt from; the options-dependent parts (scoring, level, m) follow the
/// loading detector's options. Written atomically (AtomicFileStream) and
/// streamed an entry at a time: the payload size and the checksum are
/// written once the rest is on disk, so the file is never held in memory.
void saveDetectorFile(const std::string& path, const Database& database,
                      const DetectorState& state);
/// The bytes saveDetectorFile() writes: taken under a lock that serialises
/// the detector, written (writeFileAtomically) after it is released.
std::string encodeDetectorFile(const Database& database, const DetectorState& state);
/// Reads and checks a file written by saveDetectorFile() into a NEW database
/// (nothing shared with any existing one). Throws IoError (unreadable) or
/// FormatError (bad magic/version, truncated, checksum mismatch, sizes
/// inconsistent with the file length, other vocabulary, invalid content).
/// `stored_scoring` (optional): the scoring the file's BoW vectors were
/// saved for (the saving detector's).
/// The file is streamed, never held whole: its checksum is computed over it
/// in chunks, then its payload decoded through a window of a few MB. The
/// entries' descriptors stay in the file, which the database keeps open
/// (descriptor_file.h): an archive takes ~12 kB of memory a keyframe.
std::unique_ptr<Database> loadDetectorFile(const std::string& path,
                                           std::shared_ptr<const Vocabulary> vocabulary,
                                           ScoringType scoring, int direct_index_level,
                                           int fan_bins, DetectorState* state,
                                           ScoringType* stored_scoring = nullptr);
/// loadDetectorFile() of bytes already in memory (encodeDetectorFile()'s:
/// a running detector's), `source` naming them in errors.
std::unique_ptr<Database> decodeDetectorFile(const std::string& bytes, const std::string& source,
                                             std::shared_ptr<const Vocabulary> vocabulary,
                                             ScoringType scoring, int direct_index_level,
                                             int fan_bins, DetectorState* state,
                                             ScoringType* stored_scoring = nullptr);

}  // namespace bowg
