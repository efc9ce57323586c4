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
#include "vocabulary/node_clustering.h"

namespace bowg {

void TrainingOptions::validate() const {
  if (k < 2) throw InvalidParameter("training.k: must be >= 2, got " + std::to_string(k));
  if (L < 1) throw InvalidParameter("training.L: must be >= 1, got " + std::to_string(L));
  if (L > 64) throw InvalidParameter("training.L: must be <= 64, got " + std::to_string(L));
  // The largest k every vocabulary format's loader accepts.
  if (k > kMaxBranching) {
    throw InvalidParameter("training.k: must be <= " + std::to_string(kMaxBranching) + ", got " +
                           std::to_string(k));
  }
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
using node_clustering::allIdentical;
using node_clustering::clusterNode;
using node_clustering::parallelTasks;
using node_clustering::Split;

struct Pending {
  NodeId node;
  std::size_t begin, end;  // range in the item array
};

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
