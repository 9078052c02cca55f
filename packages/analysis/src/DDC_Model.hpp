// The discrete model: replicated mesh, element evaluators per body, element
// partition, distributed DOF numbering, boundary conditions and assembly of
// the global residual and tangent (a distributed Tpetra::CrsMatrix).
#pragma once

#include <Teuchos_Comm.hpp>
#include <memory>
#include <vector>

#include "DDC_BoundaryConditions.hpp"
#include "DDC_DirectSolver.hpp"
#include "DDC_Element.hpp"
#include "DDC_Mesh.hpp"
#include "DDC_Partition.hpp"

namespace ddc {

/// Results of one assembly.
struct AssemblyResult {
  double strainEnergy = 0.0;  ///< Σ U_e over all elements (global)
};

/// The discrete model shared by every strategy. Each rank holds the whole
/// mesh (it fits one node up to millions of DOFs) and evaluates the elements
/// of the subdomains it owns. Nodes are owned by the lowest rank among the
/// elements that touch them; each rank's owned DOFs form a contiguous range,
/// so the owned DOF map is contiguous (what MUMPS needs).
class Model {
 public:
  /// \param elements one evaluator per body (index = body index)
  Model(Teuchos::RCP<const Teuchos::Comm<int>> comm, std::shared_ptr<const Mesh> mesh,
        std::vector<std::shared_ptr<const Element>> elements, Partition partition, BoundaryConditions bcs);

  const Mesh& mesh() const { return *mesh_; }
  const Partition& partition() const { return partition_; }
  const Teuchos::RCP<const Teuchos::Comm<int>>& comm() const { return comm_; }
  /// Rank owning subdomain s.
  int subdomainRank(int s) const { return subdomainRank_[s]; }
  /// Elements evaluated on this rank (those of its subdomains).
  const std::vector<int>& localElements() const { return localElements_; }

  /// Owned DOFs (contiguous) and owned + ghost DOFs of the local elements.
  Teuchos::RCP<const Map> ownedMap() const { return ownedMap_; }
  Teuchos::RCP<const Map> overlapMap() const { return overlapMap_; }
  /// Global DOF id of component c of mesh node n.
  GO dof(int n, int c) const { return 2 * static_cast<GO>(nodeNumber_[n]) + c; }
  /// True if global DOF g (numbered as dof()) is prescribed.
  bool isConstrained(GO g) const { return constrained_[g] != 0; }

  /// New owned vectors / matrix with the model's layout.
  Teuchos::RCP<Vector> createVector() const;
  Teuchos::RCP<CrsMatrix> createMatrix() const;

  /// Set the prescribed DOFs of u (owned layout) to their values at λ.
  void applyPrescribed(double lambda, Vector& u) const;
  /// Prescribed values at λ minus those at λ0, zero elsewhere (owned layout).
  void prescribedIncrement(double lambda0, double lambda, Vector& du) const;

  /// Assemble at displacement u (owned layout):
  ///  - fint: internal force (all DOFs, unmodified: reactions live there);
  ///  - residual r = fint − λ f_ext on free DOFs, 0 on prescribed DOFs, and
  ///    if `prescribedStep` is given also + K·prescribedStep (the consistent
  ///    predictor for a displacement increment imposed in the first iteration);
  ///  - K: tangent with rows and columns of prescribed DOFs replaced by the
  ///    identity (symmetric). Pass nullptr for what is not needed.
  /// \throws InadmissibleDeformation on every rank if det F <= 0 anywhere.
  AssemblyResult assemble(const Vector& u, double lambda, Vector* fint, Vector* residual, CrsMatrix* K,
                          const Vector* prescribedStep = nullptr) const;

  /// The element evaluator of element e.
  const Element& elementOf(int e) const { return *elements_[mesh_->elementBody(e)]; }

  /// λ-independent external force f_ext (tractions at load factor 1).
  const Vector& externalForce() const { return *fext_; }

  /// Import an owned vector to the overlap layout (values of all DOFs of
  /// the local elements).
  Teuchos::RCP<Vector> toOverlap(const Vector& owned) const;

 private:
  void buildDofNumbering();
  void buildConstraints();
  void buildGraph();
  void assembleTractions();

  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  std::shared_ptr<const Mesh> mesh_;
  std::vector<std::shared_ptr<const Element>> elements_;
  Partition partition_;
  BoundaryConditions bcs_;

  std::vector<int> subdomainRank_;
  std::vector<int> localElements_;
  std::vector<int> nodeNumber_;  ///< mesh node -> position in the global (rank-contiguous) numbering
  std::vector<char> constrained_;               ///< per global DOF
  std::vector<std::pair<int, int>> constraintSource_;  ///< per global DOF: (condition, node) or (-1,-1)
  Teuchos::RCP<const Map> ownedMap_, overlapMap_;
  Teuchos::RCP<const CrsGraph> ownedGraph_, overlapGraph_;
  Teuchos::RCP<const Tpetra::Export<LO, GO, Node>> exporter_;
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> importer_;
  Teuchos::RCP<Vector> fext_;
};

}  // namespace ddc
