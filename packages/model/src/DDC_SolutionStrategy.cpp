#include "DDC_SolutionStrategy.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <chrono>

#include "DDC_Error.hpp"
#include "DDC_FetiSlipRows.hpp"

namespace ddc {

namespace {

/// Seconds since the last call (or construction).
class Lap {
 public:
  double operator()() {
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - tick_).count();
    tick_ = now;
    return dt;
  }

 private:
  std::chrono::steady_clock::time_point tick_ = std::chrono::steady_clock::now();
};

// ---- Monolithic ---------------------------------------------------------------

class MonolithicStrategy : public SolutionStrategy {
 public:
  explicit MonolithicStrategy(Teuchos::ParameterList& solverParams) {
    Teuchos::ParameterList& linear = solverParams.sublist("Linear Solver");
    Teuchos::ParameterList& mumps = linear.sublist("MUMPS");
    if (!mumps.isParameter("Ordering")) mumps.set("Ordering", std::string(monolithicMumpsOrdering()));
    solver_ = DirectSolverFactory::withIterativeSolvers().create(linear, "Solver/Linear Solver");
  }

  std::string name() const override { return "Monolithic"; }

  void setUp(std::shared_ptr<Model> model, const std::function<void(const std::string&)>&) override {
    model_ = std::move(model);
    K_ = model_->createMatrix();
    topologyVersion_ = model_->topologyVersion();
    // Nodal coordinates per DOF (near-null space of the iterative back ends).
    const Mesh& mesh = model_->mesh();
    const int dim = model_->dim();
    auto coords = Teuchos::rcp(new MultiVector(model_->ownedMap(), dim));
    const auto& map = *model_->ownedMap();
    for (int n = 0; n < mesh.numNodes(); ++n)
      for (int c = 0; c < dim; ++c) {
        const LO l = map.getLocalElement(model_->dof(n, c));
        if (l == Teuchos::OrdinalTraits<LO>::invalid()) continue;
        for (int k = 0; k < dim; ++k) coords->replaceLocalValue(l, k, mesh.coord(n)[k]);
      }
    solver_->setDofsPerNode(dim);
    solver_->setCoordinates(coords);
  }

  AssemblyResult assemble(const Vector& u, double lambda, Vector& r, const Vector* prescribedStep) override {
    if (model_->topologyVersion() != topologyVersion_) {
      K_ = model_->createMatrix();  // the contact pairing changed the pattern
      topologyVersion_ = model_->topologyVersion();
      symbolicDone_ = false;
    }
    AssemblyRequest request;
    request.residual = &r;
    request.tangent = K_.get();
    request.prescribedStep = prescribedStep;
    request.inertia = inertia_;
    return model_->assemble(u, lambda, request);
  }

  double linearTolerance() const override { return solver_->relativeTolerance(); }
  void setSolveTolerance(double tol) override { solver_->setSolveTolerance(tol); }

  StrategySolveInfo solve(const Vector& b, Vector& du) override {
    StrategySolveInfo info;
    Lap lap;
    if (!symbolicDone_) {
      solver_->symbolic(K_);
      symbolicDone_ = true;
      factored_ = false;
    }
    // A constant tangent (linear elasticity without contact; in dynamics
    // K + c M at a constant time step) is factorised once per analysis.
    if (!factored_ || !model_->tangentIsConstant() || factoredMassFactor_ != tangentMassFactor()) {
      solver_->numeric();
      factored_ = true;
      factoredMassFactor_ = tangentMassFactor();
    }
    info.setupSeconds = lap();
    solver_->solve(b, du);
    info.solveSeconds = lap();
    info.iterations = solver_->lastIterations();
    return info;
  }

 private:
  std::shared_ptr<Model> model_;
  std::unique_ptr<DirectSolver> solver_;
  Teuchos::RCP<CrsMatrix> K_;
  int topologyVersion_ = -1;
  bool symbolicDone_ = false;
  bool factored_ = false;  ///< numeric() done on the current pattern
  double factoredMassFactor_ = 0.0;  ///< tangentMassFactor() of that numeric()
};

// ---- FETI-DP ------------------------------------------------------------------

class FetiDpStrategy : public SolutionStrategy {
 public:
  FetiDpStrategy(Teuchos::RCP<const Teuchos::Comm<int>> comm, Teuchos::ParameterList& solverParams)
      : feti_(std::make_unique<FetiDpSolver>(comm, solverParams.sublist("FETI-DP"), "Solver/FETI-DP")),
        primalChoice_(solverParams.sublist("FETI-DP").get<std::string>("Primal Constraints")) {}

  std::string name() const override { return feti_->usesBddc() ? "BDDC" : "FETI-DP"; }

  /// Where the automatic choices of primal constraints and method change:
  /// from this many subdomains in 3-D the subdomains are small and the
  /// coarse problem large.
  static constexpr int kManySubdomains = 512;

  /// "Method" = Automatic: from kManySubdomains in 3-D, BDDC, whose coarse
  /// solve sits in the preconditioner (single precision), took the same
  /// time as FETI-DP within the noise, and 0.80 of it at 4,096 subdomains
  /// (block_3d at 421k DOFs, doc/feti-dp.md "BDDC"). Runs with contact keep
  /// FETI-DP: their rows are its multipliers.
  bool automaticBddc() const {
    return !model_->hasContact() && model_->dim() == 3 && model_->partition().numSubdomains >= kManySubdomains;
  }

  /// "Primal Constraints" = Automatic on many subdomains in 3-D: every node
  /// of a subdomain edge primal, no averages (doc/feti-dp.md "In 3-D").
  /// With the averages the coarse problem grows with the
  /// subdomains until it dominates: block_3d at 421k DOFs on 2 ranks took
  /// 14.0 / 18.5 / 31.6 s at 512 / 1,024 / 2,048 subdomains, vertices alone
  /// 11.0 / 10.2 / 12.4 s in less memory, for 1.0 / 1.15 / 1.26 times the
  /// dual iterations (doc/performance.md). Fewer subdomains keep the edges.
  bool automaticVerticesOnly() const {
    return primalChoice_ == "Automatic" && model_->dim() == 3 &&
           model_->partition().numSubdomains >= kManySubdomains;
  }

  long long coarseRowsOnThisRank() const override {
    return static_cast<long long>(feti_->primalMap()->getNodeNumElements());
  }

  void setUp(std::shared_ptr<Model> model, const std::function<void(const std::string&)>& progress) override {
    model_ = std::move(model);
    progress_ = progress;
    const Mesh& mesh = model_->mesh();
    std::vector<std::string> report;
    // Edge averages make the interior edge nodes redundant as vertices
    // (doc/feti-dp.md "In 3-D"); with contact too, now that the contact
    // rows are weighted by the stiffness of their sides and split over the
    // copies of shared DOFs (doc/feti-dp.md "Extra rows").
    // BDDC takes vertices only (doc/feti-dp.md "BDDC"): every subdomain-edge
    // node primal, whatever the number of subdomains.
    if (!feti_->usesBddc() && feti_->setAutomaticMethod(automaticBddc()))
      progress("FETI-DP: Method = Automatic, on " + std::to_string(model_->partition().numSubdomains) +
               " subdomains in 3-D without contact: BDDC (iterates on the interface displacements)");
    const bool bddc = feti_->usesBddc();
    const bool strong = primalChoice_ == "Vertices" || automaticVerticesOnly() || bddc;
    if (automaticVerticesOnly()) {
      feti_->setAutomaticPrimalConstraints(PrimalConstraints::Vertices);
      progress("FETI-DP: Primal Constraints = Automatic, on " + std::to_string(model_->partition().numSubdomains) +
               " subdomains in 3-D: every subdomain-edge node primal, no edge averages");
    }
    // In dynamics (inertia set before setUp) K^s + c M^s is nonsingular:
    // a subdomain may float.
    const bool massive = inertia_ != nullptr;
    const auto primal =
        selectPrimalNodes(*model_, &report, strong ? VertexRule::EdgeNodes : VertexRule::EdgeEnds, massive);
    for (const auto& line : report) progress("FETI-DP: " + line);
    subdomains_ = buildSubdomainSystems(*model_, primal);
    sink_.systems = &subdomains_;
    sink_.where.assign(mesh.numElements(), {-1, -1});
    std::vector<FetiSubdomain> fs;
    for (size_t i = 0; i < subdomains_.size(); ++i) {
      for (size_t j = 0; j < subdomains_[i].elements.size(); ++j)
        sink_.where[subdomains_[i].elements[j]] = {static_cast<int>(i), static_cast<int>(j)};
      fs.push_back({subdomains_[i].id, subdomains_[i].dofs, subdomains_[i].primal, subdomains_[i].K, {}, model_->dim(),
                    subdomains_[i].component, subdomains_[i].coordinates});
      if (model_->hasContact()) {
        // Contact rows may touch the DOFs of contact-surface nodes: the
        // Dirichlet preconditioner treats them as interface DOFs.
        auto& flags = fs.back().constrainable;
        flags.assign(subdomains_[i].dofs.size(), 0);
        for (int e : subdomains_[i].elements)
          for (int a = 0; a < mesh.elementNumNodes(e); ++a) {
            const int node = mesh.elementNodes(e)[a];
            if (!model_->isContactSurfaceNode(node)) continue;
            for (int c = 0; c < model_->dim(); ++c) {
              const auto& d = subdomains_[i].dofs;
              const auto it = std::lower_bound(d.begin(), d.end(), model_->dof(node, c));
              if (it != d.end() && *it == model_->dof(node, c)) flags[it - d.begin()] = 1;
            }
          }
      }
    }
    feti_->setTopology(std::move(fs), model_->ownedMap());
    // The size of the coarse problem (doc/feti-dp.md "In 3-D": it grows with
    // the number of subdomain-edge ends a METIS partition makes).
    long ownPrimal = 0, nodes = 0;  // each primal node counted by the rank that owns it
    for (int n = 0; n < mesh.numNodes(); ++n)
      ownPrimal += primal[n] && model_->ownedMap()->isNodeGlobalElement(model_->dof(n, 0)) ? 1 : 0;
    Teuchos::reduceAll<int, long>(*model_->comm(), Teuchos::REDUCE_SUM, ownPrimal, Teuchos::outArg(nodes));
    const GO coarse = GO(feti_->primalMap()->getGlobalNumElements()), edgeFace = feti_->numEdgeFaceConstraints();
    progress(name() + ": " + std::to_string(model_->partition().numSubdomains) + " subdomains, " +
             std::to_string(nodes) + " primal nodes, coarse problem of " + std::to_string(coarse) + " DOFs (" +
             std::to_string(coarse - edgeFace) + " at primal nodes, " + std::to_string(edgeFace) +
             " edge/face constraints)");
    if (model_->hasContact()) b_ = model_->createVector();
  }

  void beginIncrement() override {
    // The contact rows of this (sub)step, from the projections and normals
    // frozen at the last converged state. They stay fixed during the Newton
    // iterations; only their active flags and right-hand sides change.
    if (!model_->hasContact()) return;
    feti_->setConstraintRows(model_->multiplierMap(), model_->contactRowEntries(subdomains_));
    rowEntries_ = model_->contact()->contactRows();
    // The rows in the multiplier map's order: each owned slot's multipliers.
    lmLids_.clear();
    rows_.clear();
    const ContactComponent& c = *model_->contact();
    for (int k : model_->ownedSlots())
      for (int m = 0; m < c.numMultipliers(k); ++m) {
        lmLids_.push_back(model_->ownedMap()->getLocalElement(c.multiplierId(k, m)));
        rows_.push_back({k, m, m > 0 && c.slipRowHeld(k, m - 1)});
      }
  }

  /// What row i of the contact rows is now (doc/feti-dp.md, "Friction rows").
  enum class RowKind { Constraint, Released, Slip };
  RowKind rowKind(size_t i) const {
    const auto& sl = model_->contactSlots()[rows_[i].slot];
    if (!(sl.active && sl.paired())) return RowKind::Released;
    if (rows_[i].multiplier == 0) return RowKind::Constraint;
    if (rows_[i].held) return RowKind::Released;
    return sl.friction == FrictionState::Stick ? RowKind::Constraint : RowKind::Slip;
  }

  /// The contact rows' state for the next solve (doc/feti-dp.md "Extra rows",
  /// "Friction rows"): per row its active flag, c = the right-hand side of
  /// the multiplier row (−g_N, with the predictor's share of the prescribed
  /// increment in the first iteration; −u_t of a sticking pair), and a
  /// slipping pair's rows coupled to its normal row with the known part of
  /// their multipliers in known_ (their forces go into b_). The multipliers
  /// are not subdomain DOFs: b_ is 0 there.
  void setContactRows(const Vector& bModel) {
    std::vector<char> active;
    std::vector<double> c;
    std::vector<CoupledRow> coupled;
    b_->assign(bModel);
    known_.assign(lmLids_.size(), 0.0);
    auto bv = b_->getDataNonConst();
    for (size_t i = 0; i < lmLids_.size(); ++i) {
      active.push_back(rowKind(i) == RowKind::Constraint);
      c.push_back(bv[lmLids_[i]]);
    }
    const ContactComponent& contact = *model_->contact();
    for (size_t i = 0; i < lmLids_.size(); ++i)
      if (rows_[i].multiplier == 0) coupleSlipRows(i, bv, active, c, coupled);
    auto slip = model_->createVector();
    {
      auto sv = slip->getDataNonConst();
      for (size_t i = 0; i < lmLids_.size(); ++i) {
        sv[lmLids_[i]] = known_[i];
        bv[lmLids_[i]] = 0.0;
      }
    }
    if (contact.frictional()) model_->subtractContactRowForces(rowEntries_, *slip, *b_);
    feti_->setConstraintState(active, c);
    if (contact.frictional()) feti_->setConstraintCoupling(coupled);
  }

  /// A slipping pair's tangential rows, its normal row at i: their flags,
  /// right-hand sides, known multiplier parts (known_) and couplings
  /// (slipRowsInDual(), doc/feti-dp.md "Friction rows"). Other pairs are
  /// left as rowKind() made them.
  void coupleSlipRows(size_t i, const Teuchos::ArrayRCP<double>& bv, std::vector<char>& active,
                      std::vector<double>& c, std::vector<CoupledRow>& coupled) {
    const ContactComponent& contact = *model_->contact();
    const int k = rows_[i].slot, nt = contact.numMultipliers(k) - 1;
    bool slips = false;
    for (int a = 1; a <= nt; ++a) slips |= rowKind(i + a) == RowKind::Slip;
    if (!slips) return;
    std::vector<double> b;
    std::vector<char> held;
    std::vector<LO> rows;
    for (int a = 1; a <= nt; ++a) {
      b.push_back(bv[lmLids_[i + a]]);
      held.push_back(rowKind(i + a) != RowKind::Slip);
      rows.push_back(LO(i + a));
    }
    const SlipRowsInDual sd = slipRowsInDual(contact.slipLinearisation(k), b, held, LO(i), rows);
    for (int a = 0; a < nt; ++a) {
      active[i + 1 + a] = sd.active[a];
      c[i + 1 + a] = sd.active[a] ? sd.rhs[a] : 0.0;
      known_[i + 1 + a] = sd.known[a];
    }
    coupled.insert(coupled.end(), sd.coupled.begin(), sd.coupled.end());
  }

  AssemblyResult assemble(const Vector& u, double lambda, Vector& r, const Vector* prescribedStep) override {
    AssemblyRequest request;
    request.residual = &r;
    request.prescribedStep = prescribedStep;
    request.subdomains = &sink_;
    request.inertia = inertia_;
    return model_->assemble(u, lambda, request);
  }

  double linearTolerance() const override { return feti_->convergenceTolerance(); }
  void setSolveTolerance(double tol) override { feti_->setSolveTolerance(tol); }

  StrategySolveInfo solve(const Vector& bModel, Vector& du) override {
    StrategySolveInfo out;
    Lap lap;
    const bool contact = model_->hasContact();
    if (contact) setContactRows(bModel);
    // The subdomain matrices hold the element tangents only (contact enters
    // as constraint rows): with a linear material they are factorised once
    // per analysis, contact or not.
    // In dynamics the subdomain matrices are K^s + c M^s: the same holds at
    // a constant time step (c unchanged).
    const bool refactor =
        !factored_ || !model_->elementTangentsAreConstant() || factoredMassFactor_ != tangentMassFactor();
    if (refactor) {
      feti_->numeric();
      factored_ = true;
      factoredMassFactor_ = tangentMassFactor();
    }
    out.setupSeconds = lap();
    const auto info = feti_->solve(contact ? *b_ : bModel, du);
    if (contact) {
      // Multiplier increments: from FETI-DP on active and slipping rows
      // (with a slipping row's known part); a released multiplier goes to
      // zero (its row of b is −λ).
      auto mu = feti_->constraintMultipliers()->getData();
      auto dv = du.getDataNonConst();
      auto rv = bModel.getData();
      for (size_t i = 0; i < lmLids_.size(); ++i) {
        const RowKind kind = rowKind(i);
        dv[lmLids_[i]] = kind == RowKind::Constraint ? mu[i]
                         : kind == RowKind::Slip     ? mu[i] + known_[i]
                                                     : rv[lmLids_[i]];
      }
    }
    out.solveSeconds = lap();
    out.iterations = info.iterations;
    out.conditionEstimate = info.conditionEstimate;
    if (info.gmresAfterBreakdown)
      progress_("    FETI-DP: CG broke down on the dual problem (indefinite tangent); GMRES solved it in " +
                std::to_string(info.iterations) + " iterations in all (Solver/FETI-DP/Belos/GMRES on CG Breakdown)");
    // (solve()'s Info repeats the last numeric()'s timings: count them once.)
    const double f = refactor ? 1.0 : 0.0;
    out.feti = {f * info.localFactorSeconds, f * info.coarseFactorSeconds, f * info.dirichletFactorSeconds,
                info.localSolveSeconds,      info.coarseSolveSeconds,      info.preconditionerSeconds};
    return out;
  }

  std::string timingReport(const std::array<double, 6>& breakdown) const override {
    double f[6];
    Teuchos::reduceAll(*model_->comm(), Teuchos::REDUCE_MAX, 6, breakdown.data(), f);
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "FETI-DP (max over ranks): local factorisation %.3f s, coarse factorisation %.3f s, Dirichlet "
                  "factorisation %.3f s; local solves %.3f s, coarse solves %.3f s, preconditioner %.3f s",
                  f[0], f[1], f[2], f[3], f[4], f[5]);
    // How often the subdomain matrices were factorised (once per analysis
    // with a linear material, contact or not: doc/feti-dp.md "Extra rows").
    const auto& st = feti_->setupInfo();
    const int lo = st.minLocalFactorizations, hi = st.maxLocalFactorizations;
    std::string line = buf;
    line += lo == hi ? "; each subdomain factorised " + std::to_string(lo) + (lo == 1 ? " time" : " times")
                     : "; subdomains factorised " + std::to_string(lo) + " to " + std::to_string(hi) + " times";
    return line;
  }

 private:
  std::shared_ptr<Model> model_;
  std::unique_ptr<FetiDpSolver> feti_;
  std::string primalChoice_;  ///< "Solver/FETI-DP/Primal Constraints"
  std::function<void(const std::string&)> progress_;
  std::vector<SubdomainSystem> subdomains_;  ///< this rank's subdomain problems
  SubdomainSink sink_;
  Teuchos::RCP<Vector> b_;    ///< right-hand side without the multiplier rows
  std::vector<LO> lmLids_;    ///< owned multiplier DOFs (LIDs in the model's map), in row-map order
  /// Per row of lmLids_: its slot, which of the slot's multipliers (0 the
  /// gap's), and whether a slip row holds nothing (slipRowHeld()).
  struct Row {
    int slot, multiplier;
    bool held;
  };
  std::vector<Row> rows_;
  std::vector<ContactRowEntry> rowEntries_;  ///< this rank's contact rows of the increment
  std::vector<double> known_;  ///< per row: a slipping row's known multiplier increment (setContactRows())
  bool factored_ = false;     ///< numeric() done once
  double factoredMassFactor_ = 0.0;  ///< tangentMassFactor() of that numeric()
};

}  // namespace

namespace {

/// Friction makes the tangent nonsymmetric (doc/contact.md, "Friction"):
/// MUMPS must factorise the whole matrix (SYM=0), not read its lower
/// triangle only. An explicit Symmetric = true is refused.
void requireNonsymmetricSolver(Teuchos::ParameterList& linear, const ContactOptions& contact) {
  if (!contact.frictional() || (linear.isParameter("Type") && linear.get<std::string>("Type") != "MUMPS")) return;
  Teuchos::ParameterList& mumps = linear.sublist("MUMPS");
  const auto* entry = mumps.getEntryPtr("Symmetric");
  DDC_INPUT_REQUIRE(!entry || entry->isDefault() || !mumps.get<bool>("Symmetric"),
                    "'Solver/Linear Solver/MUMPS/Symmetric' = true, but a contact pair has a 'Friction Coefficient' > 0: "
                    "friction makes the tangent nonsymmetric, which a symmetric factorisation (reading only the "
                    "lower triangle) would solve wrongly; remove the parameter or set it to false");
  mumps.set("Symmetric", false);
}

}  // namespace

std::unique_ptr<SolutionStrategy> makeSolutionStrategy(Teuchos::RCP<const Teuchos::Comm<int>> comm,
                                                       Teuchos::ParameterList& solver, const ContactOptions& contact) {
  if (solver.get<std::string>("Strategy") == "FETI-DP") {
    DDC_INPUT_REQUIRE(!contact.enabled() || contact.decomposed,
                      "Solver/Strategy = FETI-DP with Contact/Formulation = Node-To-Segment: the conventional "
                      "element couples the slave and master DOFs directly (its projection and normal follow both "
                      "sides), so it cannot be split across subdomains; use Contact/Formulation = Decomposed "
                      "Node-To-Segment with FETI-DP, or Solver/Strategy = Monolithic");
    DDC_INPUT_REQUIRE(!contact.enabled() || solver.sublist("FETI-DP").get<std::string>("Method", "FETI-DP") != "BDDC",
                      "Solver/FETI-DP/Method = BDDC with contact pairs: BDDC iterates on the interface "
                      "displacements and takes no extra rows, so the contact rows cannot join it "
                      "(doc/feti-dp.md, 'BDDC'); use Solver/FETI-DP/Method = FETI-DP");
    DDC_INPUT_REQUIRE(!solver.isSublist("Linear Solver"),
                      "sublist 'Solver/Linear Solver' does not apply to Solver/Strategy = FETI-DP (its local and "
                      "coarse solvers are set in 'Solver/FETI-DP')");
    return std::make_unique<FetiDpStrategy>(comm, solver);
  }
  DDC_INPUT_REQUIRE(!solver.isSublist("FETI-DP"), "sublist 'Solver/FETI-DP' does not apply to Solver/Strategy = Monolithic");
  requireNonsymmetricSolver(solver.sublist("Linear Solver"), contact);
  auto strategy = std::make_unique<MonolithicStrategy>(solver);
  DirectSolverFactory::withIterativeSolvers().requireDistributable(solver.sublist("Linear Solver"),
                                                                   "Solver/Linear Solver", comm->getSize());
  const std::string type = solver.sublist("Linear Solver").get<std::string>("Type");
  DDC_INPUT_REQUIRE(!contact.enabled() || type == "MUMPS" || type == "Amesos2",
                    "Solver/Linear Solver/Type = " << type << " cannot solve the saddle-point system of contact "
                                                   "(Lagrange multipliers): use MUMPS or Amesos2 with Contact/Pairs");
  return strategy;
}

}  // namespace ddc
