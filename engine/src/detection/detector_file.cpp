// Saving the detector file (detector_file.h; layout in
// detector_file_format.h).
#include "bowg/detection/detector_file.h"

#include "bowg/core/atomic_file.h"
#include "bowg/core/checksum.h"
#include "bowg/vocabulary/vocabulary.h"
#include "detection/detector_file_format.h"

namespace bowg {

using namespace detector_file;

namespace {

std::string littleEndian64(std::uint64_t v) {
  Writer w;
  w.u64(v);
  return w.str();
}

void writeBody(Writer* w, const Database& database, const DetectorState& state);

void writeIsland(Writer* w, const Island& i) {
  w->u32(i.first);
  w->u32(i.last);
  w->f64(i.score);
  w->u32(i.best_entry);
  w->f64(i.best_score);
  w->i32(i.size);
}

}  // namespace

void saveDetectorFile(const std::string& path, const Database& database,
                      const DetectorState& state) {
  // Streamed: an archive's file is tens of GB, far more than its database
  // holds in memory. The payload size and the checksum over it are written
  // once the rest is on disk.
  AtomicFileStream out(path);
  Writer w(&out);
  writeBody(&w, database, state);
  w.flush();
  const std::string size = littleEndian64(out.size() - kHeaderBytes);
  out.writeAt(size.data(), size.size(), kHeaderBytes - 8);
  const std::string stored = littleEndian64(checksumOfFile(out, out.size()));
  out.write(stored.data(), stored.size());
  out.commit();
}

std::string encodeDetectorFile(const Database& database, const DetectorState& state) {
  Writer w;
  writeBody(&w, database, state);
  std::string& bytes = w.str();
  const std::string size = littleEndian64(bytes.size() - kHeaderBytes);
  bytes.replace(kHeaderBytes - 8, 8, size);
  w.u64(checksum64(bytes.data(), bytes.size()));
  return std::move(bytes);
}

namespace {

// The entries, each flushed once written (a streaming writer's memory is one
// entry).
void writeEntries(Writer* wp, const Database& database) {
  Writer& w = *wp;
  w.u32(static_cast<std::uint32_t>(database.size()));
  std::vector<Descriptor> read;  // an entry's descriptors left on disk
  for (const DatabaseEntry& e : database.entries()) {
    const std::vector<Descriptor>& descriptors = e.descriptorsRead(&read);
    w.f64(e.stamp);
    w.f64(e.centre_x);
    w.f64(e.centre_y);
    w.u8(e.intrinsics.valid ? 1 : 0);
    w.f64(e.intrinsics.fx);
    w.f64(e.intrinsics.fy);
    w.f64(e.intrinsics.cx);
    w.f64(e.intrinsics.cy);
    w.u32(static_cast<std::uint32_t>(e.points.size()));
    const std::vector<ImagePoint> points = e.points.unpack();
    for (std::size_t i = 0; i < points.size(); ++i) {
      // The database keeps keypoint positions only: size, angle, response and
      // octave are written as a keypoint without them (0, -1, 0, 0).
      const Keypoint k;
      w.f32(points[i].x);
      w.f32(points[i].y);
      w.f32(k.size);
      w.f32(k.angle);
      w.f32(k.response);
      w.i32(k.octave);
      for (std::uint64_t b : descriptors[i].bits) w.u64(b);
      w.u32(e.words[i]);
    }
    w.pairs(database.bow(e.id));  // kept in the format; rebuilt from the words
    w.pairs(database.rawGroups(e.id));
    w.flush();
  }
}

// Everything but the checksum, the payload size left 0.
void writeBody(Writer* wp, const Database& database, const DetectorState& state) {
  Writer& w = *wp;
  w.bytes(kMagic, 8);
  w.u32(kVersion);
  w.u64(database.vocabulary().fingerprint());
  w.u64(0);  // payload size, written by the caller
  w.u32(static_cast<std::uint32_t>(database.scoring()));

  writeEntries(&w, database);
  w.pairs(state.previous_etas);
  writeIsland(&w, state.consistency.lastIsland());
  w.i32(state.consistency.chainLength());
  const std::vector<Normalisers> normalisers = state.normalisers.values();
  w.u32(static_cast<std::uint32_t>(normalisers.size()));
  for (const Normalisers& v : normalisers) {
    w.f64(v.word);
    w.f64(v.group);
    w.f64(v.distribution);
  }
  w.i32(state.missed_queries);
  w.i32(state.consistency.missedQueries());
  w.u32(static_cast<std::uint32_t>(database.size()));
  for (const DatabaseEntry& e : database.entries()) w.f64(e.odometer);
  w.f64(state.previous_odometer);
  w.f64(state.consistency.lastQueryOdometer());
  const std::vector<IslandHypothesis>& others = state.consistency.otherHypotheses();
  w.u32(static_cast<std::uint32_t>(others.size()));
  for (const IslandHypothesis& h : others) {
    writeIsland(&w, h.island);
    w.i32(h.chain_length);
  }
  w.u32(static_cast<std::uint32_t>(database.size()));
  for (const DatabaseEntry& e : database.entries()) w.f32(e.points.scaleFactor());
  const std::vector<EntryId> parents = state.place_links.parents(database.size());
  w.u32(static_cast<std::uint32_t>(parents.size()));
  for (EntryId p : parents) w.u32(p);
  w.u32(state.odometry_run);
  w.u32(static_cast<std::uint32_t>(database.size()));
  for (const DatabaseEntry& e : database.entries()) {
    w.u32(e.odometry_run);
    w.f64(e.position.x);
    w.f64(e.position.y);
    w.f64(e.position.z);
  }
  w.u32(static_cast<std::uint32_t>(database.size()));
  for (const DatabaseEntry& e : database.entries()) w.u8(e.searchable ? 1 : 0);
  writeMissions(&w, database, state);
  w.u32(static_cast<std::uint32_t>(database.size()));
  for (const DatabaseEntry& e : database.entries()) {
    w.f32(e.heading.x);
    w.f32(e.heading.y);
    w.f32(e.heading.z);
  }
}

}  // namespace

}  // namespace bowg
