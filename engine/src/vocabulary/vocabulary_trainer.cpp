// Hierarchical k-medians training of the vocabulary tree (see
// vocabulary_trainer.h; DBoW2's TemplatedVocabulary::create / HKmeansStep,
// k-means++ seeding of Arthur & Vassilvitskii 2007).
//
// Work layout: one array of descriptor indices, partitioned in place as the
// tree grows, so memory stays O(N) and no descriptor is copied. Each level
// clusters all its nodes (in parallel across nodes, or inside one big node),
// then numbers the children sequentially: the result does not depend on the
// thread count. Each node's random generator is seeded from (seed, node id).
#include "bowg/vocabulary/vocabulary_trainer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>

#include "bowg/core/errors.h"

namespace bowg {

void TrainingOptions::validate() const {
  if (k < 2) throw InvalidParameter("training.k: must be >= 2, got " + std::to_string(k));
  if (L < 1) throw InvalidParameter("training.L: must be >= 1, got " + std::to_string(L));
  if (L > 64) throw InvalidParameter("training.L: must be <= 64, got " + std::to_string(L));
  if (k > 4096) throw InvalidParameter("training.k: must be <= 4096, got " + std::to_string(k));
  if (max_iterations < 1) {
    throw InvalidParameter("training.max_iterations: must be >= 1, got " +
                           std::to_string(max_iterations));
  }
  if (threads < 1 || threads > 64) {
    throw InvalidParameter("training.threads: must be in [1, 64], got " + std::to_string(threads));
  }
  const int w = static_cast<int>(weighting);
  const int s = static_cast<int>(scoring);
  if (w < 0 || w > 3)
    throw InvalidParameter("training.weighting: unknown value " + std::to_string(w));
  if (s < 0 || s > 5)
    throw InvalidParameter("training.scoring: unknown value " + std::to_string(s));
}

namespace {

using Node = Vocabulary::Node;

// Runs fn(begin, end) over [0, n) split into `threads` contiguous parts.
template <typename Fn>
void parallelRanges(std::size_t n, int threads, Fn fn) {
  if (threads <= 1 || n < 4096) {
    fn(std::size_t(0), n);
    return;
  }
  std::vector<std::thread> pool;
  const std::size_t step =
      (n + static_cast<std::size_t>(threads) - 1) / static_cast<std::size_t>(threads);
  for (int t = 1; t < threads; ++t) {
    const std::size_t b = std::min(n, step * static_cast<std::size_t>(t));
    const std::size_t e = std::min(n, b + step);
    pool.emplace_back([=] { fn(b, e); });
  }
  fn(std::size_t(0), std::min(n, step));
  for (auto& th : pool) th.join();
}

// Runs task(i) for i in [0, n) on `threads` workers pulling indices.
template <typename Fn>
void parallelTasks(std::size_t n, int threads, Fn task) {
  if (threads <= 1 || n < 2) {
    for (std::size_t i = 0; i < n; ++i) task(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < n;) task(i);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
}

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

struct Pending {
  NodeId node;
  std::size_t begin, end;  // range in the item array
};

struct Split {
  std::vector<Descriptor> centres;  // one per non-empty child
  std::vector<std::size_t> bounds;  // child c owns items [bounds[c], bounds[c+1])
};

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

// Clusters items[begin, end) (at least 2 items) into at most k children and
// reorders the range so that each child's items are contiguous.
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

// The tree's nodes level by level: every node of the previous level with
// more than one distinct descriptor is clustered into at most k children.
std::vector<Node> clusterLevels(const std::vector<Descriptor>& all,
                                std::vector<std::uint32_t>* item_order,
                                const TrainingOptions& options, double steps,
                                const std::function<void(double, const std::string&)>& report) {
  std::vector<std::uint32_t>& items = *item_order;
  const std::size_t total = items.size();
  std::vector<Node> nodes(1);
  std::vector<Pending> pending{{0, 0, total}};
  for (int level = 1; level <= options.L && !pending.empty(); ++level) {
    const std::string stage =
        "clustering level " + std::to_string(level) + "/" + std::to_string(options.L);
    report((level - 1) / steps, stage);
    std::vector<Split> splits(pending.size());
    // Few big nodes: parallelise inside each; many nodes: across nodes.
    const bool across = pending.size() >= static_cast<std::size_t>(4 * options.threads);
    parallelTasks(pending.size(), across ? options.threads : 1, [&](std::size_t i) {
      const Pending& p = pending[i];
      if (p.node != 0 && allIdentical(all.data(), items.data(), p.begin, p.end)) return;  // leaf
      splits[i] = clusterNode(all.data(), items.data(), p.begin, p.end, options, p.node,
                              across ? 1 : options.threads);
    });
    std::vector<Pending> next;
    for (std::size_t i = 0; i < pending.size(); ++i) {
      Split& s = splits[i];
      const NodeId parent = pending[i].node;
      // A node split into one child only is a leaf, except the root, which
      // must have children.
      if (s.centres.empty() || (s.centres.size() == 1 && parent != 0)) continue;
      nodes[parent].first_child = static_cast<std::uint32_t>(nodes.size());
      nodes[parent].num_children = static_cast<std::uint32_t>(s.centres.size());
      for (std::size_t c = 0; c < s.centres.size(); ++c) {
        Node child;
        child.parent = parent;
        child.level = static_cast<std::uint32_t>(level);
        child.descriptor = s.centres[c];
        const NodeId id = static_cast<NodeId>(nodes.size());
        nodes.push_back(child);
        const std::size_t b = s.bounds[c];
        const std::size_t e = s.bounds[c + 1];
        if (level < options.L && e - b > 1) next.push_back({id, b, e});
      }
    }
    pending.swap(next);
  }
  return nodes;
}

// IDF weights as DBoW2's setNodeWeights: descend every training descriptor
// with the final tree, count the images containing each word. Other
// weightings: 1.
void weightWords(const std::vector<std::vector<Descriptor>>& per_image,
                 const TrainingOptions& options, WordId words, std::vector<Node>* tree_nodes) {
  std::vector<Node>& nodes = *tree_nodes;
  Vocabulary tree(options.k, options.L, options.weighting, options.scoring, nodes);
  const bool idf =
      options.weighting == WeightingType::kTfIdf || options.weighting == WeightingType::kIdf;
  if (idf) {
    const int threads = std::min<int>(options.threads, static_cast<int>(per_image.size()));
    std::vector<std::vector<std::uint32_t>> images_with(
        static_cast<std::size_t>(std::max(1, threads)), std::vector<std::uint32_t>(words, 0));
    std::atomic<std::size_t> next_image{0};
    auto worker = [&](int t) {
      std::vector<std::uint32_t>& count = images_with[static_cast<std::size_t>(t)];
      std::vector<WordId> seen;
      for (std::size_t i; (i = next_image.fetch_add(1)) < per_image.size();) {
        seen.clear();
        for (const Descriptor& d : per_image[i]) seen.push_back(tree.transform(d));
        std::sort(seen.begin(), seen.end());
        seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
        for (WordId w : seen) ++count[w];
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker, t);
    worker(0);
    for (auto& th : pool) th.join();
    const double n_images = static_cast<double>(per_image.size());
    for (std::size_t w = 0; w < words; ++w) {
      std::uint32_t ni = 0;
      for (const auto& c : images_with) ni += c[w];
      // DBoW2: words no image reached keep weight 0.
      nodes[tree.nodeOfWord(static_cast<WordId>(w))].weight =
          ni > 0 ? std::log(n_images / ni) : 0.0;
    }
  } else {
    for (std::size_t w = 0; w < words; ++w)
      nodes[tree.nodeOfWord(static_cast<WordId>(w))].weight = 1.0;
  }
}

}  // namespace

Vocabulary trainVocabulary(const std::vector<std::vector<Descriptor>>& per_image,
                           const TrainingOptions& options, const TrainingProgress& progress) {
  options.validate();
  std::size_t total = 0;
  for (const auto& image : per_image) total += image.size();
  if (total == 0) throw std::invalid_argument("trainVocabulary: no training descriptors");
  if (total >= (1ull << 31)) {
    throw std::invalid_argument("trainVocabulary: too many training descriptors (" +
                                std::to_string(total) + ", at most 2^31 - 1)");
  }
  auto report = [&](double fraction, const std::string& stage) {
    if (progress) progress(std::min(1.0, std::max(0.0, fraction)), stage);
  };

  // One flat copy so that clustering indexes a single array.
  std::vector<Descriptor> all;
  all.reserve(total);
  for (const auto& image : per_image) all.insert(all.end(), image.begin(), image.end());
  std::vector<std::uint32_t> items(total);
  for (std::size_t i = 0; i < total; ++i) items[i] = static_cast<std::uint32_t>(i);

  // Training takes L clustering levels plus one pass for the weights.
  const double steps = options.L + 1.0;
  std::vector<Node> nodes = clusterLevels(all, &items, options, steps, report);
  std::vector<std::uint32_t>().swap(items);

  // Words in leaf (= breadth-first) order.
  WordId words = 0;
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    if (nodes[i].num_children == 0) nodes[i].word = words++;
  }
  report(options.L / steps, "weighting words");

  weightWords(per_image, options, words, &nodes);
  report(1.0, "done");
  return Vocabulary(options.k, options.L, options.weighting, options.scoring, std::move(nodes));
}

}  // namespace bowg
