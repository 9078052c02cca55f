// Who owns a list of global ids in a Tpetra map (FetiDpSolver, the edge/face
// classification).
#pragma once

#include <algorithm>
#include <vector>

#include "DDC_DirectSolver.hpp"

namespace ddc {

/// Owning rank and LID of each of `gids` in `map` (-1 if absent).
/// Collective. The query is made with unique GIDs: Tpetra 13.2's
/// distributed directory answers -1 for repeated GIDs in one query
/// (doc/trilinos-notes.md), and a rank with several subdomains asks for the
/// same interface DOF more than once.
inline void owners(const Map& map, const std::vector<GO>& gids, std::vector<int>& pids, std::vector<LO>& lids) {
  std::vector<GO> unique(gids);
  std::sort(unique.begin(), unique.end());
  unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
  std::vector<int> up(unique.size());
  std::vector<LO> ul(unique.size());
  map.getRemoteIndexList(Teuchos::ArrayView<const GO>(unique.data(), unique.size()),
                         Teuchos::ArrayView<int>(up.data(), up.size()), Teuchos::ArrayView<LO>(ul.data(), ul.size()));
  pids.resize(gids.size());
  lids.resize(gids.size());
  for (size_t k = 0; k < gids.size(); ++k) {
    const size_t u = size_t(std::lower_bound(unique.begin(), unique.end(), gids[k]) - unique.begin());
    pids[k] = up[u];
    lids[k] = ul[u];
  }
}

}  // namespace ddc
