// Vocabulary speed (targets in the task: 500 descriptors through a k=10 L=6
// tree well under 0.5 ms; loading the k=10 L=6 .bowgvoc well under 0.5 s).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>

#include "bowg/core/id_index_sort.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "bowg/vocabulary/vocabulary_trainer.h"
#include "core/cpu_features.h"
#include "synthetic_vocabulary.h"
#include "vocabulary/tree_descent.h"

namespace bowg {
namespace {

const Vocabulary& k10L6() {
  static const Vocabulary v = testing::makeSyntheticVocabulary(10, 6, 1);
  return v;
}

void BM_TransformImage500(benchmark::State& state) {
  const Vocabulary& v = k10L6();
  const auto descriptors = testing::randomDescriptors(500, 2);
  BowVector bow;
  for (auto _ : state) {
    v.transform(descriptors, &bow);
    benchmark::DoNotOptimize(bow.data());
  }
  state.SetItemsProcessed(state.iterations() * 500);
}
BENCHMARK(BM_TransformImage500)->Unit(benchmark::kMicrosecond);

// The same through a k=10 L=3 tree (1111 nodes, fits in L2): the
// difference to the above is the cost of cache misses in the big tree.
void BM_TransformImage500SmallTree(benchmark::State& state) {
  const Vocabulary v = testing::makeSyntheticVocabulary(10, 3, 1);
  const auto descriptors = testing::randomDescriptors(500, 2);
  BowVector bow;
  for (auto _ : state) {
    v.transform(descriptors, &bow);
    benchmark::DoNotOptimize(bow.data());
  }
}
BENCHMARK(BM_TransformImage500SmallTree)->Unit(benchmark::kMicrosecond);

void BM_TransformImage500WithDirectIndex(benchmark::State& state) {
  const Vocabulary& v = k10L6();
  const auto descriptors = testing::randomDescriptors(500, 2);
  BowVector bow;
  DirectIndex direct;
  std::vector<WordId> words;
  for (auto _ : state) {
    v.transform(descriptors, &bow, &direct, 4, &words);
    benchmark::DoNotOptimize(bow.data());
  }
}
BENCHMARK(BM_TransformImage500WithDirectIndex)->Unit(benchmark::kMicrosecond);

// The descent alone (tree_descent.h), 500 random descriptors through the
// k=10 L=6 tree: the portable loop and, where the CPU has AVX2, the vector
// one that Vocabulary::transform then uses.
void descend(benchmark::State& state, tree_descent::DescendBatch descend_batch) {
  const Vocabulary& v = k10L6();
  const auto descriptors = testing::randomDescriptors(500, 2);
  WordId words[tree_descent::kBatch];
  NodeId nodes[tree_descent::kBatch];
  for (auto _ : state) {
    for (std::size_t i = 0; i < descriptors.size(); i += tree_descent::kBatch) {
      descend_batch(v.nodes().data(), descriptors.data() + i,
                    std::min(tree_descent::kBatch, descriptors.size() - i), 0, words, nodes);
      benchmark::DoNotOptimize(words[0]);
    }
  }
}

void BM_DescendPortable(benchmark::State& state) {
  descend(state, tree_descent::descendBatchPortable);
}
BENCHMARK(BM_DescendPortable)->Unit(benchmark::kMicrosecond);

void BM_DescendAvx2(benchmark::State& state) {
  if (!cpuHasAvx2()) {
    state.SkipWithError("this CPU has no AVX2");
    return;
  }
  descend(state, tree_descent::descendBatchAvx2);
}
BENCHMARK(BM_DescendAvx2)->Unit(benchmark::kMicrosecond);

// An image's (word, feature) pairs as the transform makes them: 500
// features' words of a k=10 L=6 tree, feature index = position.
std::vector<IdIndexPair> imageWordPairs() {
  std::mt19937 rng(3);
  std::uniform_int_distribution<std::uint32_t> word(0, 999999);
  std::vector<IdIndexPair> pairs(500);
  for (std::uint32_t i = 0; i < pairs.size(); ++i) pairs[i] = {word(rng), i};
  return pairs;
}

// The transform's sort by word: std::sort (its comparisons of random words
// mispredict) against sortIdIndexPairs (a radix sort over the ids' bytes).
void BM_SortWordPairsStdSort(benchmark::State& state) {
  const std::vector<IdIndexPair> input = imageWordPairs();
  std::vector<IdIndexPair> pairs;
  for (auto _ : state) {
    pairs = input;
    std::sort(pairs.begin(), pairs.end());
    benchmark::DoNotOptimize(pairs.data());
  }
}
BENCHMARK(BM_SortWordPairsStdSort)->Unit(benchmark::kMicrosecond);

void BM_SortWordPairsRadix(benchmark::State& state) {
  const std::vector<IdIndexPair> input = imageWordPairs();
  std::vector<IdIndexPair> pairs;
  for (auto _ : state) {
    pairs = input;
    sortIdIndexPairs(&pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
}
BENCHMARK(BM_SortWordPairsRadix)->Unit(benchmark::kMicrosecond);

void BM_LoadBowgK10L6(benchmark::State& state) {
  const std::string path = "/tmp/bowg_vocabulary_bench_k10L6.bowgvoc";
  saveVocabulary(k10L6(), path);
  for (auto _ : state) {
    const Vocabulary v = loadVocabulary(path);
    benchmark::DoNotOptimize(v.fingerprint());
  }
  std::remove(path.c_str());
}
BENCHMARK(BM_LoadBowgK10L6)->Unit(benchmark::kMillisecond)->Iterations(5);

void BM_SaveBowgK10L6(benchmark::State& state) {
  const std::string path = "/tmp/bowg_vocabulary_bench_save.bowgvoc";
  for (auto _ : state) saveVocabulary(k10L6(), path);
  std::remove(path.c_str());
}
BENCHMARK(BM_SaveBowgK10L6)->Unit(benchmark::kMillisecond)->Iterations(3);

// Training k=10 L=6 on N random descriptors (1000 images of N/1000). Random
// descriptors are the worst case for k-medians convergence.
void BM_TrainK10L6(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  std::vector<std::vector<Descriptor>> images;
  for (std::size_t i = 0; i < 1000; ++i) images.push_back(testing::randomDescriptors(n / 1000, i));
  TrainingOptions o;
  o.threads = 2;
  for (auto _ : state) {
    const Vocabulary v = trainVocabulary(images, o);
    benchmark::DoNotOptimize(v.fingerprint());
  }
}
BENCHMARK(BM_TrainK10L6)->Arg(100000)->Arg(1000000)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace bowg

BENCHMARK_MAIN();
