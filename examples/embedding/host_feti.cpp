// Depth (b) of doc/embedding.md, the minimal program: a host with its own
// mesh, element routine and assembly uses ddc::FetiDpSolver alone for one
// linear system K u = f (no ddc::Analysis, no contact, no Newton; for those
// see host_contact_feti.cpp).
//
// The problem: a linear-elastic strip [0, 4] x [0, 1] in plane strain,
// 8 x 3 Quad4 (2 x 2 Gauss, the host's own stiffness routine), clamped on its
// left edge and loaded by a downward traction on its right edge. The host
// numbers the free DOFs (the clamped ones are eliminated), cuts the strip at
// x = 2 into two subdomains, assembles each subdomain's stiffness on
// MPI_COMM_SELF with the local numbering 0..n-1 of its DOF list, lets
// findPrimalVertices() choose the primal vertices (none here: the cut is one
// edge, whose averages and rotation are primal by default, doc/feti-dp.md)
// and solves with FetiDpSolver. Subdomain s lives on rank s % P; rank 0 owns
// the DOFs of the nodes with x <= 2, rank 1 the others.
//
// It checks the FETI-DP displacements against a dense direct solve (Eigen
// LDLT) of the globally assembled system: max |u_FETI - u_direct| must not
// exceed kAgreement max |u_direct|. Run on 1 or 2 ranks:
// mpirun -np 2 host_feti
#include <DDC_FetiDpSolver.hpp>
#include <DDC_FetiPrimalVertices.hpp>
#include <DDC_TpetraTypes.hpp>
#include <Eigen/Dense>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Tpetra_Core.hpp>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <vector>

namespace {

using ddc::GO;
using ddc::LO;

constexpr int kNx = 8, kNy = 3;          ///< elements along x and y
constexpr double kLx = 4.0, kLy = 1.0;   ///< strip length and height
constexpr int kCut = kNx / 2;            ///< the node column of the cut between the subdomains
constexpr double kE = 1000.0, kNu = 0.3;
constexpr double kTraction = -1.0;       ///< y traction on the right edge, per unit length
/// Relative Belos tolerance of the dual problem F lambda = d.
constexpr double kDualTolerance = 1e-12;
/// Agreement with the direct solve, relative to max |u|: the dual residual
/// kDualTolerance plus round-off.
constexpr double kAgreement = 1e-10;

constexpr int kNumFreeDofs = 2 * kNx * (kNy + 1);  ///< the left node column is clamped

/// Node (i, j), i = 0..kNx along x, j = 0..kNy along y.
Eigen::Vector2d coordinates(int i, int j) { return {i * kLx / kNx, j * kLy / kNy}; }
/// Global id of component c of node (i, j) among the free DOFs; -1 = clamped.
GO freeDof(int i, int j, int c) { return i == 0 ? -1 : 2 * ((i - 1) * (kNy + 1) + j) + c; }

/// Element (ex, ey): its nodes (i, j), counter-clockwise.
std::array<std::array<int, 2>, 4> elementNodes(int ex, int ey) {
  return {{{ex, ey}, {ex + 1, ey}, {ex + 1, ey + 1}, {ex, ey + 1}}};
}

/// The host's element routine: plane-strain small-strain Quad4 stiffness,
/// 2 x 2 Gauss, DOFs node-major (u0x, u0y, u1x, ...).
Eigen::Matrix<double, 8, 8> quad4Stiffness(int ex, int ey) {
  const double lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), mu = kE / (2 * (1 + kNu));
  Eigen::Matrix3d D;
  D << lambda + 2 * mu, lambda, 0, lambda, lambda + 2 * mu, 0, 0, 0, mu;
  Eigen::Matrix<double, 4, 2> X;
  const auto nodes = elementNodes(ex, ey);
  for (int k = 0; k < 4; ++k) X.row(k) = coordinates(nodes[k][0], nodes[k][1]).transpose();
  const double xiNode[4] = {-1, 1, 1, -1}, etaNode[4] = {-1, -1, 1, 1}, g = 1 / std::sqrt(3.0);
  Eigen::Matrix<double, 8, 8> K = Eigen::Matrix<double, 8, 8>::Zero();
  for (int q = 0; q < 4; ++q) {
    const double xi = g * xiNode[q], eta = g * etaNode[q];
    Eigen::Matrix<double, 2, 4> dN;  // reference gradients of the shape functions
    for (int k = 0; k < 4; ++k) {
      dN(0, k) = 0.25 * xiNode[k] * (1 + etaNode[k] * eta);
      dN(1, k) = 0.25 * etaNode[k] * (1 + xiNode[k] * xi);
    }
    const Eigen::Matrix2d J = dN * X;
    const Eigen::Matrix<double, 2, 4> dNdx = J.inverse() * dN;
    Eigen::Matrix<double, 3, 8> B = Eigen::Matrix<double, 3, 8>::Zero();
    for (int k = 0; k < 4; ++k) {
      B(0, 2 * k) = dNdx(0, k);
      B(1, 2 * k + 1) = dNdx(1, k);
      B(2, 2 * k) = dNdx(1, k);
      B(2, 2 * k + 1) = dNdx(0, k);
    }
    K += B.transpose() * D * B * J.determinant();  // Gauss weights 1
  }
  return K;
}

/// The load vector over the free DOFs: the right-edge traction as
/// consistent nodal forces (half an edge length per edge end).
Eigen::VectorXd loadVector() {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(kNumFreeDofs);
  const double h = kLy / kNy;
  for (int j = 0; j < kNy; ++j) {
    f(freeDof(kNx, j, 1)) += 0.5 * kTraction * h;
    f(freeDof(kNx, j + 1, 1)) += 0.5 * kTraction * h;
  }
  return f;
}

/// Subdomain s: element columns [0, kCut) or [kCut, kNx), node columns
/// 0..kCut or kCut..kNx.
int firstColumn(int s) { return s == 0 ? 0 : kCut; }
int lastColumn(int s) { return s == 0 ? kCut : kNx; }

/// What FetiDpSolver needs of subdomain s: its free DOFs (local index =
/// position in `dofs`), component and coordinates of each, and its
/// stiffness on MPI_COMM_SELF over the local numbering, fill-complete.
ddc::FetiSubdomain makeSubdomain(int s, const Teuchos::RCP<const Teuchos::Comm<int>>& self) {
  ddc::FetiSubdomain sd;
  sd.id = s;
  sd.dim = 2;
  std::map<GO, LO> local;  // global free DOF -> local index
  for (int i = firstColumn(s); i <= lastColumn(s); ++i)
    for (int j = 0; j <= kNy; ++j)
      for (int c = 0; c < 2; ++c) {
        const GO g = freeDof(i, j, c);
        if (g < 0) continue;
        local[g] = LO(sd.dofs.size());
        sd.dofs.push_back(g);
        sd.component.push_back(c);
        const Eigen::Vector2d x = coordinates(i, j);
        sd.coordinates.insert(sd.coordinates.end(), {x(0), x(1)});
      }
  auto localMap = Teuchos::rcp(new ddc::Map(sd.dofs.size(), 0, self));  // 0..n-1, contiguous
  sd.K = Teuchos::rcp(new ddc::CrsMatrix(localMap, 18));                  // 9 nodes x 2 DOFs per row
  for (int ex = firstColumn(s); ex < lastColumn(s); ++ex)
    for (int ey = 0; ey < kNy; ++ey) {
      const auto nodes = elementNodes(ex, ey);
      const auto Ke = quad4Stiffness(ex, ey);
      std::vector<int> a;   // element DOFs that are free
      std::vector<GO> row;  // their local indices
      for (int k = 0; k < 8; ++k) {
        const GO g = freeDof(nodes[k / 2][0], nodes[k / 2][1], k % 2);
        if (g >= 0) a.push_back(k), row.push_back(local.at(g));
      }
      std::vector<double> values(a.size());
      for (size_t r = 0; r < a.size(); ++r) {
        for (size_t c = 0; c < a.size(); ++c) values[c] = Ke(a[r], a[c]);
        // Repeated (row, column) pairs are summed.
        sd.K->insertGlobalValues(row[r], Teuchos::ArrayView<const GO>(row), Teuchos::ArrayView<const double>(values));
      }
    }
  sd.K->fillComplete();  // row, domain and range map: localMap
  return sd;
}

/// The reference: the whole free-DOF system assembled densely and solved
/// directly (on every rank).
Eigen::VectorXd directSolution() {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(kNumFreeDofs, kNumFreeDofs);
  for (int ex = 0; ex < kNx; ++ex)
    for (int ey = 0; ey < kNy; ++ey) {
      const auto nodes = elementNodes(ex, ey);
      const auto Ke = quad4Stiffness(ex, ey);
      for (int a = 0; a < 8; ++a)
        for (int b = 0; b < 8; ++b) {
          const GO ga = freeDof(nodes[a / 2][0], nodes[a / 2][1], a % 2);
          const GO gb = freeDof(nodes[b / 2][0], nodes[b / 2][1], b % 2);
          if (ga >= 0 && gb >= 0) K(ga, gb) += Ke(a, b);
        }
    }
  return K.ldlt().solve(loadVector());
}

/// The FETI-DP parameters: the Solver/FETI-DP sublist of doc/parameters.md,
/// validated by the solver; what is not set takes its default.
Teuchos::ParameterList fetiParameters() {
  Teuchos::ParameterList p("FETI-DP");
  p.sublist("Belos").set("Convergence Tolerance", kDualTolerance);
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const int me = comm->getRank(), P = comm->getSize();
  int failures = 0;
  try {
    // findPrimalVertices() takes the raw MPI communicator; the subdomain
    // matrices live on MPI_COMM_SELF.
    const MPI_Comm raw = *Teuchos::rcp_dynamic_cast<const Teuchos::MpiComm<int>>(comm, true)->getRawMpiComm();
    const Teuchos::RCP<const Teuchos::Comm<int>> self = Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF));

    // The owned DOF map (the layout of f and u): rank 0 the node columns
    // 1..kCut, rank min(1, P - 1) the rest.
    std::vector<GO> owned;
    for (int i = 1; i <= kNx; ++i)
      if ((i <= kCut ? 0 : std::min(1, P - 1)) == me)
        for (int j = 0; j <= kNy; ++j)
          for (int c = 0; c < 2; ++c) owned.push_back(freeDof(i, j, c));
    auto ownedMap = Teuchos::rcp(new ddc::Map(kNumFreeDofs, Teuchos::ArrayView<const GO>(owned), 0, comm));

    std::vector<ddc::FetiSubdomain> subdomains;
    for (int s = 0; s < 2; ++s)
      if (s % P == me) subdomains.push_back(makeSubdomain(s, self));
    const auto vertices = ddc::findPrimalVertices(raw, *ownedMap, subdomains, 2);
    int myVertexDofs = 0, vertexDofs = 0;
    for (size_t k = 0; k < subdomains.size(); ++k) {
      subdomains[k].primal = vertices[k];
      myVertexDofs += int(std::count(vertices[k].begin(), vertices[k].end(), 1));
    }
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, myVertexDofs, Teuchos::outArg(vertexDofs));

    auto params = fetiParameters();
    ddc::FetiDpSolver feti(comm, params, "host/FETI-DP");
    feti.setTopology(std::move(subdomains), ownedMap);
    feti.numeric();  // no constraint rows: setConstraintRows() / setConstraintState() are not needed
    const Eigen::VectorXd fAll = loadVector();
    ddc::Vector f(ownedMap), u(ownedMap);
    for (size_t l = 0; l < owned.size(); ++l) f.replaceLocalValue(LO(l), fAll(owned[l]));
    const ddc::FetiDpSolver::Info info = feti.solve(f, u);

    const Eigen::VectorXd uDirect = directSolution();
    const auto uFeti = u.getData();
    double myDiff = 0, myMax = 0, diff = 0, uMax = 0;
    for (size_t l = 0; l < owned.size(); ++l) {
      myDiff = std::max(myDiff, std::abs(uFeti[l] - uDirect(owned[l])));
      myMax = std::max(myMax, std::abs(uDirect(owned[l])));
    }
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, myDiff, Teuchos::outArg(diff));
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, myMax, Teuchos::outArg(uMax));
    if (!(uMax > 0) || !(diff <= kAgreement * uMax)) {
      ++failures;
      if (me == 0)
        std::cerr << "host FETI-DP: max |u_FETI - u_direct| = " << diff << " exceeds " << kAgreement << " * " << uMax
                  << "\n";
    }
    if (me == 0)
      std::printf("host FETI-DP: %d free DOFs, 2 subdomains on %d ranks, %d vertex DOFs, %lld dual DOFs, "
                  "%lld edge constraints; %d iterations, dual residual %.1e; max |u| %.6e, "
                  "max |u_FETI - u_direct| %.1e (%.1e relative, tolerance %.0e)\n",
                  kNumFreeDofs, P, vertexDofs, static_cast<long long>(feti.numDualDofs()),
                  static_cast<long long>(feti.numEdgeFaceConstraints()), info.iterations, info.relativeResidual,
                  uMax, diff, diff / uMax, kAgreement);
  } catch (const std::exception& e) {
    std::cerr << "host FETI-DP: " << e.what() << "\n";
    ++failures;
  }
  int all = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, failures, Teuchos::outArg(all));
  if (me == 0) std::cout << (all ? "host FETI-DP: FAILED" : "host FETI-DP: OK") << std::endl;
  return all ? 1 : 0;
}
