// Database::query (database.h): the scores of every entry that shares a word
// or a group with the query, through the inverse index, in one walk of the
// query's lists.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "bowg/database/database.h"
#include "bowg/scoring/distribution.h"
#include "core/prefetch.h"
#include "database/id_union.h"

namespace bowg {
namespace {

using QueryWord = QueryScratch::QueryWord;

// visit(w, qw, qg) for each query word, in order.
template <typename Visit>
void forEachQueryWord(const InverseIndex& index, const std::vector<QueryWord>& words, Visit visit) {
  const std::size_t m = words.size();
  for (std::size_t i = 0; i < m; ++i) {
    // The lists lie scattered over the index: the walk waited on the first
    // load of each. Ask for the list headers 8 words ahead and their first
    // postings 4 ahead.
    if (i + 8 < m) prefetchRead(&index.list(words[i + 8].w));
    if (i + 4 < m) prefetchRead(index.list(words[i + 4].w).data());
    visit(words[i].w, words[i].qw, words[i].qg);
  }
}

// The word and group terms of every posting of the query's lists with an
// entry below n, into the scratch's accumulators; every entry reached is
// flagged (collectTouched lists them afterwards).
template <typename Term>
void accumulate(const InverseIndex& index, std::size_t n, Term term, QueryScratch* scratch) {
  forEachQueryWord(index, scratch->words, [&](WordId w, double qw, double qg) {
    for (const Posting& p : index.list(w)) {
      const EntryId e = p.entry();
      if (e >= n) break;  // lists are in ascending entry order
      if (qw != 0.0 && p.word != 0.f) {
        scratch->sums[e].word += term(qw, static_cast<double>(p.word));
        scratch->touched_flag[e] = 1;
      }
      const std::uint32_t code = p.groupCode();
      if (qg != 0.0 && code != 0) {
        scratch->sums[e].group += qg * index.groupCount(w, p);
        scratch->touched_flag[e] = 1;
      }
    }
  });
}

// accumulate() for a metric whose term is +0 when either weight is 0 (L1:
// |x| + 0 - |x|; L2 and the dot product: x * 0), so that the word term needs
// no test, nor the group term (qg * 0 for a posting without a group): adding
// +0 to a sum that starts at +0 changes no bit. The entry is flagged without
// a branch (in an aliased pipe most postings' tests go either way and were
// mispredicted) and without reading its flag: a walk that also listed each
// new entry as it went waited on every flag's load, a cache miss in a large
// map, before the next posting could be listed.
template <typename Term>
void accumulateZeroSafe(const InverseIndex& index, std::size_t n, Term term,
                        QueryScratch* scratch) {
  std::vector<QueryScratch::Sums>& sums = scratch->sums;
  std::vector<std::uint8_t>& flag = scratch->touched_flag;
  forEachQueryWord(index, scratch->words, [&](WordId w, double qw, double qg) {
    const bool with_word = qw != 0.0, with_group = qg != 0.0;
    for (const Posting& p : index.list(w)) {
      const EntryId e = p.entry();
      if (e >= n) break;  // lists are in ascending entry order
      const std::uint32_t code = p.groupCode();
      sums[e].word += term(qw, static_cast<double>(p.word));
      // A count in the overflow table is looked up only when it counts.
      const double count = code < Posting::kGroupOverflow ? static_cast<double>(code)
                           : with_group                   ? index.overflowCount(w, e)
                                                          : 0.0;
      sums[e].group += qg * count;
      flag[e] |=
          static_cast<std::uint8_t>((with_word & (p.word != 0.f)) | (with_group & (code != 0)));
    }
  });
}

// The flagged entries below n into scratch->touched, ascending; returns how
// many. One pass over the flags, without a branch per entry (a large map's
// queries flag about half of it at random); eight flags at a time are
// skipped where none is set (a query of rare words).
std::size_t collectTouched(std::size_t n, QueryScratch* scratch) {
  const std::uint8_t* flag = scratch->touched_flag.data();
  EntryId* touched = scratch->touched.data();
  std::size_t k = 0, id = 0;
  for (; id + 8 <= n; id += 8) {
    std::uint64_t eight;
    std::memcpy(&eight, flag + id, sizeof eight);
    if (eight == 0) continue;
    for (std::size_t j = id; j < id + 8; ++j) {
      touched[k] = static_cast<EntryId>(j);
      k += flag[j];
    }
  }
  for (; id < n; ++id) {
    touched[k] = static_cast<EntryId>(id);
    k += flag[id];
  }
  return k;
}

}  // namespace

void Database::collectQueryWords(const DatabaseQuery& q, bool with_groups,
                                 QueryScratch* scratch) const {
  // One walk over the query's words and groups (both sorted by id; a group
  // without a word weight is possible, e.g. a word of IDF 0). The group's
  // weight is its refined weight times the table's CURRENT IDF (eq. 1
  // applied now), read at makeQuery while the table is unchanged.
  const GroupVector& groups = q.refined_groups;
  static const GroupVector kNoGroups;
  const bool idf_read = queryIdfCurrent(q);
  scratch->words.clear();
  forEachId(q.bow, with_groups ? groups : kNoGroups,
            [&](WordId w, const BowEntry* word, const GroupEntry* group) {
              const double qw = word ? word->second : 0.0;
              const double idf = !group ? 0.0
                                 : idf_read
                                     ? q.group_idf[static_cast<std::size_t>(group - groups.data())]
                                     : group_table_.idf(w);
              const double qg = group ? group->second * idf : 0.0;
              if (qw != 0.0 || qg != 0.0) scratch->words.push_back(QueryWord{w, qw, qg});
            });
}

std::vector<EntryScores> Database::query(const DatabaseQuery& q, EntryId limit,
                                         bool with_groups) const {
  QueryScratch scratch;
  return query(q, limit, with_groups, &scratch);
}

std::vector<EntryScores> Database::query(const DatabaseQuery& q, EntryId limit, bool with_groups,
                                         QueryScratch* scratch) const {
  const std::size_t n = std::min<std::size_t>(limit, entries_.size());
  if (scratch->sums.size() < entries_.size()) {
    scratch->sums.resize(entries_.size());
    scratch->touched_flag.resize(entries_.size(), 0);
    scratch->touched.resize(entries_.size() + 1);  // one past the last: the branch-free touch
  }
  // Word score: accumulated over the shared words only, term by term as
  // scoreBowVectors() does (DBoW2's inverse-index scoring). Group score:
  // the dot product of eq. 3, <w~_q, w~_e>, with the entry's refined weight
  // = raw / sum (its TF, the division applied per entry in finishScores).
  const double base = bowScoreBase(scoring_, q.bow);
  collectQueryWords(q, with_groups, scratch);
  // The metric is chosen once per query, not once per posting.
  switch (scoring_) {
    case ScoringType::kL1:
      accumulateZeroSafe(
          index_, n, [](double x, double y) { return l1ScoreTerm(x, y); }, scratch);
      break;
    case ScoringType::kL2:
    case ScoringType::kDotProduct:
      accumulateZeroSafe(
          index_, n, [](double x, double y) { return x * y; }, scratch);
      break;
    default:
      accumulate(
          index_, n, [this](double x, double y) { return bowScoreTerm(scoring_, x, y); }, scratch);
      break;
  }
  return finishScores(q, with_groups, base, collectTouched(n, scratch), scratch);
}

std::vector<EntryScores> Database::finishScores(const DatabaseQuery& q, bool with_groups,
                                                double base, std::size_t touched,
                                                QueryScratch* scratch) const {
  std::vector<EntryScores> out;
  out.reserve(touched);
  // An empty distribution vector asks for no distribution score.
  const bool with_distribution = !q.distribution.empty();
  // A large map's query scores hundreds of thousands of entries: the query's
  // side of the distribution score is prepared once.
  DistributionScorer distribution;
  if (with_distribution) {
    distribution = DistributionScorer(
        q.distribution, static_cast<std::size_t>(distributions_.bins()), "Database::query");
  }
  for (std::size_t t = 0; t < touched; ++t) {
    const EntryId id = scratch->touched[t];
    // The table's row of an entry some places ahead: the entries touched lie
    // scattered over a large map, and each row was waited on.
    if (with_distribution && t + 8 < touched) {
      prefetchRead(distributions_.values(scratch->touched[t + 8]));
    }
    EntryScores s;
    s.entry = id;
    // An entry reached through groups only shares no word: its word score is
    // what scoreBowVectors() gives for disjoint vectors (0, or exp(-base) for KL).
    s.s_w = bowScoreFinish(scoring_, scratch->sums[id].word, base);
    const double sum = index_.groupSum(id);  // > 0 for an entry reached through a group
    s.s_g = with_groups ? groupScoreFromDot(sum > 0.0 ? scratch->sums[id].group / sum : 0.0) : 0.0;
    if (with_distribution) s.s_d = distribution.score(distributions_.values(id));
    out.push_back(s);
    scratch->sums[id] = QueryScratch::Sums();
    scratch->touched_flag[id] = 0;
  }
  return out;
}

}  // namespace bowg
