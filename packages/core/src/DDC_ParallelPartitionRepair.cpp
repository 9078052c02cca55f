// The clean-up of a partition of a DistributedGraph (DDC_ParallelPartition.hpp):
// fillEmptySubdomains(), joinDetachedPieces() and edgeCut() of
// DDC_Partition.hpp with the graph spread over the ranks. Each rank reads
// its own vertices' rows and the subdomains of the neighbours other ranks
// hold (GraphHalo); a piece of a subdomain is named by its lowest vertex id
// and judged by that vertex's rank. The rules and their tie-breaks are the
// serial ones, so the result is the serial clean-up's of the gathered
// partition (core_parallel_partition).
#include <algorithm>
#include <climits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_ParallelPartition.hpp"

namespace ddc {

namespace {

/// The neighbours of a DistributedGraph's local vertices that other ranks
/// hold (ghosts), and their values: fetch(local) returns each ghost's value
/// of a per-vertex array the ranks hold in pieces, and value() reads a
/// neighbour's value from the local array or the fetched ghosts.
class GraphHalo {
 public:
  GraphHalo(MPI_Comm comm, const DistributedGraph& g) : comm_(comm), g_(g), first_(g.firstVertex[commRank(comm)]) {
    const int size = commSize(comm);
    for (long long v : g.neighbours)
      if (!isLocal(v)) ghosts_.push_back(v);
    std::sort(ghosts_.begin(), ghosts_.end());
    ghosts_.erase(std::unique(ghosts_.begin(), ghosts_.end()), ghosts_.end());
    // Each rank asks the holders for its ghosts in increasing id, so the
    // answers arrive in the order of ghosts_ (by rank, then id).
    std::vector<std::vector<Request>> ask(size);
    for (long long v : ghosts_) ask[g.holder(v)].push_back(Request{commRank(comm), v});
    serve_.resize(size);
    for (const Request& r : exchangeRecords(comm, ask)) serve_[r.from].push_back(r.vertex - first_);
  }

  bool isLocal(long long v) const { return v >= first_ && v < first_ + g_.numLocal(); }
  long long localIndex(long long v) const { return v - first_; }
  long long first() const { return first_; }

  /// The ghosts' values of `local` (one value per local vertex on every
  /// rank), in the order value() reads them. Collective.
  template <class T>
  std::vector<T> fetch(const std::vector<T>& local) const {
    std::vector<std::vector<T>> send(serve_.size());
    for (size_t r = 0; r < serve_.size(); ++r)
      for (long long l : serve_[r]) send[r].push_back(local[l]);
    return exchangeRecords(comm_, send);
  }

  /// Vertex v's value: from `local` if this rank holds v, else from `ghosts` (fetch(local)).
  template <class T>
  T value(long long v, const std::vector<T>& local, const std::vector<T>& ghosts) const {
    if (isLocal(v)) return local[localIndex(v)];
    return ghosts[std::lower_bound(ghosts_.begin(), ghosts_.end(), v) - ghosts_.begin()];
  }

 private:
  struct Request {
    long long from, vertex;
  };
  MPI_Comm comm_;
  const DistributedGraph& g_;
  long long first_;
  std::vector<long long> ghosts_;              ///< sorted ids of the neighbours other ranks hold
  std::vector<std::vector<long long>> serve_;  ///< per rank: the local vertices it asked for, in its order
};

/// Elements per subdomain over all ranks.
std::vector<long long> subdomainSizes(MPI_Comm comm, const std::vector<int>& parts, int numSubdomains) {
  std::vector<long long> mine(numSubdomains, 0), all(numSubdomains, 0);
  for (int s : parts) ++mine[s];
  MPI_Allreduce(mine.data(), all.data(), numSubdomains, MPI_LONG_LONG, MPI_SUM, comm);
  return all;
}

/// The lowest (a, b) over the ranks, lexicographically.
std::pair<long long, long long> lowestPair(MPI_Comm comm, std::pair<long long, long long> mine) {
  long long a = mine.first, b = LLONG_MAX;
  MPI_Allreduce(&mine.first, &a, 1, MPI_LONG_LONG, MPI_MIN, comm);
  const long long candidate = mine.first == a ? mine.second : LLONG_MAX;
  MPI_Allreduce(&candidate, &b, 1, MPI_LONG_LONG, MPI_MIN, comm);
  return {a, b};
}

/// The piece of each local vertex: the lowest vertex id of the vertices of
/// its subdomain connected to it through the subdomain's edges (labels
/// spread to the lowest, exchanged until no rank's label changes).
std::vector<long long> pieceLabels(MPI_Comm comm, const DistributedGraph& g, const GraphHalo& halo,
                                   const std::vector<int>& parts, const std::vector<int>& ghostParts) {
  std::vector<long long> label(parts.size());
  for (size_t l = 0; l < label.size(); ++l) label[l] = halo.first() + static_cast<long long>(l);
  for (bool changed = true; changed;) {
    const std::vector<long long> ghostLabels = halo.fetch(label);
    bool mine = false;
    for (long long l = 0; l < g.numLocal(); ++l)
      for (long long k = g.offsets[l]; k < g.offsets[l + 1]; ++k) {
        const long long v = g.neighbours[k];
        if (halo.value(v, parts, ghostParts) != parts[l]) continue;
        const long long other = halo.value(v, label, ghostLabels);
        if (other < label[l]) label[l] = other, mine = true;
      }
    changed = anyRank(comm, mine);
  }
  return label;
}

/// What the rank of a piece's label learns of the piece.
struct PieceRecord {
  long long label, subdomain, count;  ///< subdomain -1: the piece's own size; else facets to that subdomain
};

/// A piece that joins another subdomain.
struct Move {
  long long label, target;
};

/// One pass of joinDetachedPieces() on a distributed graph; true (on every
/// rank) if a piece moved.
bool joinPiecesOnce(MPI_Comm comm, const DistributedGraph& g, const GraphHalo& halo, int numSubdomains,
                    std::vector<int>& parts) {
  const int size = commSize(comm);
  const std::vector<int> ghostParts = halo.fetch(parts);
  const std::vector<long long> label = pieceLabels(comm, g, halo, parts, ghostParts);
  // Sizes and facets to other subdomains, summed at the rank of each label.
  std::map<std::pair<long long, long long>, long long> local;
  for (long long l = 0; l < g.numLocal(); ++l) {
    ++local[{label[l], -1}];
    for (long long k = g.offsets[l]; k < g.offsets[l + 1]; ++k) {
      const int s = halo.value(g.neighbours[k], parts, ghostParts);
      if (s != parts[l]) ++local[{label[l], s}];
    }
  }
  std::vector<std::vector<PieceRecord>> send(size);
  for (const auto& [key, count] : local)
    send[g.holder(key.first)].push_back(PieceRecord{key.first, key.second, count});
  std::map<long long, std::map<long long, long long>> pieces;  // label -> subdomain (-1: size) -> count
  for (const PieceRecord& r : exchangeRecords(comm, send)) pieces[r.label][r.subdomain] += r.count;
  // The piece each subdomain keeps: its largest, the lowest label on ties.
  std::vector<long long> largest(numSubdomains, 0), kept(numSubdomains, LLONG_MAX);
  for (const auto& [piece, counts] : pieces) {
    long long& m = largest[parts[halo.localIndex(piece)]];
    m = std::max(m, counts.at(-1));
  }
  MPI_Allreduce(MPI_IN_PLACE, largest.data(), numSubdomains, MPI_LONG_LONG, MPI_MAX, comm);
  for (const auto& [piece, counts] : pieces) {
    const int s = parts[halo.localIndex(piece)];
    if (counts.at(-1) == largest[s]) kept[s] = std::min(kept[s], piece);
  }
  MPI_Allreduce(MPI_IN_PLACE, kept.data(), numSubdomains, MPI_LONG_LONG, MPI_MIN, comm);
  const double splinter = kMaxJoinedPieceShare * double(g.firstVertex.back()) / std::max(numSubdomains, 1);
  std::vector<Move> moves;
  for (const auto& [piece, counts] : pieces) {
    if (kept[parts[halo.localIndex(piece)]] == piece || double(counts.at(-1)) > splinter) continue;
    long long best = 0, target = -1;
    for (const auto& [s, facets] : counts)  // ascending ids: the lowest wins ties
      if (s >= 0 && facets > best) best = facets, target = s;
    if (target >= 0) moves.push_back(Move{piece, target});
  }
  // Every rank learns every move (splinters are few).
  std::vector<Move> all = exchangeRecords(comm, std::vector<std::vector<Move>>(size, moves));
  std::sort(all.begin(), all.end(), [](const Move& a, const Move& b) { return a.label < b.label; });
  for (long long l = 0; l < g.numLocal(); ++l) {
    const auto it = std::lower_bound(all.begin(), all.end(), label[l],
                                     [](const Move& m, long long x) { return m.label < x; });
    if (it != all.end() && it->label == label[l]) parts[l] = static_cast<int>(it->target);
  }
  return !all.empty();
}

/// "" or what is wrong with `parts` (one subdomain in range per local vertex).
std::string checkParts(const DistributedGraph& g, int numSubdomains, const std::vector<int>& parts) {
  if (static_cast<long long>(parts.size()) != g.numLocal())
    return "one subdomain per local vertex expected, got " + std::to_string(parts.size()) + " for " +
           std::to_string(g.numLocal());
  for (int s : parts)
    if (s < 0 || s >= numSubdomains) return "subdomain " + std::to_string(s) + " out of range";
  return std::string();
}

void requireParts(MPI_Comm comm, const DistributedGraph& g, int numSubdomains, const std::vector<int>& parts,
                  const char* who) {
  const std::string bad = firstErrorOnAnyRank(comm, checkParts(g, numSubdomains, parts));
  if (!bad.empty()) throw std::invalid_argument(std::string(who) + ": " + bad);
}

}  // namespace

void fillEmptySubdomains(MPI_Comm comm, const DistributedGraph& g, int numSubdomains, std::vector<int>& parts) {
  requireParts(comm, g, numSubdomains, parts, "fillEmptySubdomains()");
  std::vector<long long> count = subdomainSizes(comm, parts, numSubdomains);
  const GraphHalo halo(comm, g);
  for (int s = 0; s < numSubdomains; ++s) {
    if (count[s] != 0) continue;
    const int donor = static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());
    const std::vector<int> ghostParts = halo.fetch(parts);
    // The donor's element with the fewest neighbours inside it, lowest id on ties.
    std::pair<long long, long long> best{LLONG_MAX, LLONG_MAX};
    for (long long l = 0; l < g.numLocal(); ++l) {
      if (parts[l] != donor) continue;
      long long inside = 0;
      for (long long k = g.offsets[l]; k < g.offsets[l + 1]; ++k) inside += halo.value(g.neighbours[k], parts, ghostParts) == donor;
      best = std::min(best, std::make_pair(inside, halo.first() + l));
    }
    best = lowestPair(comm, best);
    DDC_CHECK(best.second != LLONG_MAX && count[donor] > 1, "no donor element for empty subdomain");
    if (halo.isLocal(best.second)) parts[halo.localIndex(best.second)] = s;
    --count[donor];
    ++count[s];
  }
}

void joinDetachedPieces(MPI_Comm comm, const DistributedGraph& g, int numSubdomains, std::vector<int>& parts) {
  requireParts(comm, g, numSubdomains, parts, "joinDetachedPieces()");
  const GraphHalo halo(comm, g);
  for (int pass = 0; pass < kMaxPieceJoinPasses && joinPiecesOnce(comm, g, halo, numSubdomains, parts); ++pass) {
  }
}

long long edgeCut(MPI_Comm comm, const DistributedGraph& g, const std::vector<int>& parts) {
  const GraphHalo halo(comm, g);
  const std::vector<int> ghostParts = halo.fetch(parts);
  long long cut = 0;
  for (long long l = 0; l < g.numLocal(); ++l)
    for (long long k = g.offsets[l]; k < g.offsets[l + 1]; ++k) {
      const long long v = g.neighbours[k];
      if (halo.first() + l < v && halo.value(v, parts, ghostParts) != parts[l]) ++cut;
    }
  MPI_Allreduce(MPI_IN_PLACE, &cut, 1, MPI_LONG_LONG, MPI_SUM, comm);
  return cut;
}

}  // namespace ddc
