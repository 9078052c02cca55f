// A host code using DDContact's components without ddc::Analysis
// (doc/embedding.md, depths (b) and (c)): its own mesh, DOF numbering,
// partition, element loop and Newton iteration; DDContact's contact component
// for the decomposed node-to-segment element (pairing at step ends, rows in
// the host's DOF ids, active set) and its FetiDpSolver for the linear
// systems (subdomain matrices and contact rows in, displacements and
// multipliers out).
//
// The problem: a Neo-Hookean punch (the "Upper" block, 1 x 0.5) pressed by a
// prescribed displacement of its top into a wider block ("Lower", 2 x 1)
// fixed at its bottom; non-matching meshes on the contact interface. The host
// splits each block at x = 1 into two subdomains (four in all) and lets
// findPrimalVertices() choose the primal vertices from the DOF sharing. The
// same problem is run through the whole analysis (what the ddcontact
// application runs) with another partition and the analysis' corner rule; the per-step strain energies and contact forces must agree to
// kAgreement: FETI-DP solves the same equations for any partition, so only
// the Newton and Krylov tolerances (1e-12) separate the two.
#include <DDC_Analysis.hpp>
#include <DDC_ContactComponent.hpp>
#include <DDC_Element.hpp>
#include <DDC_ElementFactory.hpp>
#include <DDC_Error.hpp>
#include <DDC_FetiDpSolver.hpp>
#include <DDC_FetiPrimalVertices.hpp>
#include <DDC_MpiRecords.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <set>

namespace {

using ddc::GO;
using ddc::LO;

/// Relative agreement of the host's and the analysis' per-step results.
constexpr double kAgreement = 1e-10;
constexpr double kPress = 0.1;  ///< prescribed downward displacement of the punch's top at load factor 1
constexpr int kSteps = 4;
constexpr double kE = 1000.0, kNu = 0.3;

struct Block {
  const char* name;
  double x0, y0, lx, ly;
  int nx, ny;
};
const Block kBlocks[2] = {{"Lower", 0.0, 0.0, 2.0, 1.0, 8, 4}, {"Upper", 0.5, 1.0, 1.0, 0.5, 6, 3}};

/// The host's mesh: Quad4 elements (counter-clockwise), nodes of Lower then Upper.
struct HostMesh {
  std::vector<Eigen::Vector2d> X;
  std::vector<std::array<int, 4>> quads;
  std::vector<int> body;
  int first[2] = {0, 0};  ///< first node of each block
  int node(int b, int i, int j) const { return first[b] + j * (kBlocks[b].nx + 1) + i; }
  HostMesh() {
    for (int b = 0; b < 2; ++b) {
      const Block& k = kBlocks[b];
      first[b] = int(X.size());
      for (int j = 0; j <= k.ny; ++j)
        for (int i = 0; i <= k.nx; ++i) X.emplace_back(k.x0 + k.lx * i / k.nx, k.y0 + k.ly * j / k.ny);
      for (int j = 0; j < k.ny; ++j)
        for (int i = 0; i < k.nx; ++i) {
          quads.push_back({node(b, i, j), node(b, i + 1, j), node(b, i + 1, j + 1), node(b, i, j + 1)});
          body.push_back(b);
        }
    }
  }
};

Teuchos::ParameterList material() {
  Teuchos::ParameterList e("Element");
  e.set("Type", "Quad4");
  e.sublist("Material").set("Type", "Neo-Hookean").set("Young's Modulus", kE).set("Poisson's Ratio", kNu);
  return e;
}

Teuchos::ParameterList fetiParameters() {
  Teuchos::ParameterList p("FETI-DP");
  p.sublist("Belos").set("Convergence Tolerance", 1e-12);
  return p;
}

/// One converged step: strain energy and contact force (y) on the slave body.
struct StepResult {
  double energy, forceY;
  int active;
};

// ---- the whole analysis (what `ddcontact` runs), as the reference ---------------

std::vector<StepResult> reference(const Teuchos::RCP<const Teuchos::Comm<int>>& comm) {
  Teuchos::ParameterList p("reference");
  for (const Block& k : kBlocks) {
    auto& body = p.sublist("Mesh").sublist("Bodies").sublist(k.name);
    body.set("Generator", "Rectangle");
    body.sublist("Rectangle")
        .set("Origin X", k.x0)
        .set("Origin Y", k.y0)
        .set("Length X", k.lx)
        .set("Length Y", k.ly)
        .set("Elements X", k.nx)
        .set("Elements Y", k.ny);
    body.set("Element", material());
  }
  auto& bc = p.sublist("Boundary Conditions");
  bc.sublist("Fixed").set("Type", "Displacement").set("Set", "Lower/bottom");
  bc.sublist("Press").set("Type", "Displacement").set("Set", "Upper/top").set("Value Y", -kPress);
  auto& c = p.sublist("Contact");
  c.set("Formulation", "Decomposed Node-To-Segment");
  c.sublist("Pairs").sublist("Interface").set("Slave", "Upper/bottom").set("Master", "Lower/top");
  p.sublist("Partition").set("Method", "Box Grid").set("Box Grid X", 2).set("Box Grid Y", 2);
  p.sublist("Solver").set("Strategy", "FETI-DP");
  p.sublist("Solver").set("FETI-DP", fetiParameters());
  p.sublist("Newton").set("Residual Tolerance", 1e-12).set("Absolute Residual Tolerance", 1e-13);
  p.sublist("Load Stepping").set("Number of Steps", kSteps);
  p.sublist("Output").set("Progress", false);
  ddc::Analysis a(comm, p);
  a.run("");
  std::vector<StepResult> out;
  for (const auto& r : a.history()) out.push_back({r.strainEnergy, r.contactForce[1], r.activeContacts});
  return out;
}

// ---- the host ----------------------------------------------------------------------

class Host {
 public:
  explicit Host(Teuchos::RCP<const Teuchos::Comm<int>> comm) : comm_(std::move(comm)) {
    const int P = comm_->getSize(), me = comm_->getRank();
    Teuchos::ParameterList el = material();
    element_ = ddc::ElementFactory::withBuiltins().create(el, "host element");
    // Partition: subdomain 2·block + (centroid right of x = 1); blocks of subdomains per rank.
    const int nel = int(mesh_.quads.size());
    sub_.resize(nel);
    for (int e = 0; e < nel; ++e) {
      double xc = 0;
      for (int a : mesh_.quads[e]) xc += 0.25 * mesh_.X[a].x();
      sub_[e] = 2 * mesh_.body[e] + (xc > 1.0 ? 1 : 0);
    }
    auto rankOf = [&](int s) { return s * P / 4; };
    const int nn = int(mesh_.X.size());
    owner_.assign(nn, P);
    for (int e = 0; e < nel; ++e)
      for (int a : mesh_.quads[e]) owner_[a] = std::min(owner_[a], rankOf(sub_[e]));
    // DOFs: each rank's nodes, in node order, contiguous per rank.
    std::vector<GO> count(P + 1, 0);
    for (int n = 0; n < nn; ++n) count[owner_[n] + 1] += 2;
    for (int r = 0; r < P; ++r) count[r + 1] += count[r];
    dof_.resize(nn);
    std::vector<GO> next(count.begin(), count.end() - 1);
    for (int n = 0; n < nn; ++n) dof_[n] = next[owner_[n]], next[owner_[n]] += 2;
    map_ = Teuchos::rcp(new ddc::Map(count[P], size_t(count[me + 1] - count[me]), 0, comm_));
    // Prescribed DOFs: Lower's bottom (both), Upper's top (both; y pressed).
    // (indexed by DOF id, replicated: the host's mesh is on every rank).
    prescribed_.assign(count[P], 0);
    for (int i = 0; i <= kBlocks[0].nx; ++i) prescribed_[dof_[mesh_.node(0, i, 0)]] = prescribed_[dof_[mesh_.node(0, i, 0)] + 1] = 1;
    for (int i = 0; i <= kBlocks[1].nx; ++i) {
      const GO g = dof_[mesh_.node(1, i, kBlocks[1].ny)];
      prescribed_[g] = prescribed_[g + 1] = 1;
    }
    for (int e = 0; e < nel; ++e)
      if (rankOf(sub_[e]) == me) localElements_.push_back(e);
    buildContact();
    buildFeti();
    // Overlap DOFs: those of local elements (the contact DOFs of this
    // rank's counterparts are among them).
    std::set<GO> ov;
    for (int e : localElements_)
      for (int a : mesh_.quads[e]) ov.insert({dof_[a], dof_[a] + 1});
    std::vector<GO> ovv(ov.begin(), ov.end());
    overlap_ = Teuchos::rcp(new ddc::Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                         Teuchos::ArrayView<const GO>(ovv), 0, comm_));
    import_ = Teuchos::rcp(new Tpetra::Import<LO, GO>(map_, overlap_));
    export_ = Teuchos::rcp(new Tpetra::Export<LO, GO>(overlap_, map_));
  }

  std::vector<StepResult> run() {
    auto u = Teuchos::rcp(new ddc::Vector(map_));
    ddc::Vector lambda(contact_->multiplierMap());
    std::vector<StepResult> out;
    contact_->updatePairing(*u, /*global=*/true, /*freeze=*/true);
    for (int n = 1; n <= kSteps; ++n) {
      const double load = double(n) / kSteps;
      applyPrescribed(*u, load);
      contact_->activateAllPaired();  // Initial Contact State = In Contact
      feti_->setConstraintRows(contact_->multiplierMap(), rowEntries());
      newton(*u, lambda, n);
      // Step end: read the converged contact state, then refresh the pairing
      // (one exchange) and freeze the next step's projections and normals.
      contact_->updateActiveSet(*u, &lambda);
      const auto summary = contact_->reduceSummary();
      out.push_back({assemble(*u, lambda, nullptr, nullptr), summary.force[1], summary.active});
      contact_->updatePairing(*u, true, true);
    }
    return out;
  }

 private:
  void buildContact() {
    const int me = comm_->getRank();
    ddc::ContactComponentOptions o;
    o.decomposed = true;
    o.searchRadius = kBlocks[0].lx / kBlocks[0].nx;           // the analysis' default: mean master segment length
    o.penetrationTolerance = 1e-6 * kBlocks[0].lx / kBlocks[0].nx;  // its default: 1e-6 of it
    contact_ = std::make_unique<ddc::ContactComponent>(comm_, o);
    ddc::ContactPairSurfaces pair;
    pair.name = "Interface";
    pair.slaveName = "punch bottom";
    pair.masterName = "block top";
    std::set<int> surface;
    // Master: Lower's top, right to left (body below on the left); its
    // elements are the top row, depth = their height.
    const Block& lo = kBlocks[0];
    for (int i = lo.nx; i > 0; --i) {
      const int e = (lo.ny - 1) * lo.nx + (i - 1);
      const int a = mesh_.node(0, i, lo.ny), b = mesh_.node(0, i - 1, lo.ny);
      surface.insert({a, b});
      if (sub_[e] * comm_->getSize() / 4 == me)
        pair.masterFacets.push_back({long(lo.nx - i), {{a, b}}, e, sub_[e], lo.ly / lo.ny});
    }
    // Slave: Upper's bottom, left to right (body above on the left).
    const Block& up = kBlocks[1];
    const int firstUpper = lo.nx * lo.ny;
    for (int i = 0; i < up.nx; ++i) {
      const int e = firstUpper + i;
      const int a = mesh_.node(1, i, 0), b = mesh_.node(1, i + 1, 0);
      surface.insert({a, b});
      if (sub_[e] * comm_->getSize() / 4 == me) pair.slaveFacets.push_back({long(i), {{a, b}}, e, sub_[e], 0.0});
    }
    for (int i = 0; i <= up.nx; ++i)
      if (owner_[mesh_.node(1, i, 0)] == me) pair.slaveNodes.push_back(mesh_.node(1, i, 0));
    std::vector<ddc::ContactNode> nodes;
    std::vector<ddc::ContactNodeDofs> dofs;
    for (int n : surface)
      if (owner_[n] == me) {
        nodes.push_back({n, mesh_.X[n]});
        dofs.push_back({n, {{dof_[n], dof_[n] + 1}}, {{bool(prescribed_[dof_[n]]), bool(prescribed_[dof_[n] + 1])}}});
      }
    contact_->registerNodes(nodes);
    contact_->registerPair(pair);
    contact_->commit();
    contact_->setDofs(map_, dofs);  // the multipliers live in FETI-DP, not in the host's vector
  }

  void buildFeti() {
    const int me = comm_->getRank(), P = comm_->getSize();
    std::vector<ddc::FetiSubdomain> fs;
    for (int s = 0; s < 4; ++s) {
      if (s * P / 4 != me) continue;
      Subdomain sd;
      sd.id = s;
      std::set<GO> dofs;
      for (int e : localElements_)
        if (sub_[e] == s) {
          sd.elements.push_back(e);
          for (int a : mesh_.quads[e])
            for (int c = 0; c < 2; ++c)
              if (!prescribed_[dof_[a] + c]) dofs.insert(dof_[a] + c);
        }
      sd.dofs.assign(dofs.begin(), dofs.end());
      ddc::FetiSubdomain f;
      f.id = s;
      f.dofs = sd.dofs;
      f.dim = 2;
      std::map<GO, int> nodeOfDof;
      for (int e : sd.elements)
        for (int a : mesh_.quads[e]) nodeOfDof[dof_[a]] = a, nodeOfDof[dof_[a] + 1] = a;
      for (GO g : f.dofs) {
        const int a = nodeOfDof[g];
        f.component.push_back(int(g - dof_[a]));
        f.coordinates.insert(f.coordinates.end(), {mesh_.X[a].x(), mesh_.X[a].y()});
        f.constrainable.push_back(contact_->isSurfaceNode(a) ? 1 : 0);
      }
      // Pattern of the subdomain stiffness (local numbering).
      const size_t nd = f.dofs.size();
      auto self = Teuchos::rcp(new Teuchos::SerialComm<int>());
      auto lmap = Teuchos::rcp(new ddc::Map(nd, 0, self));
      std::vector<std::set<LO>> rows(nd);
      for (int e : sd.elements) {
        const auto l = localDofs(sd, e);
        for (LO r : l)
          if (r >= 0)
            for (LO c : l)
              if (c >= 0) rows[r].insert(c);
      }
      Teuchos::Array<size_t> nnz(nd);
      for (size_t r = 0; r < nd; ++r) nnz[r] = rows[r].size();
      auto graph = Teuchos::rcp(new ddc::CrsGraph(lmap, lmap, nnz()));
      for (size_t r = 0; r < nd; ++r) {
        std::vector<LO> cols(rows[r].begin(), rows[r].end());
        graph->insertLocalIndices(LO(r), Teuchos::ArrayView<const LO>(cols));
      }
      graph->fillComplete();
      sd.K = Teuchos::rcp(new ddc::CrsMatrix(graph));
      sd.K->fillComplete();
      f.K = sd.K;
      fs.push_back(f);
      subdomains_.push_back(std::move(sd));
    }
    // Primal vertices from the DOF sharing and the stiffness patterns alone
    // (here: none, each cut is one edge; its averages and rotation are primal).
    const auto vertices = ddc::findPrimalVertices(ddc::rawComm(*comm_), *map_, fs, 2);
    for (size_t i = 0; i < fs.size(); ++i) fs[i].primal = vertices[i];
    auto params = fetiParameters();
    feti_ = std::make_unique<ddc::FetiDpSolver>(comm_, params, "host FETI-DP");
    feti_->setTopology(std::move(fs), map_);
  }

  struct Subdomain {
    int id = -1;
    std::vector<GO> dofs;
    std::vector<int> elements;
    Teuchos::RCP<ddc::CrsMatrix> K;
  };

  /// Local index in the subdomain of each DOF of element e (−1: prescribed).
  std::vector<LO> localDofs(const Subdomain& sd, int e) const {
    std::vector<LO> l;
    for (int a : mesh_.quads[e])
      for (int c = 0; c < 2; ++c) {
        const auto it = std::lower_bound(sd.dofs.begin(), sd.dofs.end(), dof_[a] + c);
        l.push_back(it != sd.dofs.end() && *it == dof_[a] + c ? LO(it - sd.dofs.begin()) : LO(-1));
      }
    return l;
  }

  void applyPrescribed(ddc::Vector& u, double load) const {
    for (int n = 0; n < int(mesh_.X.size()); ++n) {
      if (owner_[n] != comm_->getRank()) continue;
      const bool top = mesh_.X[n].y() == kBlocks[1].y0 + kBlocks[1].ly;
      for (int c = 0; c < 2; ++c)
        if (prescribed_[dof_[n] + c]) u.replaceGlobalValue(dof_[n] + c, top && c == 1 ? -kPress * load : 0.0);
    }
  }

  /// The contact rows in the FETI-DP subdomains' local DOFs: the slave
  /// counterpart in the first local subdomain holding the slave node, the
  /// master counterpart in its facet's subdomain.
  std::vector<std::vector<ddc::ConstraintEntry>> rowEntries() const {
    std::vector<std::vector<ddc::ConstraintEntry>> out(subdomains_.size());
    for (const auto& e : contact_->contactRows()) {
      for (size_t i = 0; i < subdomains_.size(); ++i) {
        const auto& d = subdomains_[i].dofs;
        const auto it = std::lower_bound(d.begin(), d.end(), e.dof);
        if (it == d.end() || *it != e.dof) continue;
        if (e.role == ddc::SurfaceContactRole::Master && subdomains_[i].id != e.subdomain) continue;
        out[i].push_back({e.row, LO(it - d.begin()), e.coefficient});
        break;
      }
    }
    return out;
  }

  /// Element loop: strain energy (global); with r, the residual f_int + contact
  /// forces on the free DOFs (owned layout) and each multiplier row's
  /// residual (frozen gap when active) in `rows`; the subdomain tangents.
  double assemble(const ddc::Vector& u, const ddc::Vector& lambda, ddc::Vector* r, ddc::Vector* rows) {
    ddc::Vector uo(overlap_);
    uo.doImport(u, *import_, Tpetra::INSERT);
    auto ud = uo.getData();
    ddc::Vector ro(overlap_);
    auto rd = ro.getDataNonConst();
    double energy = 0.0;
    Eigen::MatrixXd X(4, 2), ue(4, 2);
    ddc::ElementResult er;
    for (auto& sd : subdomains_) {
      if (r) sd.K->resumeFill(), sd.K->setAllToScalar(0.0);
      for (int e : sd.elements) {
        for (int a = 0; a < 4; ++a) {
          const int n = mesh_.quads[e][a];
          X.row(a) = mesh_.X[n].transpose();
          for (int c = 0; c < 2; ++c) ue(a, c) = ud[overlap_->getLocalElement(dof_[n] + c)];
        }
        element_->compute(X, ue, r ? ddc::kAll : ddc::kEnergy, er);
        energy += er.energy;
        if (!r) continue;
        const auto l = localDofs(sd, e);
        for (int a = 0; a < 8; ++a) {
          const int n = mesh_.quads[e][a / 2];
          if (!prescribed_[dof_[n] + a % 2]) rd[overlap_->getLocalElement(dof_[n] + a % 2)] += er.residual[a];
          if (l[a] < 0) continue;
          for (int b = 0; b < 8; ++b)
            if (l[b] >= 0) sd.K->sumIntoLocalValues(l[a], Teuchos::tuple<LO>(l[b]), Teuchos::tuple<double>(er.tangent(a, b)));
        }
      }
      if (r) sd.K->fillComplete();
    }
    double total = 0.0;
    Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, energy, Teuchos::outArg(total));
    if (!r) return total;
    // Contact: forces λ·∂g/∂u on the free DOFs, the multiplier rows' residuals
    // summed over the two counterparts.
    std::map<GO, double> rowPart;
    contact_->assemble(u, &lambda, ddc::kResidual, [&](const std::vector<GO>& dofs, ddc::ElementResult& c) {
      for (size_t a = 0; a + 1 < dofs.size(); ++a)
        if (!prescribed_[dofs[a]]) rd[overlap_->getLocalElement(dofs[a])] += c.residual[a];
      rowPart[dofs.back()] += c.residual[dofs.size() - 1];
    });
    rd = Teuchos::null;
    r->putScalar(0.0);
    r->doExport(ro, *export_, Tpetra::ADD);
    std::vector<GO> ids;
    for (const auto& kv : rowPart) ids.push_back(kv.first);
    auto partMap = Teuchos::rcp(new ddc::Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                             Teuchos::ArrayView<const GO>(ids), 0, comm_));
    ddc::Vector part(partMap);
    for (const auto& kv : rowPart) part.replaceGlobalValue(kv.first, kv.second);
    rows->putScalar(0.0);
    rows->doExport(part, Tpetra::Export<LO, GO>(partMap, rows->getMap()), Tpetra::ADD);
    return total;
  }

  void newton(ddc::Vector& u, ddc::Vector& lambda, int step) {
    ddc::Vector r(map_), du(map_), rows(contact_->multiplierMap());
    double r0 = 0.0;
    bool stateChanged = true;
    for (int it = 0; it < 30; ++it) {
      assemble(u, lambda, &r, &rows);
      // The residual of the active set: forces, and the multiplier rows
      // (gap when active, λ when released).
      std::vector<char> active;
      std::vector<double> c;
      auto rv = rows.getData();
      auto lv = lambda.getData();
      double rowNorm2 = 0.0;
      for (size_t i = 0; i < contact_->ownedSlots().size(); ++i) {
        const auto& s = contact_->slots()[contact_->ownedSlots()[i]];
        const bool on = s.active && s.paired();
        active.push_back(on);
        c.push_back(on ? -rv[i] : 0.0);
        rowNorm2 += on ? rv[i] * rv[i] : lv[i] * lv[i];
      }
      double rowTotal = 0.0;
      Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, rowNorm2, Teuchos::outArg(rowTotal));
      const double rnorm = std::sqrt(std::pow(r.norm2(), 2) + rowTotal);
      if (it == 0) r0 = rnorm;
      if (it > 0 && !stateChanged && rnorm <= 1e-12 * r0) return;
      r.scale(-1.0);
      feti_->setConstraintState(active, c);
      feti_->numeric();
      feti_->solve(r, du);
      u.update(1.0, du, 1.0);
      // Multipliers: the increment on active rows; a released one is zero.
      std::vector<double> next(active.size());
      {
        auto mu = feti_->constraintMultipliers()->getData();
        auto lv = lambda.getData();
        for (size_t i = 0; i < active.size(); ++i) next[i] = active[i] ? lv[i] + mu[i] : 0.0;
      }
      for (size_t i = 0; i < next.size(); ++i) lambda.replaceLocalValue(LO(i), next[i]);
      stateChanged = !contact_->updateActiveSet(u, &lambda).empty();
    }
    throw ddc::SolverError("host Newton: no convergence in step " + std::to_string(step));
  }

  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  HostMesh mesh_;
  std::shared_ptr<ddc::Element> element_;
  std::vector<int> sub_, owner_, localElements_;
  std::vector<GO> dof_;
  std::vector<char> prescribed_;  ///< per DOF id
  Teuchos::RCP<const ddc::Map> map_, overlap_;
  Teuchos::RCP<Tpetra::Import<LO, GO>> import_;
  Teuchos::RCP<Tpetra::Export<LO, GO>> export_;
  std::unique_ptr<ddc::ContactComponent> contact_;
  std::unique_ptr<ddc::FetiDpSolver> feti_;
  std::vector<Subdomain> subdomains_;
};

}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  int failures = 0;
  try {
    Host host(comm);
    const auto mine = host.run();
    const auto ref = reference(comm);
    if (mine.size() != ref.size()) {
      ++failures;
      std::cerr << "host: " << mine.size() << " steps, reference " << ref.size() << "\n";
    }
    for (size_t n = 0; n < std::min(mine.size(), ref.size()); ++n) {
      const double de = std::abs(mine[n].energy - ref[n].energy) / std::abs(ref[n].energy);
      const double df = std::abs(mine[n].forceY - ref[n].forceY) / std::abs(ref[n].forceY);
      if (comm->getRank() == 0)
        std::printf("step %zu: energy %.15g (analysis %.15g, rel. diff %.1e), contact force y %.15g (%.15g, %.1e), "
                    "active %d (%d)\n",
                    n + 1, mine[n].energy, ref[n].energy, de, mine[n].forceY, ref[n].forceY, df, mine[n].active,
                    ref[n].active);
      if (!(de <= kAgreement) || !(df <= kAgreement) || mine[n].active != ref[n].active || !(ref[n].forceY > 0))
        ++failures;
    }
  } catch (const std::exception& e) {
    std::cerr << "host contact + FETI-DP: " << e.what() << "\n";
    ++failures;
  }
  if (comm->getRank() == 0)
    std::cout << (failures ? "host contact + FETI-DP: FAILED" : "host contact + FETI-DP: OK") << std::endl;
  return failures ? 1 : 0;
}
