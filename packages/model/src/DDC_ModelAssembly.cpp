// Model::assemble(): one pass over this rank's elements and the contact
// component's contributions, into overlap vectors exported to the owned
// layout and, for the tangent, into its owned rows in place and a ghost-row
// matrix exported to the rows' owners. The passes of one call share their
// buffers in Model::Assembly.
#include "DDC_Model.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <stdexcept>
#include <string>

#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_Substructuring.hpp"

namespace ddc {

class Model::Assembly {
 public:
  Assembly(const Model& model, const Vector& u, const AssemblyRequest& request);
  /// The continuum elements of this rank (stops at an element that fails).
  void elements();
  /// The contact component's contributions (every rank enters it).
  void contact();
  /// Agree over the ranks on failures, reduce the energy, finish the outputs.
  AssemblyResult finish(double lambda);

 private:
  /// Overlap view of an owned vector (null if none).
  Teuchos::ArrayRCP<const double> overlap(const Vector* v, Teuchos::RCP<Vector>& keep) const;
  /// x = X + u of a node whose DOFs are in the overlap map.
  std::array<double, 3> position(int n) const;
  /// Scatter one contribution (DOF lids `lids_`) into the overlap
  /// structures: prescribed rows/columns dropped, predictor term added.
  void scatter(ElementResult& er);
  /// M a (and C v) of local element `local` into inertiaForce_, c M into its tangent.
  void addInertia(size_t local, ElementResult& er);
  /// The free-DOF block of element e's tangent into its subdomain's matrix.
  void addToSubdomain(int e, const ElementResult& er);
  /// Contact row entries of one contribution for the rigid-motion check.
  void addContactRow(const std::vector<GO>& d, const ElementResult& r);
  /// Zero the tangent's values and the ghost rows' (kept between calls,
  /// same graph until the topology changes) for summing into them.
  void beginTangent();
  void exportResidual(double lambda);
  void exportTangent();

  const Model& m_;
  const Vector& u_;
  const AssemblyRequest& req_;
  Teuchos::RCP<Vector> uov_, aov_, vov_, dpov_, fov_, rov_;
  Teuchos::ArrayRCP<const double> ud_, ad_, vd_, dp_;
  Teuchos::ArrayRCP<double> fd_, rd_;
  CrsMatrix* K_ = nullptr;       // the tangent: owned rows, summed in place
  CrsMatrix* Kghost_ = nullptr;  // the rows other ranks own (Model::ghostMatrix_)
  LO numOwned_ = 0;
  std::vector<LO> kcols_;  // one contribution's columns in the tangent's column map
  unsigned what_ = kEnergy;
  RigidMotionCheck* rigid_ = nullptr;
  std::vector<LO> lids_;
  std::vector<char> con_;
  std::vector<int> entities_;  ///< addContactRow(): the node or slot of each DOF of the row
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Ke_;
  std::vector<LO> cols_;  // subdomain scatter buffers, reused across elements
  std::vector<double> vals_;
  Eigen::VectorXd inertiaForce_;
  double energy_ = 0.0;
  int failedElement_ = -1;
  std::string failure_, contactFailure_;
};

Model::Assembly::Assembly(const Model& model, const Vector& u, const AssemblyRequest& request)
    : m_(model), u_(u), req_(request) {
  ud_ = overlap(&u, uov_);
  if (req_.inertia) {
    m_.requireMass();
    ad_ = overlap(req_.inertia->acceleration, aov_);
    if (req_.inertia->damped()) vd_ = overlap(req_.inertia->velocity, vov_);
  }
  dp_ = overlap(req_.prescribedStep, dpov_);
  if (req_.fint) {
    fov_ = Teuchos::rcp(new Vector(m_.overlapMap_));
    fd_ = fov_->getDataNonConst();
  }
  if (req_.residual) {
    rov_ = Teuchos::rcp(new Vector(m_.overlapMap_));
    rd_ = rov_->getDataNonConst();
  }
  numOwned_ = LO(m_.ownedMap_->getNodeNumElements());
  if (req_.tangent) beginTangent();
  if (req_.fint || req_.residual) what_ |= kResidual;
  if (req_.tangent || req_.prescribedStep || req_.subdomains) what_ |= kTangent;
  // Stiffness-proportional damping needs the element tangents for C v.
  if (req_.residual && req_.inertia && req_.inertia->damped() && req_.inertia->stiffnessDamping != 0.0)
    what_ |= kTangent;
  if (req_.subdomains)
    for (auto& sys : *req_.subdomains->systems) {
      sys.K->resumeFill();
      sys.K->setAllToScalar(0.0);
    }
  // The rigid-motion check (AssemblyResult::freeMotions) with every tangent,
  // unless inertia makes the tangent nonsingular.
  const bool massive = req_.inertia && req_.inertia->tangentFactor > 0.0;
  rigid_ = (req_.tangent || req_.subdomains) && !massive ? m_.rigidCheck_.get() : nullptr;
  if (rigid_) rigid_->reset();
}

Teuchos::ArrayRCP<const double> Model::Assembly::overlap(const Vector* v, Teuchos::RCP<Vector>& keep) const {
  if (!v) return Teuchos::null;
  keep = m_.toOverlap(*v);
  return keep->getData();
}

std::array<double, 3> Model::Assembly::position(int n) const {
  std::array<double, 3> x = m_.entityReference(n);
  const GO first = m_.entityFirstDof(n);
  for (int c = 0; c < m_.mesh_->dim(); ++c) {
    const LO l = m_.overlapMap_->getLocalElement(first + c);
    if (l != Teuchos::OrdinalTraits<LO>::invalid()) x[c] += ud_[l];
  }
  return x;
}

void Model::Assembly::scatter(ElementResult& er) {
  const int n = static_cast<int>(lids_.size());
  con_.resize(n);
  for (int a = 0; a < n; ++a) con_[a] = m_.constrained_[m_.overlapMap_->getGlobalElement(lids_[a])];
  if (req_.fint)
    for (int a = 0; a < n; ++a) fd_[lids_[a]] += er.residual[a];
  if (req_.residual) {
    if (req_.prescribedStep) {
      Eigen::VectorXd d(n);
      for (int a = 0; a < n; ++a) d[a] = con_[a] ? dp_[lids_[a]] : 0.0;
      er.residual += er.tangent * d;
    }
    for (int a = 0; a < n; ++a)
      if (!con_[a]) rd_[lids_[a]] += er.residual[a];
  }
  if (req_.tangent) {
    for (int a = 0; a < n; ++a)
      if (con_[a]) {
        er.tangent.row(a).setZero();
        er.tangent.col(a).setZero();
      }
    Ke_ = er.tangent;  // row-major copy: host elements need not be symmetric
    kcols_.resize(n);
    for (int b = 0; b < n; ++b) kcols_[b] = m_.ownedColumn_[lids_[b]];
    for (int a = 0; a < n; ++a) {
      const Teuchos::ArrayView<const double> values(Ke_.data() + a * n, n);
      const LO summed = lids_[a] < numOwned_
                            ? K_->sumIntoLocalValues(lids_[a], Teuchos::ArrayView<const LO>(kcols_), values)
                            : Kghost_->sumIntoLocalValues(lids_[a] - numOwned_,
                                                          Teuchos::ArrayView<const LO>(lids_.data(), n), values);
      // Tpetra skips an entry outside the pattern without a word; the
      // patterns are built from the same elements and slots, so that is a
      // defect here, never an input error.
      if (summed != n)
        throw std::logic_error("Model::assemble: DOF " +
                               std::to_string(m_.overlapMap_->getGlobalElement(lids_[a])) +
                               ": a contribution outside the matrix pattern");
    }
  }
}

void Model::Assembly::addInertia(size_t local, ElementResult& er) {
  // M a into the residual (not fint), c M into every tangent.
  const Inertia& in = *req_.inertia;
  const Eigen::MatrixXd& Me = m_.elementMass(local);
  Eigen::VectorXd ae(lids_.size());
  for (size_t a = 0; a < lids_.size(); ++a) ae[a] = ad_[lids_[a]];
  inertiaForce_ = in.residualFactor * (Me * ae);
  double massFactor = in.tangentFactor;
  if (in.damped()) {
    // C v = (α_R M + β_R K_e) v, K_e the element tangent before the mass
    // enters it; the tangent gains (dv/du) C.
    Eigen::VectorXd ve(lids_.size());
    for (size_t a = 0; a < lids_.size(); ++a) ve[a] = vd_[lids_[a]];
    inertiaForce_ += in.massDamping * (Me * ve);
    if (in.stiffnessDamping != 0.0) inertiaForce_ += in.stiffnessDamping * (er.tangent * ve);
    if (what_ & kTangent) er.tangent *= 1.0 + in.stiffnessDamping * in.velocityFactor;
    massFactor += in.massDamping * in.velocityFactor;
  }
  if (what_ & kTangent) er.tangent += massFactor * Me;
}

void Model::Assembly::addToSubdomain(int e, const ElementResult& er) {
  const auto [sysIndex, pos] = req_.subdomains->where[e];
  auto& sys = (*req_.subdomains->systems)[sysIndex];
  const auto& l = sys.elementLocal[pos];
  for (size_t a = 0; a < l.size(); ++a) {
    if (l[a] < 0) continue;
    cols_.clear();
    vals_.clear();
    for (size_t b = 0; b < l.size(); ++b)
      if (l[b] >= 0) {
        cols_.push_back(l[b]);
        vals_.push_back(er.tangent(a, b));
      }
    sys.K->sumIntoLocalValues(l[a], Teuchos::ArrayView<const LO>(cols_), Teuchos::ArrayView<const double>(vals_));
  }
}

void Model::Assembly::elements() {
  const Mesh& mesh = *m_.mesh_;
  const int d = mesh.dim();
  ElementResult er;
  Eigen::MatrixXd X, ue;
  std::vector<GO> dofs;
  for (size_t local = 0; local < m_.localElements_.size(); ++local) {
    const int e = m_.localElements_[local];
    const int nn = mesh.elementNumNodes(e);
    const int* en = mesh.elementNodes(e);
    X.resize(nn, d);
    ue.resize(nn, d);
    m_.elementDofs(e, dofs);
    lids_.resize(dofs.size());
    for (int i = 0; i < nn; ++i)
      for (int c = 0; c < d; ++c) {
        X(i, c) = mesh.coord(en[i])[c];
        lids_[d * i + c] = m_.overlapMap_->getLocalElement(dofs[d * i + c]);
        ue(i, c) = ud_[lids_[d * i + c]];
      }
    try {
      m_.elements_[mesh.elementBody(e)]->compute(X, ue, what_, er);
    } catch (const InadmissibleDeformation& ex) {
      failedElement_ = e;
      failure_ = ex.what();
      break;
    }
    energy_ += er.energy;
    if (req_.inertia) addInertia(local, er);
    if (req_.subdomains) addToSubdomain(e, er);
    scatter(er);
    if (req_.inertia && req_.residual)
      for (size_t a = 0; a < lids_.size(); ++a)
        if (!con_[a]) rd_[lids_[a]] += inertiaForce_[a];
  }
  if (req_.subdomains)
    for (auto& sys : *req_.subdomains->systems) sys.K->fillComplete(sys.K->getDomainMap(), sys.K->getRangeMap());
}

void Model::Assembly::addContactRow(const std::vector<GO>& d, const ElementResult& r) {
  // (lids_ holds the overlap LIDs of d.)
  // The multipliers' rows of the tangent are the contact rows C_k: the
  // normal row always (an inactive one is empty), a frictional pair's
  // tangential rows only while it sticks (a slipping pair does not hold the
  // bodies along the surface).
  if (!rigid_) return;
  const int n = static_cast<int>(d.size());
  entities_.resize(d.size());
  for (int a = 0; a < n; ++a) entities_[a] = m_.entityAt(lids_[a], d[a]);
  int first = n;
  while (first > 0 && entities_[first - 1] < 0) --first;
  if (first == 0 || first == n) return;
  const int k = -1 - entities_[first];
  const bool sticks = m_.contact_->slots()[k].friction == FrictionState::Stick;
  for (int c = 0; c < n - first; ++c) {
    if (c > 0 && !sticks) break;
    const int row = first + c;
    for (int a = 0; a < first; ++a) {
      const int node = entities_[a];
      if (r.tangent(row, a) != 0.0)
        rigid_->addBodyRowEntry(k * m_.rigidRowsPerSlot_ + c, m_.entityBody(node),
                                static_cast<int>(d[a] - m_.entityFirstDof(node)), position(node), r.tangent(row, a));
    }
  }
}

void Model::Assembly::contact() {
  // The component's contributions (the conventional element of each owned
  // slot, or the decomposed counterparts where they live), in this model's
  // DOF ids. Every rank enters it, also after a failed element here: its
  // gather of the contact DOFs is collective, and a rank that skipped it
  // left the others waiting there for ever. A contact element that fails
  // (its projection does not converge) is agreed on in finish().
  if (!m_.contact_) return;
  try {
    m_.contact_->assemble(u_, nullptr, what_, [&](const std::vector<GO>& d, ElementResult& r) {
      if (failedElement_ >= 0) return;  // the assembly is thrown away in finish()
      lids_.resize(d.size());
      for (size_t a = 0; a < d.size(); ++a) lids_[a] = m_.overlapMap_->getLocalElement(d[a]);
      addContactRow(d, r);
      scatter(r);
    });
  } catch (const InadmissibleDeformation& ex) {
    contactFailure_ = ex.what();
  }
}

AssemblyResult Model::Assembly::finish(double lambda) {
  const Mesh& mesh = *m_.mesh_;
  // Every rank learns whether any element failed, so all take the same path.
  int failedAny = -1;
  Teuchos::reduceAll(*m_.comm_, Teuchos::REDUCE_MAX, failedElement_, Teuchos::outArg(failedAny));
  if (failedAny >= 0) {
    DDC_THROW(InadmissibleDeformation, "inadmissible deformation in element " << failedAny << " (body '"
                                           << mesh.body(mesh.elementBody(failedAny)).name << "')"
                                           << (failure_.empty() ? "" : ": " + failure_));
  }
  if (m_.contact_) {
    contactFailure_ = firstErrorOnAnyRank(*m_.comm_, contactFailure_);
    if (!contactFailure_.empty()) DDC_THROW(InadmissibleDeformation, contactFailure_);
  }
  AssemblyResult result;
  Teuchos::reduceAll(*m_.comm_, Teuchos::REDUCE_SUM, energy_, Teuchos::outArg(result.strainEnergy));
  const GO first = m_.ownedMap_->getMinGlobalIndex();
  const size_t numOwned = m_.ownedMap_->getNodeNumElements();
  if (rigid_) {
    for (size_t l = 0; l < numOwned; ++l) {
      const GO g = first + static_cast<GO>(l);
      const int n = m_.overlapEntity_[l];
      if (m_.constrained_[g] && n >= 0) rigid_->addPrescribed(n, static_cast<int>(g - m_.nodeDof_[n]), position(n));
    }
    result.freeMotions = rigid_->freeMotions(*m_.comm_);
  }
  if (req_.fint) {
    fd_ = Teuchos::null;
    req_.fint->putScalar(0.0);
    req_.fint->doExport(*fov_, *m_.exporter_, Tpetra::ADD);
  }
  if (req_.residual) exportResidual(lambda);
  if (req_.tangent) exportTangent();
  return result;
}

void Model::Assembly::exportResidual(double lambda) {
  const GO first = m_.ownedMap_->getMinGlobalIndex();
  const size_t numOwned = m_.ownedMap_->getNodeNumElements();
  Vector& residual = *req_.residual;
  rd_ = Teuchos::null;
  residual.putScalar(0.0);
  residual.doExport(*rov_, *m_.exporter_, Tpetra::ADD);
  auto r = residual.getDataNonConst();
  // λ f_ext, or with a traction's Load Curve Σ s_t(λ) f_t (externalForceAt()).
  Teuchos::RCP<Vector> curved;
  if (m_.hasTractionCurves()) {
    curved = m_.createVector();
    m_.externalForceAt(lambda, *curved);
  }
  auto f = curved ? curved->getData() : m_.fext_->getData();
  const double factor = curved ? 1.0 : lambda;
  for (size_t l = 0; l < numOwned; ++l)
    if (!m_.constrained_[first + l]) r[l] -= factor * f[l];
  if (m_.bodyForce_) {
    auto b = m_.bodyForce_->getData();
    for (size_t l = 0; l < numOwned; ++l)
      if (!m_.constrained_[first + l]) r[l] -= b[l];
  }
  if (req_.inertia && req_.inertia->force) {
    auto g = req_.inertia->force->getData();
    for (size_t l = 0; l < numOwned; ++l)
      if (!m_.constrained_[first + l]) r[l] += g[l];
  }
}

void Model::Assembly::beginTangent() {
  K_ = req_.tangent;
  if (K_->getCrsGraph().get() != m_.ownedGraph_.get())
    throw std::logic_error("Model::assemble: the tangent was not made by createMatrix() for the current "
                           "sparsity pattern (topologyVersion())");
  K_->resumeFill();
  K_->setAllToScalar(0.0);
  if (m_.ghostMatrix_.is_null() || m_.ghostMatrix_->getCrsGraph().get() != m_.ghostGraph_.get())
    m_.ghostMatrix_ = Teuchos::rcp(new CrsMatrix(m_.ghostGraph_));
  else
    m_.ghostMatrix_->resumeFill();
  Kghost_ = m_.ghostMatrix_.get();
  Kghost_->setAllToScalar(0.0);
}

void Model::Assembly::exportTangent() {
  const GO first = m_.ownedMap_->getMinGlobalIndex();
  Kghost_->fillComplete(m_.ownedMap_, m_.ownedMap_);
  K_->doExport(*Kghost_, *m_.ghostExporter_, Tpetra::ADD);
  // A prescribed DOF's row and column are the identity's (its element
  // entries were dropped in scatter()); an owned DOF's column LID is its row LID.
  for (LO l = 0; l < numOwned_; ++l)
    if (m_.constrained_[first + l]) K_->replaceLocalValues(l, Teuchos::tuple<LO>(l), Teuchos::tuple<double>(1.0));
  K_->fillComplete(m_.ownedMap_, m_.ownedMap_);
}

AssemblyResult Model::assemble(const Vector& u, double lambda, const AssemblyRequest& request) const {
  Assembly a(*this, u, request);
  a.elements();
  a.contact();
  return a.finish(lambda);
}

}  // namespace ddc
