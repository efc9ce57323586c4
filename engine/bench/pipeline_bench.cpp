// Per-keyframe cost of the BoWG pipeline after feature extraction
// (LoopDetector::process: transform, word groups, query, islands,
// verification) on 640x480-like synthetic keyframes of ~400 features,
// for databases of 1,000, 5,000 and 20,000 keyframes. The keyframes come
// from a corridor of landmarks driven round and round (synthetic_corridor.h),
// so later laps revisit earlier ones and share words the way real revisits
// do (2 flipped bits per descriptor, 0.5 px noise).
//
// BM_PipelineTrained: a 200 m corridor (760 keyframes a lap, so every size
// times revisits) with a k=10 L=6 vocabulary trained on it (k-medians,
// vocabulary_trainer.h), as a vocabulary trained on real images puts the
// views of one patch in one word, and the pipe preset's options
// (config/pipe.yaml); at most 3 keyframes of a place in the inverse index
// (IslandOptions::indexed_per_place, the preset's), or every keyframe (0).
// The scale targets: < 5 ms mean, < 15 ms max at 20,000
// keyframes, growth from 1,000 to 20,000 <= 1.5x.
// BM_Pipeline and BM_PipelinePlaceIndex: the stress case, a 500 m corridor
// (1,960 keyframes a lap: 1,000 keyframes hold no revisit) and a random
// k=10 L=6 vocabulary, in which noisy descriptors spread over many words and
// a query shares words with about a quarter of the database; every keyframe
// indexed, or at most 1 or 3 of a place.
//
// Counters (per keyframe, in ms unless named otherwise): transform,
// word_groups, query, islands, verification, total_mean, total_max,
// features, candidates, loops (fraction of keyframes), bytes_per_keyframe
// (Database::memoryBytes() / size), rss_growth_per_keyframe and
// estimate_growth_per_keyframe (resident set and memoryBytes() growth per
// keyframe added since the previous size).
#include <benchmark/benchmark.h>
#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <random>

#include "bowg/core/resident_memory.h"
#include "bowg/database/database.h"
#include "bowg/detection/loop_detector.h"
#include "bowg/vocabulary/vocabulary.h"
#include "corridor_keyframes.h"
#include "synthetic_corridor.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace {

const double kStep = 0.25;          // metres between keyframes
const int kLandmarksPerMetre = 50;  // keyframes of ~400 features

struct Pipeline {
  std::shared_ptr<const Vocabulary> vocabulary;
  testing::Corridor corridor;
  std::unique_ptr<LoopDetector> detector;
  std::mt19937_64 rng{17};
  std::size_t next = 0;

  Pipeline(std::shared_ptr<const Vocabulary> v, testing::Corridor c, const LoopDetectorOptions& o)
      : vocabulary(std::move(v)), corridor(std::move(c)) {
    detector.reset(new LoopDetector(vocabulary, o));
  }

  KeyframeInput nextKeyframe() {
    // Laps of the corridor, leaving the last 10 m (one view) unvisited so
    // that every view is full.
    const double x = std::fmod(next * kStep, corridor.length - 10.0) + 5.0;
    KeyframeInput kf = bench::corridorKeyframe(corridor, x, 1.0 + next * 0.1, rng);
    ++next;
    return kf;
  }

  /// Processes keyframes until the database holds n; returns their features.
  double growTo(std::size_t n) {
    double features = 0;
    while (detector->database().size() < n) {
      const KeyframeInput kf = nextKeyframe();
      features += kf.features.size();
      detector->process(kf);
    }
    return features;
  }
};

// The resident set after glibc has handed its free memory back: the previous
// size's batch of keyframe inputs (~6 MB) is freed before a measurement
// starts, and the database reusing that memory would hide ~1.6 kB per
// keyframe of its growth over 4,000 keyframes.
double trimmedResidentBytes() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
  return residentBytes();
}

// 100 keyframes = 25 m: views (8 m of wall) of keyframes just outside a
// shorter window still overlap the query; those trivial "loops" would make
// every query run the verification.
const int kRecentExclusion = 100;

// The stress case's options: the defaults with the distribution score on,
// and the corridor's recent-exclusion window.
LoopDetectorOptions stressOptions(int indexed_per_place) {
  LoopDetectorOptions o;
  o.distribution.enabled = true;
  o.similarity.lambda_1 = 0.4;
  o.similarity.lambda_2 = 0.4;
  o.islands.recent_exclusion = kRecentExclusion;
  o.islands.indexed_per_place = indexed_per_place;
  return o;
}

// The stress case's corridor and random vocabulary. `landmarks_per_metre`:
// 50 gives keyframes of ~400 features, 63 of ~500.
std::unique_ptr<Pipeline> stressPipeline(int indexed_per_place, int landmarks_per_metre) {
  return std::unique_ptr<Pipeline>(new Pipeline(
      std::make_shared<Vocabulary>(testing::makeSyntheticVocabulary(10, 6, 1)),
      testing::makeCorridor(500.0, landmarks_per_metre, 5), stressOptions(indexed_per_place)));
}

// The trained case's options: the pipe preset (its verification, scores
// and temporal chain) with the corridor's window and threshold.
LoopDetectorOptions presetOptions(int indexed_per_place) {
  LoopDetectorOptions o = bench::corridorPresetOptions(kRecentExclusion);
  o.islands.indexed_per_place = indexed_per_place;
  return o;
}

// The trained case: a 200 m corridor and a k=10 L=6 vocabulary trained on
// its views one metre apart (190 images, ~76,000 descriptors with the
// keyframes' noise), made once and shared.
std::unique_ptr<Pipeline> trainedPipeline(int indexed_per_place) {
  static std::shared_ptr<const Vocabulary> vocabulary;
  const testing::Corridor corridor = testing::makeCorridor(200.0, kLandmarksPerMetre, 5);
  if (!vocabulary) {
    vocabulary = std::make_shared<Vocabulary>(
        bench::trainCorridorVocabulary(corridor, corridor.length - 5.0));
  }
  return std::unique_ptr<Pipeline>(
      new Pipeline(vocabulary, corridor, presetOptions(indexed_per_place)));
}

// One database per case and indexed_per_place, grown from size to size (each
// made on first use: the others' memory stays out of a run that filters them
// away).
Pipeline& pipeline(bool trained, int indexed_per_place) {
  static std::map<std::pair<bool, int>, std::unique_ptr<Pipeline>> pipelines;
  std::unique_ptr<Pipeline>& p = pipelines[std::make_pair(trained, indexed_per_place)];
  if (!p) {
    p = trained ? trainedPipeline(indexed_per_place)
                : stressPipeline(indexed_per_place, kLandmarksPerMetre);
  }
  return *p;
}

// Per keyframe added: the growth of the resident set and of
// Database::memoryBytes(), and the features.
struct Growth {
  double rss = 0, estimate = 0, features = 0;
};

// Grows `p` to n keyframes, measuring what each added keyframe cost.
Growth growMeasured(Pipeline& p, std::size_t n) {
  const std::size_t size_before = p.detector->database().size();
  const double rss_before = trimmedResidentBytes();
  const double estimate_before = static_cast<double>(p.detector->database().memoryBytes());
  const double features = p.growTo(n);
  const double added =
      static_cast<double>(std::max<std::size_t>(1, p.detector->database().size() - size_before));
  Growth g;
  g.rss = (trimmedResidentBytes() - rss_before) / added;
  g.estimate =
      (static_cast<double>(p.detector->database().memoryBytes()) - estimate_before) / added;
  g.features = features / added;
  return g;
}

void runPipeline(benchmark::State& state, Pipeline& p) {
  // Memory: the growth of the resident set while the database grows to this
  // size (from the previous size, or from empty), against the growth of
  // Database::memoryBytes() over the same keyframes.
  const Growth growth = growMeasured(p, static_cast<std::size_t>(state.range(0)));
  // Keyframes are generated before timing; each iteration processes one.
  const int kBatch = 256;
  std::vector<KeyframeInput> batch;
  std::size_t b = kBatch;
  StageTimings sum;
  double total_max = 0, features = 0, candidates = 0, loops = 0;
  std::int64_t n = 0;
  for (auto _ : state) {
    if (b == static_cast<std::size_t>(kBatch)) {
      state.PauseTiming();
      batch.clear();
      for (int i = 0; i < kBatch; ++i) batch.push_back(p.nextKeyframe());
      b = 0;
      state.ResumeTiming();
    }
    const LoopResult r = p.detector->process(batch[b]);
    features += batch[b].features.size();
    ++b;
    bench::addStageTimes(r.timings, &sum);
    total_max = std::max(total_max, r.timings.total_ms);
    candidates += r.candidates_scored;
    loops += r.status == LoopStatus::kLoopDetected ? 1 : 0;
    ++n;
  }
  const double k = n > 0 ? 1.0 / n : 0.0;
  state.counters["transform"] = sum.transform_ms * k;
  state.counters["word_groups"] = sum.word_groups_ms * k;
  state.counters["query"] = sum.query_ms * k;
  state.counters["islands"] = sum.islands_ms * k;
  state.counters["verification"] = sum.verification_ms * k;
  state.counters["total_mean"] = sum.total_ms * k;
  state.counters["total_max"] = total_max;
  state.counters["features"] = features * k;
  state.counters["candidates"] = candidates * k;
  state.counters["loops"] = loops * k;
  const Database& db = p.detector->database();
  state.counters["db_size"] = static_cast<double>(db.size());
  state.counters["bytes_per_keyframe"] =
      static_cast<double>(db.memoryBytes()) / std::max<std::size_t>(1, db.size());
  state.counters["rss_growth_per_keyframe"] = growth.rss;
  state.counters["estimate_growth_per_keyframe"] = growth.estimate;
}

// Every keyframe indexed (IslandOptions::indexed_per_place 0, the default
// and DBoW2's way).
void BM_Pipeline(benchmark::State& state) { runPipeline(state, pipeline(false, 0)); }

BENCHMARK(BM_Pipeline)
    ->Arg(1000)
    ->Arg(5000)
    ->Arg(20000)
    ->Iterations(500)
    ->Unit(benchmark::kMillisecond);

// The same corridor with at most n keyframes of a place in the inverse
// index (arguments: keyframes, indexed_per_place n): the postings a query
// walks grow with the places, not the laps.
void BM_PipelinePlaceIndex(benchmark::State& state) {
  runPipeline(state, pipeline(false, static_cast<int>(state.range(1))));
}

// The trained case (arguments: keyframes, indexed_per_place n).
void BM_PipelineTrained(benchmark::State& state) {
  runPipeline(state, pipeline(true, static_cast<int>(state.range(1))));
}

BENCHMARK(BM_PipelineTrained)
    ->Args({1000, 3})
    ->Args({5000, 3})
    ->Args({20000, 3})
    ->Args({1000, 0})
    ->Args({5000, 0})
    ->Args({20000, 0})
    ->Iterations(500)
    ->Unit(benchmark::kMillisecond);

BENCHMARK(BM_PipelinePlaceIndex)
    ->Args({1000, 3})
    ->Args({5000, 3})
    ->Args({20000, 3})
    ->Args({1000, 1})
    ->Args({5000, 1})
    ->Args({20000, 1})
    ->Iterations(500)
    ->Unit(benchmark::kMillisecond);

// Memory at the 500 features per keyframe the memory target is stated for:
// resident-set and memoryBytes() growth per keyframe from 3,000 to 6,000
// keyframes (past the fixed tables and the first laps' new lists).
// Counters: features, rss_growth_per_keyframe, estimate_growth_per_keyframe
// (bytes), estimate_error (estimate / resident growth - 1).
void BM_Memory500Features(benchmark::State& state) {
  static std::unique_ptr<Pipeline> pipeline = stressPipeline(0, 63);
  Pipeline& p = *pipeline;
  for (auto _ : state) {
    p.growTo(3000);
    const Growth g = growMeasured(p, 6000);
    state.counters["features"] = g.features;
    state.counters["rss_growth_per_keyframe"] = g.rss;
    state.counters["estimate_growth_per_keyframe"] = g.estimate;
    state.counters["estimate_error"] = g.estimate / g.rss - 1.0;
  }
}

BENCHMARK(BM_Memory500Features)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace bowg

BENCHMARK_MAIN();
