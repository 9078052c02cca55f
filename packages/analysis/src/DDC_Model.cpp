#include "DDC_Model.hpp"

#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "DDC_Error.hpp"

namespace ddc {

namespace {

/// Node -> elements adjacency of the whole mesh (CSR).
void nodeElementAdjacency(const Mesh& mesh, std::vector<int>& offset, std::vector<int>& elems) {
  offset.assign(mesh.numNodes() + 1, 0);
  for (int e = 0; e < mesh.numElements(); ++e)
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) offset[mesh.elementNodes(e)[i] + 1]++;
  std::partial_sum(offset.begin(), offset.end(), offset.begin());
  elems.resize(offset.back());
  std::vector<int> fill(offset.begin(), offset.end() - 1);
  for (int e = 0; e < mesh.numElements(); ++e)
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) elems[fill[mesh.elementNodes(e)[i]]++] = e;
}

}  // namespace

Model::Model(Teuchos::RCP<const Teuchos::Comm<int>> comm, std::shared_ptr<const Mesh> mesh,
             std::vector<std::shared_ptr<const Element>> elements, Partition partition, BoundaryConditions bcs)
    : comm_(std::move(comm)),
      mesh_(std::move(mesh)),
      elements_(std::move(elements)),
      partition_(std::move(partition)),
      bcs_(std::move(bcs)) {
  DDC_ASSERT(static_cast<int>(elements_.size()) == mesh_->numBodies(), "one element evaluator per body");
  subdomainRank_ = subdomainOwnerRank(partition_.numSubdomains, comm_->getSize());
  for (int e = 0; e < mesh_->numElements(); ++e)
    if (subdomainRank_[partition_.elementSubdomain[e]] == comm_->getRank()) localElements_.push_back(e);
  buildDofNumbering();
  buildConstraints();
  buildGraph();
  assembleTractions();
}

void Model::buildDofNumbering() {
  const Mesh& mesh = *mesh_;
  const int nranks = comm_->getSize(), me = comm_->getRank();
  std::vector<int> owner(mesh.numNodes(), nranks);
  for (int e = 0; e < mesh.numElements(); ++e) {
    const int r = subdomainRank_[partition_.elementSubdomain[e]];
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
      int& o = owner[mesh.elementNodes(e)[i]];
      o = std::min(o, r);
    }
  }
  std::vector<int> count(nranks + 1, 0);
  for (int n = 0; n < mesh.numNodes(); ++n) count[owner[n] + 1]++;
  std::partial_sum(count.begin(), count.end(), count.begin());
  nodeNumber_.assign(mesh.numNodes(), -1);
  std::vector<int> next(count.begin(), count.end() - 1);
  for (int n = 0; n < mesh.numNodes(); ++n) nodeNumber_[n] = next[owner[n]]++;

  const GO numGlobal = 2 * static_cast<GO>(mesh.numNodes());
  const size_t numOwned = 2 * static_cast<size_t>(count[me + 1] - count[me]);
  ownedMap_ = Teuchos::rcp(new Map(numGlobal, numOwned, 0, comm_));

  // Overlap: owned DOFs first, then ghosts (nodes of local elements owned elsewhere).
  std::vector<GO> gids;
  gids.reserve(numOwned);
  for (GO g = 2 * static_cast<GO>(count[me]); g < 2 * static_cast<GO>(count[me + 1]); ++g) gids.push_back(g);
  std::vector<GO> ghosts;
  for (int e : localElements_)
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
      const int n = mesh.elementNodes(e)[i];
      if (owner[n] != me) {
        ghosts.push_back(dof(n, 0));
        ghosts.push_back(dof(n, 1));
      }
    }
  std::sort(ghosts.begin(), ghosts.end());
  ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
  gids.insert(gids.end(), ghosts.begin(), ghosts.end());
  overlapMap_ = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                     Teuchos::ArrayView<const GO>(gids), 0, comm_));
  importer_ = Teuchos::rcp(new Tpetra::Import<LO, GO, Node>(ownedMap_, overlapMap_));
  exporter_ = Teuchos::rcp(new Tpetra::Export<LO, GO, Node>(overlapMap_, ownedMap_));
}

void Model::buildConstraints() {
  const Mesh& mesh = *mesh_;
  constrained_.assign(2 * mesh.numNodes(), 0);
  constraintSource_.assign(2 * mesh.numNodes(), {-1, -1});
  for (int b = 0; b < static_cast<int>(bcs_.displacements.size()); ++b) {
    const auto& bc = bcs_.displacements[b];
    for (int n : mesh.nodeSet(bc.setName))
      for (int c = 0; c < 2; ++c) {
        if (!bc.fix[c]) continue;
        const GO g = dof(n, c);
        auto& src = constraintSource_[g];
        if (src.first >= 0) {
          // Two conditions on one DOF must agree (e.g. shared corner of two fixed edges).
          const auto& other = bcs_.displacements[src.first];
          const auto& X = mesh.coord(n);
          for (double lam : {0.5, 1.0}) {
            const double a = other.prescribed(c, X, lam), v = bc.prescribed(c, X, lam);
            DDC_INPUT_REQUIRE(std::abs(a - v) <= 1e-12 * (1.0 + std::abs(a) + std::abs(v)),
                              "boundary conditions '" << other.name << "' and '" << bc.name
                                                      << "' prescribe different " << (c ? "y" : "x")
                                                      << " displacements at node " << n << " ("
                                                      << X[0] << ", " << X[1] << ")");
          }
          continue;
        }
        src = {b, n};
        constrained_[g] = 1;
      }
  }
}

void Model::buildGraph() {
  const Mesh& mesh = *mesh_;
  std::vector<int> adjOff, adjElem;
  nodeElementAdjacency(mesh, adjOff, adjElem);

  // Owned graph: rows of owned DOFs, columns from every element touching the
  // node (the whole mesh is known, so no communication is needed).
  const size_t numOwnedRows = ownedMap_->getNodeNumElements();
  std::vector<std::vector<GO>> rows(numOwnedRows / 2);
  std::vector<int> ownedNodes(numOwnedRows / 2);
  const GO first = ownedMap_->getMinGlobalIndex();
  for (int n = 0; n < mesh.numNodes(); ++n) {
    const GO g = dof(n, 0);
    if (g >= first && g < first + static_cast<GO>(numOwnedRows)) ownedNodes[(g - first) / 2] = n;
  }
  Teuchos::Array<size_t> nnz(numOwnedRows);
  for (size_t k = 0; k < ownedNodes.size(); ++k) {
    const int n = ownedNodes[k];
    auto& cols = rows[k];
    for (int a = adjOff[n]; a < adjOff[n + 1]; ++a) {
      const int e = adjElem[a];
      for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
        cols.push_back(dof(mesh.elementNodes(e)[i], 0));
        cols.push_back(dof(mesh.elementNodes(e)[i], 1));
      }
    }
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    nnz[2 * k] = nnz[2 * k + 1] = cols.size();
  }
  auto owned = Teuchos::rcp(new CrsGraph(ownedMap_, nnz()));
  for (size_t k = 0; k < rows.size(); ++k)
    for (int c = 0; c < 2; ++c) owned->insertGlobalIndices(first + 2 * k + c, Teuchos::ArrayView<const GO>(rows[k]));
  owned->fillComplete(ownedMap_, ownedMap_);
  ownedGraph_ = owned;

  // Overlap graph: rows of all DOFs of local elements, entries of local
  // elements only; columns indexed by the overlap map so element DOF lists
  // can be used directly as local column indices.
  const size_t numOv = overlapMap_->getNodeNumElements();
  std::vector<std::vector<LO>> ovRows(numOv);
  for (int e : localElements_) {
    const int nn = mesh.elementNumNodes(e);
    std::vector<LO> l(2 * nn);
    for (int i = 0; i < nn; ++i)
      for (int c = 0; c < 2; ++c) l[2 * i + c] = overlapMap_->getLocalElement(dof(mesh.elementNodes(e)[i], c));
    for (LO r : l) ovRows[r].insert(ovRows[r].end(), l.begin(), l.end());
  }
  Teuchos::Array<size_t> ovnnz(numOv);
  for (size_t r = 0; r < numOv; ++r) {
    std::sort(ovRows[r].begin(), ovRows[r].end());
    ovRows[r].erase(std::unique(ovRows[r].begin(), ovRows[r].end()), ovRows[r].end());
    ovnnz[r] = ovRows[r].size();
  }
  auto ov = Teuchos::rcp(new CrsGraph(overlapMap_, overlapMap_, ovnnz()));
  for (size_t r = 0; r < numOv; ++r) ov->insertLocalIndices(r, Teuchos::ArrayView<const LO>(ovRows[r]));
  ov->fillComplete(ownedMap_, ownedMap_);
  overlapGraph_ = ov;
}

void Model::assembleTractions() {
  const Mesh& mesh = *mesh_;
  auto fov = Teuchos::rcp(new Vector(overlapMap_));
  auto f = fov->getDataNonConst();
  std::vector<char> isLocal(mesh.numElements(), 0);
  for (int e : localElements_) isLocal[e] = 1;
  // 3-point Gauss rule on [-1, 1]: exact for the quadratic segments' |J| N.
  const double gp[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double gw[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  for (const auto& t : bcs_.tractions) {
    for (const Segment& s : mesh.sideSet(t.setName)) {
      if (!isLocal[s.element]) continue;
      for (int q = 0; q < 3; ++q) {
        const double xi = gp[q];
        double N[3], dN[3];
        if (s.numNodes == 2) {
          N[0] = 0.5 * (1 - xi), N[1] = 0.5 * (1 + xi);
          dN[0] = -0.5, dN[1] = 0.5;
        } else {  // start (ξ=-1), end (ξ=1), middle (ξ=0)
          N[0] = 0.5 * xi * (xi - 1), N[1] = 0.5 * xi * (xi + 1), N[2] = 1 - xi * xi;
          dN[0] = xi - 0.5, dN[1] = xi + 0.5, dN[2] = -2 * xi;
        }
        double tx = 0, ty = 0;
        for (int i = 0; i < s.numNodes; ++i) {
          tx += dN[i] * mesh.coord(s.nodes[i])[0];
          ty += dN[i] * mesh.coord(s.nodes[i])[1];
        }
        const double jac = std::hypot(tx, ty);
        for (int i = 0; i < s.numNodes; ++i)
          for (int c = 0; c < 2; ++c)
            f[overlapMap_->getLocalElement(dof(s.nodes[i], c))] += N[i] * t.traction[c] * jac * gw[q];
      }
    }
  }
  f = Teuchos::null;
  fext_ = createVector();
  fext_->doExport(*fov, *exporter_, Tpetra::ADD);
}

Teuchos::RCP<Vector> Model::createVector() const { return Teuchos::rcp(new Vector(ownedMap_)); }

Teuchos::RCP<CrsMatrix> Model::createMatrix() const {
  auto K = Teuchos::rcp(new CrsMatrix(ownedGraph_));
  K->fillComplete(ownedMap_, ownedMap_);
  return K;
}

Teuchos::RCP<Vector> Model::toOverlap(const Vector& owned) const {
  auto v = Teuchos::rcp(new Vector(overlapMap_));
  v->doImport(owned, *importer_, Tpetra::INSERT);
  return v;
}

void Model::applyPrescribed(double lambda, Vector& u) const {
  auto d = u.getDataNonConst();
  const GO first = ownedMap_->getMinGlobalIndex();
  for (size_t l = 0; l < ownedMap_->getNodeNumElements(); ++l) {
    const GO g = first + l;
    const auto& src = constraintSource_[g];
    if (src.first < 0) continue;
    d[l] = bcs_.displacements[src.first].prescribed(static_cast<int>(g % 2), mesh_->coord(src.second), lambda);
  }
}

void Model::prescribedIncrement(double lambda0, double lambda, Vector& du) const {
  du.putScalar(0.0);
  auto d = du.getDataNonConst();
  const GO first = ownedMap_->getMinGlobalIndex();
  for (size_t l = 0; l < ownedMap_->getNodeNumElements(); ++l) {
    const GO g = first + l;
    const auto& src = constraintSource_[g];
    if (src.first < 0) continue;
    const auto& bc = bcs_.displacements[src.first];
    const int c = static_cast<int>(g % 2);
    d[l] = bc.prescribed(c, mesh_->coord(src.second), lambda) - bc.prescribed(c, mesh_->coord(src.second), lambda0);
  }
}

AssemblyResult Model::assemble(const Vector& u, double lambda, Vector* fint, Vector* residual, CrsMatrix* K,
                               const Vector* prescribedStep) const {
  const Mesh& mesh = *mesh_;
  auto uov = toOverlap(u);
  auto ud = uov->getData();
  Teuchos::RCP<Vector> dpov;
  Teuchos::ArrayRCP<const double> dp;
  if (prescribedStep) {
    dpov = toOverlap(*prescribedStep);
    dp = dpov->getData();
  }
  Teuchos::RCP<Vector> fov, rov;
  Teuchos::ArrayRCP<double> fd, rd;
  if (fint) {
    fov = Teuchos::rcp(new Vector(overlapMap_));
    fd = fov->getDataNonConst();
  }
  if (residual) {
    rov = Teuchos::rcp(new Vector(overlapMap_));
    rd = rov->getDataNonConst();
  }
  Teuchos::RCP<CrsMatrix> Kov;
  if (K) {
    Kov = Teuchos::rcp(new CrsMatrix(overlapGraph_));
    Kov->setAllToScalar(0.0);
  }
  unsigned what = kEnergy;
  if (fint || residual) what |= kResidual;
  if (K || prescribedStep) what |= kTangent;

  AssemblyResult result;
  double energy = 0.0;
  int failedElement = -1;
  std::string failure;
  ElementResult er;
  Eigen::MatrixX2d X, ue;
  std::vector<LO> lids;
  std::vector<char> con;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Ke;
  for (int e : localElements_) {
    const int nn = mesh.elementNumNodes(e);
    const int* en = mesh.elementNodes(e);
    X.resize(nn, 2);
    ue.resize(nn, 2);
    lids.resize(2 * nn);
    con.resize(2 * nn);
    for (int i = 0; i < nn; ++i) {
      X(i, 0) = mesh.coord(en[i])[0];
      X(i, 1) = mesh.coord(en[i])[1];
      for (int c = 0; c < 2; ++c) {
        const GO g = dof(en[i], c);
        lids[2 * i + c] = overlapMap_->getLocalElement(g);
        con[2 * i + c] = constrained_[g];
        ue(i, c) = ud[lids[2 * i + c]];
      }
    }
    try {
      elements_[mesh.elementBody(e)]->compute(X, ue, what, er);
    } catch (const InadmissibleDeformation& ex) {
      failedElement = e;
      failure = ex.what();
      break;
    }
    energy += er.energy;
    if (fint)
      for (int a = 0; a < 2 * nn; ++a) fd[lids[a]] += er.residual[a];
    if (!residual && !K) continue;
    if (residual) {
      if (prescribedStep) {
        Eigen::VectorXd d(2 * nn);
        for (int a = 0; a < 2 * nn; ++a) d[a] = con[a] ? dp[lids[a]] : 0.0;
        er.residual += er.tangent * d;
      }
      for (int a = 0; a < 2 * nn; ++a)
        if (!con[a]) rd[lids[a]] += er.residual[a];
    }
    if (K) {
      for (int a = 0; a < 2 * nn; ++a) {
        if (con[a]) {
          er.tangent.row(a).setZero();
          er.tangent.col(a).setZero();
        }
      }
      // Row-major copy: element tangents need not be symmetric (host elements).
      Ke = er.tangent;
      for (int a = 0; a < 2 * nn; ++a)
        Kov->sumIntoLocalValues(lids[a], Teuchos::ArrayView<const LO>(lids.data(), 2 * nn),
                                Teuchos::ArrayView<const double>(Ke.data() + a * 2 * nn, 2 * nn));
    }
  }
  // Every rank learns whether any element failed, so all take the same path.
  int failedAny = -1, failedHere = failedElement;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, failedHere, Teuchos::outArg(failedAny));
  if (failedAny >= 0) {
    DDC_THROW(InadmissibleDeformation, "inadmissible deformation in element " << failedAny << " (body '"
                                           << mesh.body(mesh.elementBody(failedAny)).name << "')"
                                           << (failure.empty() ? "" : ": " + failure));
  }
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, energy, Teuchos::outArg(result.strainEnergy));

  if (fint) {
    fd = Teuchos::null;
    fint->putScalar(0.0);
    fint->doExport(*fov, *exporter_, Tpetra::ADD);
  }
  if (residual) {
    rd = Teuchos::null;
    residual->putScalar(0.0);
    residual->doExport(*rov, *exporter_, Tpetra::ADD);
    // r = fint − λ f_ext on free DOFs (rows of prescribed DOFs were never summed).
    auto r = residual->getDataNonConst();
    auto f = fext_->getData();
    const GO first = ownedMap_->getMinGlobalIndex();
    for (size_t l = 0; l < ownedMap_->getNodeNumElements(); ++l)
      if (!constrained_[first + l]) r[l] -= lambda * f[l];
  }
  if (K) {
    Kov->fillComplete(ownedMap_, ownedMap_);
    K->resumeFill();
    K->setAllToScalar(0.0);
    K->doExport(*Kov, *exporter_, Tpetra::ADD);
    const GO first = ownedMap_->getMinGlobalIndex();
    const double one = 1.0;
    for (size_t l = 0; l < ownedMap_->getNodeNumElements(); ++l) {
      const GO g = first + l;
      if (constrained_[g]) K->replaceGlobalValues(g, Teuchos::tuple<GO>(g), Teuchos::tuple<double>(one));
    }
    K->fillComplete(ownedMap_, ownedMap_);
  }
  return result;
}

}  // namespace ddc
