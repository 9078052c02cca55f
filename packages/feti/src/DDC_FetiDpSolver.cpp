// FETI-DP dual-interface solver (doc/feti-dp.md): see DDC_FetiDpSolver.hpp
// for the method. This unit holds the parameters and the driver
// (setTopology(), numeric(), solve(), the constraint rows); the state lives
// in the units of DDC_FetiDpImpl.hpp (Subdomain, JumpOperator,
// CoarseProblem, DualOperator, Preconditioner).
#include "DDC_FetiDpSolver.hpp"

#include <BelosLinearProblem.hpp>
#include <BelosPseudoBlockCGSolMgr.hpp>
#include <BelosSolverFactory.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <algorithm>
#include <climits>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "DDC_Error.hpp"
#include "DDC_FetiDpImpl.hpp"
#include "DDC_MapOwners.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

const std::vector<std::string>& preconditionerNames() {
  static const std::vector<std::string> n{"Dirichlet", "Lumped", "None"};
  return n;
}
const std::vector<std::string>& scalingNames() {
  static const std::vector<std::string> n{"Automatic", "Multiplicity", "Stiffness"};
  return n;
}
/// "Local Solver/Type" by default (measured in doc/performance.md).
constexpr const char* kDefaultLocalSolver = "CHOLMOD";

const std::vector<std::string>& belosSolverNames() {
  static const std::vector<std::string> n{"CG", "GMRES", "MINRES"};
  return n;
}

/// BDDC works on the caller's DOFs with vertices as the primal space and
/// multiplicity weights (doc/feti-dp.md "BDDC"): the options it cannot
/// honour are refused by name.
/// \returns "" if BDDC can honour the options, else the first it cannot,
/// with what it expects.
std::string bddcConflict(const Teuchos::ParameterList& params, const std::string& path) {
  auto conflict = [&](const std::string& name, const std::string& expected) {
    return "parameter '" + joinPath(path, name) + "' = " + params.get<std::string>(name) + " cannot be used with '" +
           joinPath(path, "Method") + "' = BDDC; expected " + expected;
  };
  if (params.get<std::string>("Preconditioner") != "Dirichlet") return conflict("Preconditioner", "Dirichlet");
  if (params.get<std::string>("Scaling") == "Stiffness") return conflict("Scaling", "Automatic or Multiplicity");
  const std::string primal = params.get<std::string>("Primal Constraints");
  if (primal != "Automatic" && primal != "Vertices") return conflict("Primal Constraints", "Automatic or Vertices");
  return "";
}

/// True if `coarse` (the sublist "Coarse Solver", before validation) is MUMPS
/// with no precision given: the method may choose it.
bool coarsePrecisionOpen(const Teuchos::ParameterList& coarse) {
  if (coarse.isParameter("Type") && coarse.get<std::string>("Type") != "MUMPS") return false;
  return !coarse.isSublist("MUMPS") || !coarse.sublist("MUMPS").isParameter("Precision");
}

/// The arithmetic of a MUMPS coarse solver. BDDC's coarse solve is inside
/// its preconditioner only: single precision halves its factorisation and
/// solves for the same iterations, so it is BDDC's default. FETI-DP's coarse
/// solve is inside F, which must be exact: single precision is refused.
void chooseCoarsePrecision(Teuchos::ParameterList& coarse, const std::string& path, bool bddc) {
  // `coarse` is the sublist "Coarse Solver" of the solver's list at `path`.
  if (coarse.isParameter("Type") && coarse.get<std::string>("Type") != "MUMPS") return;
  if (coarsePrecisionOpen(coarse)) {
    if (bddc) coarse.sublist("MUMPS").set("Precision", std::string("Single"));
    return;
  }
  const Teuchos::ParameterEntry* e = coarse.sublist("MUMPS").getEntryPtr("Precision");
  const bool single = e->isType<std::string>() && Teuchos::getValue<std::string>(*e) == "Single";
  if (single && !bddc)
    DDC_THROW(InputError, "parameter '" << joinPath(path, "Coarse Solver/MUMPS/Precision")
                                        << "' = Single needs '" << joinPath(path, "Method")
                                        << "' = BDDC: FETI-DP's coarse solve is inside its operator F and must "
                                           "be exact (Method = Automatic may choose FETI-DP); remove the parameter "
                                           "or set Method = BDDC");
}

}  // namespace

// ---------------------------------------------------------------------------
// public API
// ---------------------------------------------------------------------------

Teuchos::RCP<const Teuchos::ParameterList> FetiDpSolver::getValidParameters() {
  static const RCP<const Teuchos::ParameterList> valid = [] {
    auto pl = rcp(new Teuchos::ParameterList("FETI-DP"));
    pl->set("Method", std::string("Automatic"),
            "What the Krylov solver iterates on: Automatic (ddcontact: BDDC in 3-D from 512 subdomains when the "
            "run has no contact pairs and the options below allow it, where it took the same time as FETI-DP within "
            "the noise, or less, doc/feti-dp.md 'BDDC'; a host code chooses by FetiDpSolver::setAutomaticMethod(); FETI-DP "
            "otherwise), FETI-DP (the Lagrange multipliers, F lambda = d) or BDDC (the "
            "displacements of the interface DOFs, S u = g, preconditioned by the same subdomain factorisations, "
            "coarse problem and Dirichlet blocks; Dohrmann 2003, the same spectrum as FETI-DP by Mandel, Dohrmann "
            "& Tezaur 2005). Its coarse solve is in the preconditioner only, so BDDC factorises the coarse "
            "matrix in single precision by default (Coarse Solver/MUMPS/Precision), for half the coarse time at "
            "the same iterations. BDDC takes no extra rows (contact, ties) and primal vertices only: it needs "
            "Preconditioner = Dirichlet, Scaling = Automatic or Multiplicity and Primal Constraints = Automatic "
            "(then Vertices) or Vertices (doc/feti-dp.md, 'BDDC').",
            enumValidator({"Automatic", "FETI-DP", "BDDC"}, "Method"));
    pl->set("Preconditioner", std::string("Dirichlet"),
            "Preconditioner of F on the LM space, M^{-1} = sum_s B_D^s S^s B_D^sT: Dirichlet (S^s = K_DD - K_DI "
            "K_II^{-1} K_ID, the Schur complement on the subdomain's dual interface DOFs with its primal DOFs fixed; "
            "one more factorisation per subdomain), Lumped (S^s ~ K_DD, cheaper, more iterations), None.",
            enumValidator(preconditionerNames(), "Preconditioner"));
    pl->set("Scaling", std::string("Automatic"),
            "Weights of B_D (doc/feti-dp.md, 'Preconditioner and scaling'). Compatibility rows: the entry of "
            "subdomain s in the row between s and t at DOF j is scaled by 1/m_j (m_j = number of subdomains "
            "sharing j) with Multiplicity and Automatic, by K^t_jj / sum_k K^k_jj with Stiffness (rho-scaling "
            "from diagonal entries, for coefficients that jump inside a body). Extra rows (contact), which join "
            "different bodies: Automatic and Stiffness weight each side (the row's entries in one connected part "
            "of a subdomain's matrix graph, e.g. one body's piece of a METIS subdomain) by the other sides' share "
            "of the row's stiffness sum_j c_j^2 K_jj (robust to a stiff body against a soft one); Multiplicity "
            "by 1/m, m = number of sides.",
            enumValidator(scalingNames(), "Scaling"));
    pl->set("Primal Constraints", std::string("Automatic"),
            "Primal (coarse) constraints besides the caller's vertex DOFs: Automatic (Vertices and Edges, with "
            "or without contact rows; ddcontact in 3-D with 512 or more subdomains: Vertices, whose coarse problem "
            "grows less; measured in doc/performance.md), Vertices (none), Vertices and Edges "
            "(plus the average of each displacement component over each edge: in 2-D a subdomain-subdomain "
            "interface, in 3-D the interface DOFs shared by >= 3 subdomains), Vertices, Edges and Faces (plus "
            "the averages over the 3-D faces, DOFs shared by exactly 2 subdomains; in 2-D the same as Vertices "
            "and Edges; in 3-D they cost more set-up and memory than the iterations they save, doc/performance.md). "
            "The constraint values (averages; rotations: 'Rotational Constraints') enter by a change of "
            "basis (doc/feti-dp.md, 'Primal constraints').",
            enumValidator([] {
              auto names = primalConstraintNames();
              names.insert(names.begin(), "Automatic");
              return names;
            }(), "Primal Constraints"));
    pl->set("Rotational Constraints", true,
            "With edges / faces: besides the average of each displacement component, make the rigid rotations of "
            "each edge / face primal (the rigid-body modes restricted to it, orthogonalised against the "
            "translations; 1 per edge in 2-D, up to 3 per edge / face in 3-D). Needs the DOF coordinates "
            "(FetiSubdomain::coordinates).");
    pl->set("Local Singularity Threshold", 1e13,
            "A subdomain's remainder stiffness K_rr whose 1-norm condition estimate (one inverse-iteration step "
            "with a pseudo-random vector) exceeds this is reported singular (insufficient primal DOFs); a direct "
            "solver may factorise a singular matrix with tiny pivots instead of failing. 0 disables the check.",
            atLeast(0.0));
    pl->set("Local Schur Complement", true,
            "Compute each S_PiPi^s as the Schur complement of a partial factorisation of K^s on its primal DOFs "
            "(MUMPS ICNTL(19)) and apply K~^{-1} by condensing onto and expanding from them (ICNTL(26)); "
            "otherwise factorise K_rr^s alone and store Phi^s = K_rr^{-1} K_rPi (a dense remainder x primal "
            "block per subdomain, np solves to build). The Schur path sets up faster in less memory, but each dual "
            "iteration makes two local-solver calls per subdomain instead of one, so a run dominated by dual "
            "iterations on small subdomains is faster with false (doc/performance.md). Only MUMPS can: CHOLMOD (the "
            "default Local Solver) and Amesos2 use Phi^s either way (doc/feti-dp.md, 'Dual problem').");
    Teuchos::ParameterList belos("Belos");
    belos.set("Solver Type", std::string("CG"),
              "Belos solver for F lambda = d (Belos::SolverFactory names): CG (symmetric tangents, the "
              "preconditioner applied as Belos left preconditioner), GMRES (nonsymmetric), MINRES (symmetric "
              "indefinite F). A solve whose coupled rows make F nonsymmetric (slipping frictional contact "
              "pairs, doc/feti-dp.md 'Coupled rows') uses GMRES whatever is chosen.",
              enumValidator(belosSolverNames(), "Solver Type"));
    belos.set("Convergence Tolerance", 1e-10,
              "Relative residual ||d - F lambda|| / ||d|| at which Belos stops (its implicit residual).",
              between(0.0, 1.0));
    belos.set("GMRES on CG Breakdown", true,
              "With Solver Type = CG: when CG breaks down on a non-positive p.F.p (F indefinite: a tangent "
              "past a limit point, e.g. a twisting contact body), solve the same system again with GMRES "
              "instead of failing (reported per solve in the solver statistics, and as a progress line).");
    belos.set("Maximum Iterations", 500, "Iteration limit; reaching it without convergence is a SolverError.",
              greaterThan(0));
    belos.set("Verbosity", 0,
              "Belos::MsgType bit mask: 0 silent, 1 Errors, 2 Warnings, 4 IterationDetails, 16 FinalSummary, "
              "32 TimingDetails, 64 StatusTestDetails (with Output Frequency > 0: the residual per iteration).",
              atLeast(0));
    // Belos takes the iteration count modulo the frequency: 0 would divide by zero.
    belos.set("Output Frequency", -1, "Print the status test every this many iterations (-1: only at the end).",
              Teuchos::rcp(new NumberValidator<int>(NumberValidator<int>::Bound{1, true}, std::nullopt, {-1})));
    // sublist(name, false, doc) keeps the doc string (set(name, list, doc) drops it).
    pl->sublist("Belos", false,
                "Dual iterations on F lambda = d (passed to Belos::SolverFactory). Besides the options below, any "
                "parameter of the chosen Belos solver (e.g. 'Num Blocks' or 'Orthogonalization' for GMRES) is "
                "accepted with the type Belos gives it and passed through.")
        .setParameters(belos);
    {
      Teuchos::ParameterList local = *DirectSolverFactory::getValidParameters();
      const Teuchos::ParameterEntry type = local.getEntry("Type");
      local.set("Type", std::string(kDefaultLocalSolver), type.docString(), type.validator());
      pl->sublist("Local Solver", false,
                  "Direct solver {Type, ...} for the subdomain matrices K_rr (or K^s with a Schur complement) and "
                  "K_II (on MPI_COMM_SELF). CHOLMOD by default: its solves cost a third of MUMPS' on subdomains "
                  "of a few thousand DOFs, where a FETI-DP run spends its time (doc/performance.md); an "
                  "indefinite subdomain matrix falls back to MUMPS.")
          .setParameters(local);
    }
    pl->sublist("Coarse Solver", false,
                "Direct solver {Type, ...} for the coarse matrix S_PiPi, distributed over all ranks (MUMPS "
                "factorises it in parallel, with Method = BDDC in single precision unless MUMPS/Precision says "
                "otherwise; FETI-DP refuses Single; Amesos2 gathers it to rank 0, because KLU2 is wrong on distributed "
                "matrices in Debian's Trilinos 13.2: doc/trilinos-notes.md).")
        .setParameters(*DirectSolverFactory::getValidParameters());
    return RCP<const Teuchos::ParameterList>(pl);
  }();
  return valid;
}

FetiDpSolver::FetiDpSolver(RCP<const Teuchos::Comm<int>> comm, Teuchos::ParameterList& params,
                           const std::string& path)
    : FetiDpSolver(std::move(comm), params, path, DirectSolverFactory::withBuiltins()) {}

FetiDpSolver::FetiDpSolver(RCP<const Teuchos::Comm<int>> comm, Teuchos::ParameterList& params,
                           const std::string& path, DirectSolverFactory solvers)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.factory = std::move(solvers);
  if (comm.is_null()) throw std::invalid_argument("FetiDpSolver: null communicator");
  m.ctx.comm = comm;
  m.ctx.mpi = rawComm(comm);
  MPI_Comm_rank(m.ctx.mpi, &m.ctx.rank);
  MPI_Comm_size(m.ctx.mpi, &m.ctx.size);
  m.ctx.path = path;
  const auto valid = getValidParameters();
  validateLevel(params, *valid, path);
  const std::string prec = params.get<std::string>("Preconditioner");
  m.prec.kind = prec == "Dirichlet" ? Preconditioner::Kind::Dirichlet
                : prec == "Lumped"  ? Preconditioner::Kind::Lumped
                                    : Preconditioner::Kind::None;
  {
    const std::string sc = params.get<std::string>("Scaling");
    m.jump.scaling = sc == "Stiffness"      ? JumpOperator::Scaling::Stiffness
                     : sc == "Multiplicity" ? JumpOperator::Scaling::Multiplicity
                                            : JumpOperator::Scaling::Automatic;
  }
  m.bddc = params.get<std::string>("Method") == "BDDC";
  m.automaticMethod = params.get<std::string>("Method") == "Automatic";
  m.bddcConflict = bddcConflict(params, path);
  if (m.bddc && !m.bddcConflict.empty()) DDC_THROW(InputError, m.bddcConflict);
  m.prec.interiorsOnly = m.bddc;
  m.dual.singularityThreshold = params.get<double>("Local Singularity Threshold");
  m.dual.localSchur = params.get<bool>("Local Schur Complement");
  m.automaticPrimal = params.get<std::string>("Primal Constraints") == "Automatic";
  m.primalChoice = m.automaticPrimal ? (m.bddc ? PrimalConstraints::Vertices : PrimalConstraints::VerticesAndEdges)
                                     : primalConstraintsFromName(params.get<std::string>("Primal Constraints"));
  m.rotations = params.get<bool>("Rotational Constraints");
  // Belos: the entries documented here are validated with their ranges;
  // any other entry must be a parameter of the chosen Belos solver (its
  // getValidParameters(), same type) and is passed through to it.
  Teuchos::ParameterList& belos = params.sublist("Belos");
  {
    const Teuchos::ParameterList& validBelos = valid->sublist("Belos");
    const std::string where = joinPath(path, "Belos");
    Teuchos::ParameterList ours("Belos");
    m.belosExtra = Teuchos::ParameterList("Belos");
    for (auto it = belos.begin(); it != belos.end(); ++it)
      (validBelos.isParameter(belos.name(it)) ? ours : m.belosExtra).setEntry(belos.name(it), belos.entry(it));
    validateLevel(ours, validBelos, where);
    belos.setParameters(ours);  // defaults filled in
    const std::string type = ours.get<std::string>("Solver Type");
    const auto belosValid =
        Belos::SolverFactory<Scalar, MultiVector, Operator>().create(type, Teuchos::parameterList())->getValidParameters();
    std::vector<std::string> names;
    for (auto it = validBelos.begin(); it != validBelos.end(); ++it) names.push_back(validBelos.name(it));
    for (auto it = belosValid->begin(); it != belosValid->end(); ++it)
      if (!validBelos.isParameter(belosValid->name(it))) names.push_back(belosValid->name(it));
    for (auto it = m.belosExtra.begin(); it != m.belosExtra.end(); ++it) {
      const std::string& name = m.belosExtra.name(it);
      const Teuchos::ParameterEntry& e = m.belosExtra.entry(it);
      if (!belosValid->isParameter(name))
        DDC_THROW(InputError, "parameter '" << joinPath(where, name) << "' is neither a FETI-DP Belos option nor a "
                                            << "parameter of Belos' " << type << " solver; valid names: "
                                            << quotedNames(names));
      const Teuchos::ParameterEntry& v = belosValid->getEntry(name);
      if (e.isList() != v.isList() || (!e.isList() && e.getAny(false).type() != v.getAny(false).type()))
        DDC_THROW(InputError, "parameter '" << joinPath(where, name) << "' must be of type "
                                            << v.getAny(false).typeName() << " (Belos' " << type << " solver), got "
                                            << e.getAny(false).typeName());
    }
  }
  m.belosType = belos.get<std::string>("Solver Type");
  m.belosGmresOnBreakdown = belos.get<bool>("GMRES on CG Breakdown");
  m.belosTol = m.solveTol = belos.get<double>("Convergence Tolerance");
  m.belosMaxIt = belos.get<int>("Maximum Iterations");
  m.belosVerbosity = belos.get<int>("Verbosity");
  m.belosOutputFrequency = belos.get<int>("Output Frequency");
  // Creating a solver validates the sublist (unknown Type, misspelt options)
  // now rather than at the first numeric(). A host's own factory without
  // CHOLMOD keeps the factory's default.
  {
    Teuchos::ParameterList& local = params.sublist("Local Solver");
    const auto known = m.factory.names();
    if (!local.isParameter("Type") && std::count(known.begin(), known.end(), kDefaultLocalSolver))
      local.set("Type", std::string(kDefaultLocalSolver));
  }
  m.factory.create(params.sublist("Local Solver"), joinPath(path, "Local Solver"));
  m.coarsePrecisionOpen = coarsePrecisionOpen(params.sublist("Coarse Solver"));
  chooseCoarsePrecision(params.sublist("Coarse Solver"), path, m.bddc);
  m.factory.create(params.sublist("Coarse Solver"), joinPath(path, "Coarse Solver"));
  m.factory.requireDistributable(params.sublist("Coarse Solver"), joinPath(path, "Coarse Solver"), comm->getSize());
  m.localSolverParams = params.sublist("Local Solver");
  m.coarseSolverParams = params.sublist("Coarse Solver");
}

FetiDpSolver::~FetiDpSolver() = default;

void FetiDpSolver::setTopology(std::vector<FetiSubdomain> local, RCP<const Map> ownedMap) {
  impl_->buildTopology(std::move(local), std::move(ownedMap));
}

void FetiDpSolver::numeric() {
  Impl& m = *impl_;
  if (!m.haveTopology) throw std::logic_error("FetiDpSolver::numeric() called before setTopology()");
  m.factored = false;
  m.couplingScaled = false;
  const double t0 = MPI_Wtime();
  Info& st = m.setup;
  st = Info{};

  // 1. Subdomain factorisations (values refreshed first, K^ = T^T K T too).
  std::string msg;
  for (size_t ls = 0; ls < m.subs.size() && msg.empty(); ++ls) msg = m.dual.factor(m.ctx, m.subs[ls], ls, m.analysed);
  const double t1 = MPI_Wtime();
  st.localFactorSeconds = t1 - t0;
  raiseCollectively<SolverError>(m.ctx.mpi, msg);
  {
    int mm[2] = {INT_MAX, 0};  // min, -max
    for (const auto& s : m.subs) mm[0] = std::min(mm[0], s.factorizations), mm[1] = std::min(mm[1], -s.factorizations);
    int g[2];
    MPI_Allreduce(mm, g, 2, MPI_INT, MPI_MIN, m.ctx.mpi);
    st.minLocalFactorizations = g[0] == INT_MAX ? 0 : g[0];
    st.maxLocalFactorizations = -g[1];
  }

  // 2. The weights of B_D read the new diagonals; the Dirichlet blocks.
  m.jump.computeWeights(m.ctx, m.subs);
  m.prec.factor(m.ctx, m.subs, m.analysed);
  if (m.bddc) m.iface.refresh(m.subs);
  const double t2 = MPI_Wtime();
  st.dirichletFactorSeconds = t2 - t1;

  // 3. The coarse problem from the S_PiPi^s.
  {
    std::vector<std::vector<double>> S(m.subs.size());
    for (size_t ls = 0; ls < m.subs.size(); ++ls) S[ls].swap(m.dual.local[ls].S);
    m.coarse.assembleAndFactor(m.ctx, S, m.analysed);
  }
  const double t3 = MPI_Wtime();
  st.coarseFactorSeconds = t3 - t2;
  st.setupSeconds = t3 - t0;
  double loc[4] = {st.localFactorSeconds, st.dirichletFactorSeconds, st.coarseFactorSeconds, st.setupSeconds};
  double glob[4];
  MPI_Allreduce(loc, glob, 4, MPI_DOUBLE, MPI_MAX, m.ctx.mpi);
  st.localFactorSeconds = glob[0];
  st.dirichletFactorSeconds = glob[1];
  st.coarseFactorSeconds = glob[2];
  st.setupSeconds = glob[3];
  m.analysed = true;
  m.factored = true;
}

double FetiDpSolver::convergenceTolerance() const { return impl_->belosTol; }

void FetiDpSolver::setSolveTolerance(double tol) {
  if (!(tol >= impl_->belosTol && tol < 1.0))
    throw std::invalid_argument("FetiDpSolver::setSolveTolerance(" + std::to_string(tol) + "): expected a value in [" +
                                std::to_string(impl_->belosTol) + " (" + impl_->param("Belos/Convergence Tolerance") +
                                "), 1)");
  impl_->solveTol = tol;
}

namespace {

using Impl = FetiDpSolver::Impl;

/// b and u are on the owned DOF map, and b is zero on DOFs of no subdomain
/// (collective).
void checkSolveVectors(const Impl& m, const Vector& b, const Vector& u) {
  const bool sameMaps = b.getMap()->isSameAs(*m.ctx.ownedMap) && u.getMap()->isSameAs(*m.ctx.ownedMap);
  if (!sameMaps) throw std::invalid_argument("FetiDpSolver::solve: b and u must be on the owned DOF map");
  auto bv = b.getData();
  std::string msg;
  for (LO l = 0; l < LO(bv.size()); ++l)
    if (m.ctx.ownedMult[l] == 0 && bv[l] != 0.0) {
      std::ostringstream os;
      os << "FetiDpSolver::solve: b = " << bv[l] << " on DOF " << m.ctx.ownedMap->getGlobalElement(l)
         << ", which belongs to no subdomain";
      msg = os.str();
      break;
    }
  raiseCollectively<std::invalid_argument>(m.ctx.mpi, msg);
}

}  // namespace

/// f~ of each subdomain into DualOperator::local[].fr, fp: interior DOFs as
/// is, dual copies b_j / m_j; the primal DOFs are assembled directly into the
/// coarse right-hand side (primalForces()). With edge/face constraints, f^s =
/// T^T (b_j / m_j): the constraint DOFs get their share in f_Pi^s, summed over
/// the subdomains by the coarse assembly.
void Impl::loadForces(const Vector& b) {
  dofOvWork->doImport(b, *ctx.dofImport, Tpetra::INSERT);
  loadOverlapForces(*dofOvWork);
}

/// loadForces() from b already imported to Context::dofOvMap.
void Impl::loadOverlapForces(const Vector& bOv) {
  auto bo = bOv.getData();
  std::vector<double> f;
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    const Subdomain& s = subs[ls];
    LocalProblem& lp = dual.local[ls];
    std::fill(lp.fp.begin(), lp.fp.end(), 0.0);
    if (s.cob.active()) {
      f.resize(s.n);
      for (LO k = 0; k < s.n; ++k) f[k] = bo[s.ovLid[k]] * s.invMult[k];
      s.cob.forceToNew(f);
      for (LO r = 0; r < s.nr; ++r) lp.fr[r] = f[s.rDof[r]];
      for (LO p = 0; p < s.np; ++p)
        if (s.cob.holdsConstraint(s.pDof[p])) lp.fp[p] = f[s.pDof[p]];
    } else {
      for (LO r = 0; r < s.nr; ++r) lp.fr[r] = bo[s.ovLid[s.rDof[r]]] * s.invMult[s.rDof[r]];
    }
  }
}

/// The coarse right-hand side of the primal vertex DOFs: b at their owners
/// (zero at edge/face constraint values).
void Impl::primalForces(const Vector& b, Vector& fPi) const {
  auto bv = b.getData();
  auto f = fPi.getDataNonConst();
  for (size_t k = 0; k < coarse.ownedLid.size(); ++k) f[k] = coarse.isEdgeFace[k] ? 0.0 : bv[coarse.ownedLid[k]];
}

/// x from A x = rhs by Belos (CG, then GMRES if CG breaks down on an
/// indefinite A and that is allowed; GMRES for a nonsymmetric A); adds the
/// iterations, residual and condition estimate to `info`. \throws
/// SolverError naming `system` if it does not converge.
void Impl::solveByBelos(const RCP<Operator>& A, const RCP<Operator>& M, const RCP<MultiVector>& rhs,
                        const RCP<MultiVector>& x, bool symmetric, const std::string& system,
                        FetiDpSolver::Info& info) {
  Belos::SolverFactory<Scalar, MultiVector, Operator> factory;
  auto bp = Teuchos::parameterList();
  bp->set("Convergence Tolerance", solveTol);
  bp->set("Maximum Iterations", belosMaxIt);
  bp->set("Verbosity", belosVerbosity);
  bp->set("Output Frequency", belosOutputFrequency);
  bp->setParameters(belosExtra);
  Belos::ReturnType ret = Belos::Unconverged;
  std::string failure, type = belosType;
  // Coupled rows with T != Gᵀ make F nonsymmetric: CG and MINRES do not apply.
  if (!symmetric && type != "GMRES") {
    type = "GMRES";
    info.gmresForCoupledRows = true;
  }
  auto run = [&] {
    x->putScalar(0.0);
    info.conditionEstimate = -1.0;  // from CG only, and from the last run
    auto solver = factory.create(type, bp);
    auto problem = rcp(new Belos::LinearProblem<Scalar, MultiVector, Operator>(A, x, rhs));
    if (!M.is_null()) problem->setLeftPrec(M);
    problem->setProblem();
    solver->setProblem(problem);
    failure.clear();
    try {
      ret = solver->solve();
    } catch (const std::exception& e) {
      failure = e.what();
    }
    info.iterations += solver->getNumIters();
    if (auto cg = Teuchos::rcp_dynamic_cast<Belos::PseudoBlockCGSolMgr<Scalar, MultiVector, Operator>>(solver))
      info.conditionEstimate = cg->getConditionEstimate();
    try {
      info.relativeResidual = solver->achievedTol();
    } catch (const std::exception&) {
      info.relativeResidual = -1.0;
    }
  };
  run();
  // CG needs A positive definite; an indefinite tangent (past a limit
  // point) makes it break down on p.A.p <= 0. GMRES does not need it.
  if (type == "CG" && belosGmresOnBreakdown && failure.find("non-positive value for p^H*A*p") != std::string::npos) {
    type = "GMRES";
    info.gmresAfterBreakdown = true;
    run();
  }
  if (!failure.empty() || ret != Belos::Converged) {
    std::ostringstream os;
    os << (bddc ? "BDDC" : "FETI-DP") << ": Belos " << type << " did not converge on " << system << ": "
       << info.iterations << " iterations, achieved relative residual " << std::scientific << info.relativeResidual
       << ", tolerance " << solveTol;
    if (!failure.empty()) os << "; Belos reported: " << failure;
    os << ". Raise '" << param("Belos/Maximum Iterations") << "' (" << belosMaxIt << "), loosen '"
       << param("Belos/Convergence Tolerance") << "', or change '" << param("Preconditioner") << "' / '"
       << param("Belos/Solver Type") << "'";
    throw SolverError(os.str());
  }
}

/// Assemble u from the subdomain solutions (DualOperator::local[].xr, up)
/// and the coarse solution: copies of dual DOFs averaged (weights 1/m_j),
/// vertex DOFs from the coarse solution. With edge/face constraints, u^s =
/// T û^s first; the DOFs that held constraint values are then averaged like
/// dual DOFs.
void Impl::assembleDisplacement(Vector& u) {
  dofOvWork->putScalar(0.0);
  {
    auto uo = dofOvWork->getDataNonConst();
    std::vector<double> us;
    for (size_t ls = 0; ls < subs.size(); ++ls) {
      const Subdomain& s = subs[ls];
      const LocalProblem& lp = dual.local[ls];
      if (!s.cob.active()) {
        for (LO r = 0; r < s.nr; ++r) uo[s.ovLid[s.rDof[r]]] += lp.xr[r] * s.invMult[s.rDof[r]];
        continue;
      }
      us.assign(s.n, 0.0);
      for (LO r = 0; r < s.nr; ++r) us[s.rDof[r]] = lp.xr[r];
      for (LO p = 0; p < s.np; ++p) us[s.pDof[p]] = lp.up[p];
      s.cob.displacementToOld(us);
      for (LO k = 0; k < s.n; ++k)
        if (s.rIdx[k] != kNone || s.cob.holdsConstraint(k)) uo[s.ovLid[k]] += us[k] * s.invMult[k];
    }
  }
  u.putScalar(0.0);
  u.doExport(*dofOvWork, *ctx.dofExport, Tpetra::ADD);
  if (coarse.n > 0) {
    auto uv = u.getDataNonConst();
    auto c = coarse.sol->getData();
    for (size_t k = 0; k < coarse.ownedLid.size(); ++k)
      if (!coarse.isEdgeFace[k]) uv[coarse.ownedLid[k]] = c[k];
  }
}

/// u from b by the dual problem F lambda = d (doc/feti-dp.md "The dual
/// problem"); the Belos iterations into `info`. Returns Belos' seconds.
double Impl::solveDual(const Vector& b, Vector& u, FetiDpSolver::Info& info) {
  std::vector<std::vector<double>> frBase(subs.size()), fpBase(subs.size());
  loadForces(b);
  for (size_t ls = 0; ls < subs.size(); ++ls) frBase[ls] = dual.local[ls].fr, fpBase[ls] = dual.local[ls].fp;
  Vector fPi(coarse.map);
  primalForces(b, fPi);

  // d = B K~^{-1} f~ (the compatibility constraints have zero right-hand side)
  auto d = rcp(new MultiVector(jump.lmMap, 1));
  auto lambda = rcp(new MultiVector(jump.lmMap, 1));
  dual.applyKtildeInv(subs, coarse, &fPi);
  dual.gatherB(jump, *d->getVectorNonConst(0));
  // d = G B K~^{-1} f~ - c (G = P without coupled rows; c = 0 on inactive rows)
  jump.equations(*d->getVectorNonConst(0), nullptr);
  d->getVectorNonConst(0)->update(-1.0, *jump.rhs, 1.0);
  if (!couplingScaled) scaleCompliantRows(), couplingScaled = true;

  double dNorm = 0.0;
  {
    Teuchos::Array<double> n(1);
    d->norm2(n());
    dNorm = n[0];
  }
  const double tb0 = MPI_Wtime();
  if (jump.lmMap->getGlobalNumElements() > 0 && dNorm > 0.0) {
    std::ostringstream system;
    system << "F lambda = d (" << jump.lmMap->getGlobalNumElements() << " Lagrange multipliers)";
    solveByBelos(fOp, mOp, d, lambda, jump.coupling.symmetric, system.str(), info);
  }
  const double tb1 = MPI_Wtime();

  // The multipliers T x (restrained rows exactly zero)
  jump.multipliers(*lambda->getVector(0), *jump.lastLambda);

  // u = K~^{-1} (f~ - B^T lambda)
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    dual.local[ls].fr = frBase[ls];
    dual.local[ls].fp = fpBase[ls];
  }
  dual.scatterBt(jump, *jump.lastLambda, -1.0);
  dual.applyKtildeInv(subs, coarse, &fPi);
  assembleDisplacement(u);
  return tb1 - tb0;
}

FetiDpSolver::Info FetiDpSolver::solve(const Vector& b, Vector& u) {
  Impl& m = *impl_;
  if (!m.factored) throw std::logic_error("FetiDpSolver::solve() called without a successful numeric()");
  const double t0 = MPI_Wtime();
  m.dual.tLocalSolve = m.coarse.tSolve = m.prec.tApply = m.prec.tDirichletSolve = 0.0;
  m.dual.nApply = m.prec.nApply = m.iface.nApply = 0;
  Info info = m.setup;
  if (!m.jump.weightsCurrent) m.jump.computeWeights(m.ctx, m.subs);
  checkSolveVectors(m, b, u);
  const double belos = m.bddc ? m.solveBddc(b, u, info) : m.solveDual(b, u, info);

  const double t1 = MPI_Wtime();
  double loc[5] = {t1 - t0, belos, m.dual.tLocalSolve, m.coarse.tSolve, m.prec.tApply};
  double glob[5];
  MPI_Allreduce(loc, glob, 5, MPI_DOUBLE, MPI_MAX, m.ctx.mpi);
  info.solveSeconds = glob[0];
  info.belosSeconds = glob[1];
  info.localSolveSeconds = glob[2];
  info.coarseSolveSeconds = glob[3];
  info.preconditionerSeconds = glob[4];
  info.operatorApplications = m.bddc ? m.iface.nApply : m.dual.nApply;
  info.preconditionerApplications = m.prec.nApply;
  return info;
}

void FetiDpSolver::setConstraintRows(Teuchos::RCP<const Map> rowMap,
                                     const std::vector<std::vector<ConstraintEntry>>& entries) {
  Impl& m = *impl_;
  if (!m.haveTopology) throw std::logic_error("FetiDpSolver::setConstraintRows() called before setTopology()");
  std::string msg;
  if (rowMap.is_null() || rowMap->getComm()->getSize() != m.ctx.size || !rowMap->isOneToOne())
    msg = "FetiDpSolver::setConstraintRows: the row map must be a one-to-one map on the solver's communicator";
  else if (entries.size() != m.subs.size())
    msg = "FetiDpSolver::setConstraintRows: one entry list per local subdomain (" + std::to_string(m.subs.size()) +
          "), got " + std::to_string(entries.size());
  for (size_t ls = 0; ls < entries.size() && msg.empty(); ++ls)
    for (const auto& e : entries[ls])
      if (e.dof < 0 || e.dof >= m.subs[ls].n || !std::isfinite(e.coef)) {
        std::ostringstream os;
        os << "FetiDpSolver::setConstraintRows: subdomain " << m.subs[ls].id << ": entry (row " << e.row << ", DOF "
           << e.dof << ", coefficient " << e.coef << ") has a local DOF outside 0.." << m.subs[ls].n - 1
           << " or a non-finite coefficient";
        msg = os.str();
        break;
      }
  raiseCollectively<std::invalid_argument>(m.ctx.mpi, msg);
  if (m.bddc && rowMap->getGlobalNumElements() > 0)
    DDC_THROW(InputError, "FetiDpSolver::setConstraintRows: '" << m.param("Method")
                              << "' = BDDC takes no extra rows (contact, ties); use FETI-DP");

  // With edge/face constraints the rows act on û: c^T u = (c^T T) û, row by row.
  std::vector<std::vector<ConstraintEntry>> transformed;
  const std::vector<std::vector<ConstraintEntry>>* use = &entries;
  bool anyActive = false;
  for (const auto& s : m.subs) anyActive = anyActive || s.cob.active();
  if (anyActive) {
    transformed.resize(entries.size());
    for (size_t ls = 0; ls < entries.size(); ++ls) {
      if (!m.subs[ls].cob.active()) {
        transformed[ls] = entries[ls];
        continue;
      }
      std::map<GO, std::vector<std::pair<LO, double>>> rows;
      for (const auto& e : entries[ls]) rows[e.row].emplace_back(e.dof, e.coef);
      for (const auto& [row, list] : rows)
        for (const auto& [dof, coef] : m.subs[ls].cob.rowToNew(list))
          transformed[ls].push_back(ConstraintEntry{row, dof, coef});
    }
    use = &transformed;
  }

  // Extra row GIDs: nCompat + (rows of lower ranks) + LID in rowMap.
  long long mine = static_cast<long long>(rowMap->getNodeNumElements());
  std::vector<long long> counts(m.ctx.size), offsets(m.ctx.size, 0);
  MPI_Allgather(&mine, 1, MPI_LONG_LONG, counts.data(), 1, MPI_LONG_LONG, m.ctx.mpi);
  for (int r = 1; r < m.ctx.size; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  // The LM GID of every row the caller named (-1: not in the row map); the
  // rows in the new basis are the same rows.
  std::map<GO, GO> lmOf;
  {
    std::vector<GO> rows;
    for (const auto& list : entries)
      for (const auto& e : list) rows.push_back(e.row);
    std::vector<int> pids;
    std::vector<LO> lids;
    owners(*rowMap, rows, pids, lids);
    for (size_t k = 0; k < rows.size(); ++k) lmOf[rows[k]] = pids[k] < 0 ? -1 : m.jump.nCompat + offsets[pids[k]] + lids[k];
  }
  for (size_t ls = 0; ls < entries.size(); ++ls) {
    m.jump.rows[ls].extraUser.clear();
    for (const auto& e : entries[ls])
      if (lmOf[e.row] >= 0) m.jump.rows[ls].extraUser.push_back(JumpOperator::GidEntry{lmOf[e.row], e.dof, e.coef});
  }
  std::vector<std::vector<JumpOperator::GidEntry>> rowsNew(use->size());
  for (size_t ls = 0; ls < use->size(); ++ls)
    for (const ConstraintEntry& e : (*use)[ls]) {
      const GO lm = lmOf[e.row];
      if (lm < 0) {
        if (msg.empty()) msg = "FetiDpSolver::setConstraintRows: row " + std::to_string(e.row) + " (subdomain " +
                               std::to_string(m.subs[ls].id) + ") is not in the row map";
        continue;
      }
      rowsNew[ls].push_back(JumpOperator::GidEntry{lm, e.dof, e.coef});
    }
  raiseCollectively<std::invalid_argument>(m.ctx.mpi, msg);
  msg = m.jump.distributeExtra(m.ctx, m.subs, rowsNew);
  raiseCollectively<std::invalid_argument>(m.ctx.mpi, msg);
  m.jump.extraRowMap = rowMap;
  m.jump.extraOffset = offsets[m.ctx.rank];
  // The rows are constraint rows only: the factorisations stay valid (a
  // linear material is factorised once per analysis, doc/feti-dp.md "Extra
  // rows"); finalize() marks the weights of B_D for the next solve().
  m.jump.finalize(m.ctx, m.subs);
}

void FetiDpSolver::setConstraintState(const std::vector<char>& active, const std::vector<double>& rhs) {
  Impl& m = *impl_;
  const size_t n = m.jump.extraRowMap.is_null() ? 0 : m.jump.extraRowMap->getNodeNumElements();
  std::string msg;
  if (active.size() != n || rhs.size() != n)
    msg = "FetiDpSolver::setConstraintState: one active flag and one right-hand side per owned row of the row map (" +
          std::to_string(n) + ")";
  raiseCollectively<std::invalid_argument>(m.ctx.mpi, msg);
  if (n == 0 && m.jump.extraRowMap.is_null()) return;
  m.jump.coupling = RowCoupling();
  m.couplingScaled = false;
  m.jump.mask = rcp(new Vector(m.jump.lmMap));
  m.jump.mask->putScalar(1.0);
  m.jump.rhs->putScalar(0.0);
  auto mk = m.jump.mask->getDataNonConst();
  auto c = m.jump.rhs->getDataNonConst();
  auto cnt = m.jump.rowEntries->getData();
  for (size_t k = 0; k < n; ++k) {
    const size_t l = size_t(m.jump.nCompatOwned) + k;
    mk[l] = active[k] ? 1.0 : 0.0;
    c[l] = active[k] ? rhs[k] : 0.0;
    if (active[k] && cnt[l] == 0.0 && msg.empty())
      msg = "FETI-DP: constraint row " + std::to_string(m.jump.extraRowMap->getGlobalElement(LO(k))) +
            " is active but has no entry on a free DOF of any subdomain (all its DOFs are prescribed), so it "
            "cannot be enforced";
  }
  raiseCollectively<SolverError>(m.ctx.mpi, msg);
}

Teuchos::RCP<const Vector> FetiDpSolver::constraintMultipliers() const {
  const Impl& m = *impl_;
  if (m.jump.extraRowMap.is_null()) return Teuchos::null;
  auto out = rcp(new Vector(m.jump.extraRowMap));
  auto o = out->getDataNonConst();
  auto l = m.jump.lastLambda->getData();
  for (size_t k = 0; k < o.size(); ++k) o[k] = l[size_t(m.jump.nCompatOwned) + k];
  return out;
}

const FetiDpSolver::Info& FetiDpSolver::setupInfo() const { return impl_->setup; }

Teuchos::RCP<const Map> FetiDpSolver::lmMap() const { return impl_->jump.lmMap; }
Teuchos::RCP<const Map> FetiDpSolver::primalMap() const { return impl_->coarse.primalMap; }
GO FetiDpSolver::numDualDofs() const { return impl_->jump.nDual; }
GO FetiDpSolver::numEdgeFaceConstraints() const { return impl_->coarse.nEdgeFace; }

void FetiDpSolver::setAutomaticPrimalConstraints(PrimalConstraints choice) {
  if (impl_->automaticPrimal && !impl_->bddc) impl_->primalChoice = choice;
}

bool FetiDpSolver::setAutomaticMethod(bool bddc) {
  Impl& m = *impl_;
  if (m.haveTopology) throw std::logic_error("FetiDpSolver::setAutomaticMethod() called after setTopology()");
  if (!m.automaticMethod || !bddc || !m.bddcConflict.empty()) return m.bddc;
  m.bddc = true;
  m.prec.interiorsOnly = true;
  if (m.automaticPrimal) m.primalChoice = PrimalConstraints::Vertices;
  if (m.coarsePrecisionOpen) m.coarseSolverParams.sublist("MUMPS").set("Precision", std::string("Single"));
  return true;
}

bool FetiDpSolver::usesBddc() const { return impl_->bddc; }

PrimalConstraints FetiDpSolver::primalConstraints() const { return impl_->primalChoice; }

Teuchos::RCP<Vector> FetiDpSolver::applyB(const std::vector<std::vector<double>>& field) const {
  Impl& m = *impl_;
  if (!m.haveTopology) throw std::logic_error("FetiDpSolver::applyB() called before setTopology()");
  bool bad = field.size() != m.subs.size();
  for (size_t ls = 0; !bad && ls < field.size(); ++ls) bad = field[ls].size() != size_t(m.subs[ls].n);
  if (bad) throw std::invalid_argument("FetiDpSolver::applyB: one value per local DOF of each local subdomain");
  for (size_t ls = 0; ls < field.size(); ++ls) {
    const Subdomain& s = m.subs[ls];
    LocalProblem& lp = m.dual.local[ls];
    std::vector<double> f(field[ls]);
    s.cob.displacementToNew(f);  // B acts on û
    for (LO r = 0; r < s.nr; ++r) lp.xr[r] = f[s.rDof[r]];
    for (LO p = 0; p < s.np; ++p) lp.up[p] = f[s.pDof[p]];
  }
  auto y = rcp(new Vector(m.jump.lmMap));
  m.dual.gatherB(m.jump, *y);
  return y;
}

Teuchos::RCP<const Tpetra::Operator<Scalar, LO, GO, Node>> FetiDpSolver::fOperator() const { return impl_->fOp; }
Teuchos::RCP<const Tpetra::Operator<Scalar, LO, GO, Node>> FetiDpSolver::preconditioner() const {
  return impl_->mOp;
}

}  // namespace ddc
