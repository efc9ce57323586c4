// Clustering one node of the vocabulary tree (node_clustering.h; DBoW2's
// HKmeansStep with k-means++ seeding of Arthur & Vassilvitskii 2007).
#include "vocabulary/node_clustering.h"

#include <random>

namespace bowg {
namespace node_clustering {
namespace {

// SplitMix64: decorrelates (seed, node id) into one generator seed.
std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

std::uint64_t draw64(std::mt19937& rng) {
  const std::uint64_t hi = rng();
  return (hi << 32) | rng();
}

// Bit counts of the members of one cluster, for the bitwise-majority centre.
inline void addBits(const Descriptor& d, std::int32_t* counts, std::int32_t delta) {
  for (int b = 0; b < 4; ++b) {
    std::uint64_t w = d.bits[b];
    while (w != 0) {
      counts[b * 64 + __builtin_ctzll(w)] += delta;
      w &= w - 1;
    }
  }
}

// DBoW2's rule (FORB::meanValue): bit set when at least ceil(n/2) members
// have it, i.e. 2 * count >= n.
Descriptor majority(const std::int32_t* counts, std::int32_t n) {
  Descriptor d;
  for (int bit = 0; bit < 256; ++bit) {
    if (2 * counts[bit] >= n) d.bits[bit / 64] |= 1ull << (bit % 64);
  }
  return d;
}

inline std::uint32_t nearest(const Descriptor& d, const std::vector<Descriptor>& centres) {
  std::uint32_t best = 0;
  int best_distance = hammingDistance(d, centres[0]);
  for (std::uint32_t c = 1; c < centres.size(); ++c) {
    const int distance = hammingDistance(d, centres[c]);
    if (distance < best_distance) {
      best_distance = distance;
      best = c;
    }
  }
  return best;
}

// k-means++ seeding: the first centre drawn uniformly, each next one with
// probability proportional to its squared Hamming distance to the nearest
// centre so far; stops early when every descriptor coincides with a centre.
std::vector<Descriptor> seedCentres(const Descriptor* all, const std::uint32_t* it, std::size_t m,
                                    std::size_t k, std::mt19937* rng, int threads) {
  std::vector<Descriptor> centres;
  centres.push_back(all[it[draw64(*rng) % m]]);
  std::vector<std::uint32_t> d2(m);
  parallelRanges(m, threads, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const std::uint32_t d = static_cast<std::uint32_t>(hammingDistance(all[it[i]], centres[0]));
      d2[i] = d * d;
    }
  });
  while (centres.size() < k) {
    std::uint64_t total = 0;
    for (std::uint32_t v : d2) total += v;
    if (total == 0) break;  // every descriptor coincides with a centre
    const std::uint64_t r = draw64(*rng) % total;
    std::uint64_t acc = 0;
    std::size_t pick = 0;
    for (; pick < m; ++pick) {
      acc += d2[pick];
      if (acc > r) break;
    }
    centres.push_back(all[it[pick]]);
    const Descriptor& c = centres.back();
    parallelRanges(m, threads, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        const std::uint32_t d = static_cast<std::uint32_t>(hammingDistance(all[it[i]], c));
        d2[i] = std::min(d2[i], d * d);
      }
    });
  }
  return centres;
}

// The cluster of every item and the size of every cluster.
struct Assignment {
  std::vector<std::uint32_t> cluster;
  std::vector<std::int32_t> sizes;
};

// k-medians iterations with incremental bit counts: after the first
// assignment only the descriptors that change cluster are recounted. Moves
// `centres` to the bitwise majority of their members.
Assignment kMedians(const Descriptor* all, const std::uint32_t* it, std::size_t m,
                    int max_iterations, int threads, std::vector<Descriptor>* centres) {
  const std::size_t kc = centres->size();
  Assignment a;
  a.cluster.resize(m);
  a.sizes.assign(kc, 0);
  std::vector<std::uint32_t>& assign = a.cluster;
  std::vector<std::int32_t>& sizes = a.sizes;
  std::vector<std::uint32_t> next(m);
  std::vector<std::int32_t> counts(kc * 256, 0);
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    parallelRanges(m, threads, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) next[i] = nearest(all[it[i]], *centres);
    });
    bool changed = false;
    for (std::size_t i = 0; i < m; ++i) {
      if (iteration == 0) {
        addBits(all[it[i]], &counts[next[i] * 256], 1);
        ++sizes[next[i]];
        changed = true;
      } else if (next[i] != assign[i]) {
        addBits(all[it[i]], &counts[assign[i] * 256], -1);
        --sizes[assign[i]];
        addBits(all[it[i]], &counts[next[i] * 256], 1);
        ++sizes[next[i]];
        changed = true;
      }
    }
    assign.swap(next);
    if (!changed) break;
    for (std::size_t c = 0; c < kc; ++c) {
      if (sizes[c] > 0) (*centres)[c] = majority(&counts[c * 256], sizes[c]);
    }
  }
  return a;
}

// Drops empty clusters and sorts items[begin, end) by cluster (stable
// counting sort): the split's centres and child ranges.
Split sortByCluster(const Assignment& a, const std::vector<Descriptor>& centres,
                    std::uint32_t* items, std::size_t begin, std::size_t end) {
  const std::size_t m = end - begin;
  std::uint32_t* const it = items + begin;
  const std::size_t kc = centres.size();
  std::vector<std::uint32_t> remap(kc, 0xffffffffu);
  std::vector<std::size_t> offset;
  Split split;
  std::size_t pos = begin;
  for (std::size_t c = 0; c < kc; ++c) {
    if (a.sizes[c] == 0) continue;
    remap[c] = static_cast<std::uint32_t>(split.centres.size());
    split.centres.push_back(centres[c]);
    offset.push_back(pos);
    pos += static_cast<std::size_t>(a.sizes[c]);
  }
  split.bounds = offset;
  split.bounds.push_back(end);
  std::vector<std::uint32_t> sorted(m);
  for (std::size_t i = 0; i < m; ++i) sorted[offset[remap[a.cluster[i]]]++ - begin] = it[i];
  std::copy(sorted.begin(), sorted.end(), it);
  return split;
}

}  // namespace

Split clusterNode(const Descriptor* all, std::uint32_t* items, std::size_t begin, std::size_t end,
                  const TrainingOptions& options, NodeId node, int threads) {
  const std::size_t m = end - begin;
  std::uint32_t* const it = items + begin;
  const std::size_t k = static_cast<std::size_t>(options.k);
  if (m <= k) {
    // DBoW2: with at most k descriptors, each is its own cluster.
    Split split;
    for (std::size_t i = 0; i < m; ++i) {
      split.centres.push_back(all[it[i]]);
      split.bounds.push_back(begin + i);
    }
    split.bounds.push_back(end);
    return split;
  }
  std::mt19937 rng(static_cast<std::uint32_t>(mix64(options.seed ^ mix64(node))));
  std::vector<Descriptor> centres = seedCentres(all, it, m, k, &rng, threads);
  const Assignment a = kMedians(all, it, m, options.max_iterations, threads, &centres);
  return sortByCluster(a, centres, items, begin, end);
}

bool allIdentical(const Descriptor* all, const std::uint32_t* items, std::size_t begin,
                  std::size_t end) {
  for (std::size_t i = begin + 1; i < end; ++i) {
    if (all[items[i]] != all[items[begin]]) return false;
  }
  return true;
}

}  // namespace node_clustering
}  // namespace bowg
