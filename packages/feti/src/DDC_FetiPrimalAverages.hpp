// Edge and face averages as FETI-DP primal constraints (doc/feti-dp.md,
// "Primal constraints: vertices, edges, faces"; Klawonn & Widlund 2006,
// Comm. Pure Appl. Math. 59; Farhat, Lesoinne & Pierson 2000 for the
// averages in 3-D).
//
// Two pieces, both mesh-free:
//  - findPrimalAverages(): classify the interface DOFs by the set of
//    subdomains sharing them (as PETSc's PCBDDC graph and FROSch's
//    DDInterface do) and return, per subdomain, the groups of DOFs whose
//    average becomes a primal unknown: in 2-D every set of two subdomains is
//    an edge; in 3-D a set of two is a face and a set of three or more an
//    edge. Averages are per displacement component. Caller-chosen primal
//    (vertex) DOFs are left out of every group.
//  - ChangeOfBasis: the local change of basis u = T û of one subdomain that
//    makes each group's average an explicit DOF (at the group's first DOF),
//    so that FetiDpSolver can treat it as an ordinary primal DOF.
#pragma once

#include <mpi.h>

#include <string>
#include <vector>

#include "DDC_DirectSolver.hpp"

namespace ddc {

/// Which primal constraints FETI-DP uses ("Primal Constraints").
enum class PrimalConstraints { Vertices, VerticesAndEdges, VerticesEdgesAndFaces };

/// The parameter values, in the order of the enumeration.
const std::vector<std::string>& primalConstraintNames();
/// \throws std::invalid_argument for a name not in primalConstraintNames().
PrimalConstraints primalConstraintsFromName(const std::string& name);

/// One subdomain as findPrimalAverages() needs it (the fields of
/// FetiSubdomain of the same name).
struct AverageInput {
  int id = -1;                  ///< global subdomain id
  std::vector<GO> dofs;         ///< global ids of the subdomain's free DOFs
  std::vector<char> primal;     ///< per local DOF: already primal (a vertex)
  std::vector<int> component;   ///< per local DOF: displacement component 0..dim-1
};

/// Groups of local DOFs (per subdomain of `subs`, in the same order) whose
/// averages are primal constraints under `choice`. Each group lists local
/// DOF indices sorted by global id; the groups of a subdomain are sorted by
/// their first global id. Every subdomain sharing a group's DOFs gets the
/// same group (same global ids in the same order). Collective over `comm`
/// (exchanges with the owners of the DOFs in `ownedMap`).
/// \param dim spatial dimension, 2 or 3.
/// \throws std::invalid_argument (on every rank) for dim not 2 or 3 or a
///         component outside 0..dim-1.
std::vector<std::vector<std::vector<LO>>> findPrimalAverages(MPI_Comm comm, const Map& ownedMap,
                                                             const std::vector<AverageInput>& subs, int dim,
                                                             PrimalConstraints choice);

/// The change of basis u = T û of one subdomain for its average groups
/// (Klawonn & Widlund 2006, sec. 4): in a group G = (g_1, ..., g_m) the new
/// DOF at g_1 is the average, û_{g_1} = (1/m) sum_i u_{g_i}, and the others
/// are the deviations from it, û_{g_i} = u_{g_i} - û_{g_1} (i >= 2):
///
///     u_{g_1} = û_{g_1} - sum_{i>=2} û_{g_i},   u_{g_i} = û_{g_1} + û_{g_i}.
///
/// T is the same in every subdomain sharing G (same groups), so continuity
/// of u is continuity of û, and û_{g_1} can be assembled like a vertex DOF.
/// K̂ = T^T K T gains a dense m x m block per group (the cost of this choice,
/// doc/feti-dp.md).
class ChangeOfBasis {
 public:
  ChangeOfBasis() = default;
  /// \param n number of local DOFs; \param groups as from findPrimalAverages().
  ChangeOfBasis(LO n, std::vector<std::vector<LO>> groups);

  /// True if there is at least one group (otherwise T = I).
  bool active() const { return !groups_.empty(); }
  const std::vector<std::vector<LO>>& groups() const { return groups_; }
  /// Per local DOF: true if it holds a group average after the change.
  bool isAverage(LO dof) const { return !head_.empty() && head_[dof] == dof; }

  /// Build the pattern of K̂ = T^T K T from K's pattern (n x n, MPI_COMM_SELF,
  /// as FetiSubdomain::K) and fill its values. Returns K̂ (fill-complete).
  Teuchos::RCP<CrsMatrix> setPattern(const CrsMatrix& K);
  /// Recompute the values of the K̂ returned by setPattern() from K's
  /// current values (same pattern).
  void update(const CrsMatrix& K);

  /// f̂ = T^T f (loads, in place; f has one value per local DOF).
  void forceToNew(std::vector<double>& f) const;
  /// u = T û (displacements, in place).
  void displacementToOld(std::vector<double>& u) const;
  /// û = T^{-1} u (displacements, in place).
  void displacementToNew(std::vector<double>& u) const;
  /// A constraint row c^T u = c^T T û: the coefficients (local DOF, value)
  /// of c^T T, merged, zeros dropped.
  std::vector<std::pair<LO, double>> rowToNew(const std::vector<std::pair<LO, double>>& row) const;

 private:
  /// Row i of T as (column, coefficient) pairs.
  void tRow(LO i, std::vector<std::pair<LO, double>>& out) const;

  LO n_ = 0;
  std::vector<std::vector<LO>> groups_;
  std::vector<LO> head_;   // per local DOF: first DOF of its group, or -1
  std::vector<LO> group_;  // per local DOF: its group index, or -1
  // K̂ = sum over plan entries: khat[dst] += coef * k[src] (flat indices in
  // the row-view order of K and K̂).
  struct PlanEntry {
    size_t src, dst;
    double coef;
  };
  std::vector<PlanEntry> plan_;
  std::vector<size_t> kOffsets_, hatOffsets_;
  std::vector<std::vector<LO>> hatCols_;
  Teuchos::RCP<CrsMatrix> hat_;
};

}  // namespace ddc
