// Who holds each node of a mesh divided into parts over the ranks
// (Mesh::part(), Mesh::migrated()): what the ranks that share a node must
// agree on is said to the node's directory rank, which passes it on to every
// rank that holds the node (doc/architecture.md, "What a distributed mesh
// has to change").
#pragma once

#include <mpi.h>

#include <utility>
#include <vector>

#include "DDC_Mesh.hpp"

namespace ddc {

/// The ranks that hold each node of the parts of one mesh. Each node id has
/// a directory rank (the ids split evenly over the ranks), which keeps the
/// ranks that hold the node. Works on a whole mesh too (every rank then
/// holds every node), at the cost of sending every node.
class NodeDirectory {
 public:
  /// Something one rank says of a node: an int value.
  struct Note {
    Mesh::GlobalId node;
    int value;
  };

  /// Collective on `comm`; `mesh` is this rank's part and must outlive the
  /// directory.
  NodeDirectory(MPI_Comm comm, const Mesh& mesh);

  /// Per node of this rank's part, the lowest rank that holds it.
  const std::vector<int>& lowestHolder() const { return lowest_; }

  /// Sends every note to every rank that holds its node (its sender
  /// included). \returns what this rank receives, as (local node, value),
  /// ordered by node id and then by value, duplicates kept. Collective.
  std::vector<std::pair<int, int>> toHolders(const std::vector<Note>& notes) const;

  /// Per node, the union over the ranks that hold it of their `values[n]`
  /// (sorted, without duplicates). Collective.
  std::vector<std::vector<int>> unite(const std::vector<std::vector<int>>& values) const;

  /// Per node, 1 if any rank that holds it has flags[n] set. Collective.
  std::vector<char> anyHolder(const std::vector<char>& flags) const;

 private:
  int directoryRank(Mesh::GlobalId id) const;

  MPI_Comm comm_;
  const Mesh* mesh_;
  int ranks_ = 1;
  /// This rank's share of the directory: (node id, holder), sorted.
  std::vector<std::pair<Mesh::GlobalId, int>> holders_;
  std::vector<int> lowest_;
};

}  // namespace ddc
