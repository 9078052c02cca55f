// Which rigid-body motions of the bodies nothing restrains: the cause of a
// singular tangent that a direct solver factorises without complaint
// (doc/user-guide.md, "A singular problem").
//
// A body's rigid motions (translations and rotations, taken about its
// centroid in the current configuration) leave its strain energy unchanged,
// so only prescribed displacements and active contact constraints can hold
// them. With R the rigid-motion columns of every body (each scaled so that
// its largest nodal amplitude is about 1) the restraint of a combination c of
// them is
//
//     c^T G c,   G = sum over prescribed DOFs g of  R_g^T R_g
//                  + sum over contact rows k of  (C_k R)^T (C_k R) / |C_k|^2,
//
// the squared prescribed motion plus the squared normalised gap change it
// causes. A combination with c^T G c below kRestraintTolerance times the
// largest eigenvalue of G is free: the global tangent (saddle-point matrix
// with the contact rows) is singular along it. The contact rows are those of
// the assembled contact contributions, whichever element and strategy, so
// the check sees what the solver would see; a released or unpaired slot's
// row has no displacement entries and restrains nothing.
//
// The contact rows of the decomposed element arrive as a slave part and a
// master part, possibly on two ranks: their products with R are summed over
// the ranks (one reduction of (modes + 1) values per slot) before they are
// squared.
#pragma once

#include <Eigen/Dense>
#include <Teuchos_Comm.hpp>
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "DDC_Mesh.hpp"

namespace ddc {

class RigidMotionCheck {
 public:
  /// A restraint weaker than this fraction of the strongest counts as none:
  /// the numerical rank tolerance of G (the singular directions of a
  /// stiffness matrix are resolved to about 1e-16 relative; a restraint at
  /// 1e-10 already makes the solution of the Newton system meaningless).
  static constexpr double kRestraintTolerance = 1e-10;

  /// \param numSlots contact constraint rows of the model (one per multiplier
  ///        slot), 0 without contact
  /// \param comm, counted for a part of a mesh (Mesh::isPart()): the
  ///        ranks that hold the other parts, and which nodes of this part
  ///        this rank counts (each node of the whole mesh on one rank), so
  ///        that every rank takes the whole bodies' centroids and sizes;
  ///        unused for a whole mesh
  RigidMotionCheck(const Mesh& mesh, int numSlots, const Teuchos::Comm<int>* comm = nullptr,
                   const std::function<bool(int)>& counted = {});

  /// Forget the restraints (call before an assembly).
  void reset();
  /// Number of rigid-motion columns: 3 (2-D) or 6 (3-D) per body.
  int numModes() const { return modesPerBody_ * numBodies_; }
  /// A prescribed DOF: component c of node n, the node at position x.
  void addPrescribed(int n, int c, const std::array<double, 3>& x);
  /// One coefficient of contact row `slot` (this rank's part of it):
  /// component c of node n at position x.
  void addRowEntry(int slot, int n, int c, const std::array<double, 3>& x, double coefficient);
  /// addRowEntry() for a node named by its body: a contact surface node
  /// that this rank's part of a mesh does not hold.
  void addBodyRowEntry(int slot, int body, int c, const std::array<double, 3>& x, double coefficient);
  /// Collective: the free rigid motions, described for a message ("body
  /// 'Upper': translation along x; ..."), or "" if every motion is
  /// restrained. Equal on every rank.
  std::string freeMotions(const Teuchos::Comm<int>& comm) const;

  /// Collective: a basis of the free combinations (columns, numModes() rows,
  /// reduced row echelon form of their transpose); for tests.
  Eigen::MatrixXd freeBasis(const Teuchos::Comm<int>& comm) const;

 private:
  /// The rigid-motion values at component c of a node of body `body` at
  /// position x: the body, and its modesPerBody_ columns in `values`.
  int modeValues(int body, int c, const std::array<double, 3>& x, double* values) const;

  int dim_ = 2;
  int modesPerBody_ = 3;
  int numBodies_ = 0;
  int numSlots_ = 0;
  std::vector<std::string> bodyNames_;
  std::vector<int> nodeBody_;
  std::vector<Eigen::Vector3d> centre_;
  std::vector<double> radius_;
  Eigen::MatrixXd prescribed_;  ///< this rank's share of the prescribed part of G
  std::vector<double> rows_;    ///< per slot: C_k R (numModes()), then |C_k|^2 (this rank's part)
};

}  // namespace ddc
