// The distribution line a run prints before its first step: how much of the
// model the busiest rank assembles, owns and holds, and its estimated memory
// (doc/user-guide.md, "The distribution line"). Each figure is the maximum
// over the ranks, so one line on rank 0 says whether the work is balanced
// and what every rank still holds whole.
#pragma once

#include <Teuchos_Comm.hpp>
#include <string>

#include "DDC_MeshInRanges.hpp"

namespace ddc {

class Model;

/// This rank's share of a model.
struct RankShare {
  long long elements = 0;    ///< elements it assembles (those of its subdomains)
  long long nodes = 0;       ///< nodes whose DOFs it owns
  long long slots = 0;       ///< contact slots it owns
  long long coarseRows = 0;  ///< rows of the FETI-DP coarse problem it owns (0: none)
  /// Elements and nodes of the mesh it holds: the whole mesh, or with a
  /// part of it (Mesh::part()) its elements and their nodes.
  long long heldElements = 0, heldNodes = 0;
};

/// This rank's share of `model`, with `coarseRows` from the solution strategy.
RankShare rankShare(const Model& model, long long coarseRows);

/// "distribution: the busiest rank assembles 205 of 544 elements (37.7 %),
/// owns 350 of 804 nodes (43.5 %), 78 of 217 contact slots (35.9 %), 131 of
/// 200 coarse rows (65.5 %); every rank holds the whole mesh (544 elements,
/// 804 nodes) and all 217 contact slots; estimated 13 MiB per rank" (the
/// contact and coarse parts only when there are contact slots or a coarse
/// problem; each count the largest over the ranks, perhaps of different
/// ranks). On a part of a mesh (Partition/Mesh On Every Rank = false) the
/// held part says "the busiest rank holds 205 of 544 elements (37.7 %) and
/// 402 of 804 nodes (50.0 %) of the mesh (its elements' nodes, those shared
/// with other ranks included)", and then how the parts were made (`origin`):
/// "; no rank held the whole mesh (built in ranges of elements)", "; only
/// rank 0 held the whole mesh (and sent each rank a range of its
/// elements)", or "; each rank built the whole mesh and kept its part".
/// Collective.
std::string distributionLine(const Teuchos::Comm<int>& comm, const Model& model, const RankShare& mine,
                             double estimatedBytesPerRank, MeshOrigin origin = MeshOrigin::EveryRank);

}  // namespace ddc
