// One vocabulary load in a fresh process, as a node starting up meets it
// (the in-process benchmark, bowg_vocabulary_bench's BM_LoadBowgK10L6,
// reuses pages a previous load freed). scripts/run_benchmarks.sh runs it
// several times and reports the median against the 50 ms target.
//
//   bowg_vocabulary_load_once_bench --make-k10l6 PATH   write the synthetic k=10 L=6 tree
//   bowg_vocabulary_load_once_bench PATH                load it, print the milliseconds
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

#include "bowg/vocabulary/vocabulary.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "synthetic_vocabulary.h"

int main(int argc, char** argv) {
  try {
    if (argc == 3 && std::string(argv[1]) == "--make-k10l6") {
      bowg::saveVocabulary(bowg::testing::makeSyntheticVocabulary(10, 6, 1), argv[2]);
      return 0;
    }
    if (argc != 2) {
      std::fprintf(stderr, "usage: %s [--make-k10l6] PATH\n", argv[0]);
      return 2;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const bowg::Vocabulary v = bowg::loadVocabulary(argv[1]);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%.2f ms (%zu nodes)\n", ms, v.nodes().size());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
