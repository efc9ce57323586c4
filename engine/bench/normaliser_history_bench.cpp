// Cost of the normaliser floor per query (normaliser_history.h): the median of
// the last `window` normalisers (three components) and one push. It runs for
// every keyframe, floor on or off, so it must stay negligible next to the
// ~1-4 ms of LoopDetector::process (docs/benchmarks.md).
#include <benchmark/benchmark.h>

#include <cstdint>

#include "bowg/scoring/normaliser_history.h"

namespace bowg {
namespace {

void BM_NormaliserMedianAndPush(benchmark::State& state) {
  const std::size_t window = static_cast<std::size_t>(state.range(0));
  NormaliserHistory h;
  std::uint64_t x = 12345;
  auto next = [&x]() {  // xorshift: varied values so nth_element does real work
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return static_cast<double>(x % 1000) / 1000.0;
  };
  for (std::size_t i = 0; i < window; ++i) h.push({next(), next(), next()}, window);
  for (auto _ : state) {
    const Normalisers m = h.median();
    benchmark::DoNotOptimize(m.word + m.group + m.distribution);
    h.push({next(), next(), next()}, window);
  }
}
BENCHMARK(BM_NormaliserMedianAndPush)->Arg(50)->Arg(500)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace bowg

BENCHMARK_MAIN();
