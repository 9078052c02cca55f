// Edge and face constraints as FETI-DP primal unknowns (doc/feti-dp.md,
// "Primal constraints: vertices, edges, faces"; Klawonn & Widlund 2006,
// Comm. Pure Appl. Math. 59, for the change of basis; Farhat, Lesoinne &
// Pierson 2000 for averages in 3-D).
//
// Two pieces, both mesh-free:
//  - findEdgeFaceConstraints(): classify the interface DOFs by the set of
//    subdomains sharing them (as PETSc's PCBDDC graph and FROSch's
//    DDInterface do): in 2-D every set of two subdomains is an edge; in 3-D
//    a set of two is a face and a set of three or more an edge. Each edge /
//    face gets its primal constraints: the average of each displacement
//    component and, with coordinates, its rigid rotations (the rigid-body
//    modes restricted to it, orthogonalised against the translations;
//    rotations that vanish on it, e.g. about a straight edge's axis, are
//    dropped). Caller-chosen primal (vertex) DOFs are left out.
//  - ChangeOfBasis: the local change of basis u = T û of one subdomain that
//    makes each constraint value an explicit DOF, so that FetiDpSolver can
//    treat it as an ordinary primal DOF.
#pragma once

#include <mpi.h>

#include <string>
#include <utility>
#include <vector>

#include "DDC_DirectSolver.hpp"

namespace ddc {

/// Which primal constraints FETI-DP uses ("Primal Constraints").
enum class PrimalConstraints { Vertices, VerticesAndEdges, VerticesEdgesAndFaces };

/// The parameter values, in the order of the enumeration.
const std::vector<std::string>& primalConstraintNames();
/// \throws std::invalid_argument for a name not in primalConstraintNames().
PrimalConstraints primalConstraintsFromName(const std::string& name);

/// One subdomain as findEdgeFaceConstraints() needs it (the fields of
/// FetiSubdomain of the same name).
struct EdgeFaceInput {
  int id = -1;                      ///< global subdomain id
  std::vector<GO> dofs;             ///< global ids of the subdomain's free DOFs
  std::vector<char> primal;         ///< per local DOF: already primal (a vertex)
  std::vector<int> component;       ///< per local DOF: displacement component 0..dim-1
  std::vector<double> coordinates;  ///< dim values per local DOF (its node), or empty: no rotations
};

/// One edge or face of a subdomain and its constraints.
struct PrimalGroup {
  /// Local DOF indices, sorted by global id (the same DOFs, in the same
  /// order, in every subdomain sharing them).
  std::vector<LO> dofs;
  /// Constraint rows c_j (one value per entry of `dofs`): c_j^T u is
  /// continuous across the subdomains. Translations first.
  std::vector<std::vector<double>> rows;
};

/// Per subdomain of `subs`, per local DOF: the ids of the subdomains sharing
/// it, ascending (its interface set), for every non-primal DOF shared by two
/// or more subdomains; empty otherwise. Collective over `comm` (each DOF's
/// owner in `ownedMap` learns who has it and tells them).
/// \throws std::invalid_argument (on every rank) for a DOF not in `ownedMap`.
std::vector<std::vector<std::vector<int>>> dofSharingSets(MPI_Comm comm, const Map& ownedMap,
                                                          const std::vector<EdgeFaceInput>& subs);

/// The edges / faces (per subdomain of `subs`, in the same order) whose
/// constraints are primal under `choice`, sorted by their first global id.
/// Every subdomain sharing a group's DOFs gets the same group and the same
/// rows (computed from the same data in the same order). Collective over
/// `comm` (exchanges with the owners of the DOFs in `ownedMap`).
/// \param dim spatial dimension, 2 or 3.
/// \param rotations add the rotations (needs coordinates).
/// \throws std::invalid_argument (on every rank) for dim not 2 or 3, a
///         component outside 0..dim-1, sizes that do not match, or
///         rotations without coordinates.
std::vector<std::vector<PrimalGroup>> findEdgeFaceConstraints(MPI_Comm comm, const Map& ownedMap,
                                                              const std::vector<EdgeFaceInput>& subs, int dim,
                                                              PrimalConstraints choice, bool rotations);

/// The change of basis u = T û of one subdomain (Klawonn & Widlund 2006,
/// sec. 4, in the form of Li & Widlund 2006): in a group G with constraint
/// rows C (k x |G|), k "representative" DOFs R of G (chosen by pivoting on
/// C) take the constraint values and the others O keep their values,
///
///     û_R = C u_G,  û_O = u_O    <=>    u_R = C_R^{-1} (û_R - C_O û_O).
///
/// T is the same in every subdomain sharing G (same groups, same rows), so
/// continuity of u is continuity of û, and û_R can be assembled like vertex
/// DOFs. K̂ = T^T K T gains a dense |G| x |G| block per group (the cost of
/// this choice, doc/feti-dp.md).
class ChangeOfBasis {
 public:
  ChangeOfBasis() = default;
  /// \param n number of local DOFs; \param groups as from findEdgeFaceConstraints().
  /// \throws std::invalid_argument for DOFs out of range or in two groups,
  ///         or rows that are linearly dependent.
  /// \param avoid optional, per local DOF: 1 = do not make it a
  ///        representative unless the group leaves no other choice (the
  ///        DOFs that extra constraint rows touch: a row on an O DOF stays
  ///        as it is in the new basis, a row on an R DOF spreads over the
  ///        whole group). Must be the same in every subdomain sharing a group.
  ChangeOfBasis(LO n, const std::vector<PrimalGroup>& groups, const std::vector<char>& avoid = {});

  /// True if there is at least one group (otherwise T = I).
  bool active() const { return !groups_.empty(); }
  /// Per local DOF: true if it holds a constraint value (a DOF of some R).
  bool holdsConstraint(LO dof) const { return !rep_.empty() && rep_[dof] >= 0; }
  /// Number of constraint values (sum of k over the groups).
  LO numConstraints() const;

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
  /// A constraint row c^T u = (T^T c)^T û: the coefficients (local DOF,
  /// value) of T^T c, merged, zeros dropped.
  std::vector<std::pair<LO, double>> rowToNew(const std::vector<std::pair<LO, double>>& row) const;

 private:
  struct Group {
    std::vector<LO> R, O;                // representative / other local DOFs
    std::vector<double> C;               // k x |G| rows (R columns then O columns), row-major
    std::vector<double> Minv;            // C_R^{-1}, k x k, row-major
    std::vector<double> W;               // C_R^{-1} C_O, k x |O|, row-major
    size_t k() const { return R.size(); }
  };
  /// Row i / column a of T as (index, coefficient) pairs.
  void tRow(LO i, std::vector<std::pair<LO, double>>& out) const;
  void tCol(LO a, std::vector<std::pair<LO, double>>& out) const;
  /// K̂ = T^T K T: the pattern (values = false, into hatCols_, which
  /// setPattern() frees once the graph holds it) or the values (into hat_).
  void multiply(const CrsMatrix& K, bool values);

  LO n_ = 0;
  std::vector<Group> groups_;
  std::vector<LO> group_;  // per local DOF: its group index, or -1
  std::vector<LO> rep_;    // per local DOF: its index in its group's R, or -1
  std::vector<LO> other_;  // per local DOF: its index in its group's O, or -1
  size_t kNnz_ = 0;        // entries of K at setPattern()
  std::vector<std::vector<LO>> hatCols_;
  Teuchos::RCP<CrsMatrix> hat_;
};

}  // namespace ddc
