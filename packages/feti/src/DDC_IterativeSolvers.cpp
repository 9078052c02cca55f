// Common part of the monolithic iterative solvers ("Belos-MueLu",
// "Belos-FROSch"): parameters, coordinates -> near-null space, the Belos
// solve and its convergence check, factory registration. The
// preconditioners are in DDC_MueLuSolver.cpp and DDC_FroschSolver.cpp.
#include "DDC_IterativeSolvers.hpp"

#include <mpi.h>

#include <BelosLinearProblem.hpp>
#include <BelosPseudoBlockCGSolMgr.hpp>
#include <BelosPseudoBlockGmresSolMgr.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

using Operator = IterativeSolver::Operator;

constexpr const char* kRigidBodyModes = "Rigid Body Modes";
constexpr const char* kTranslations = "Translations";

/// Accepted ratio of the explicit residual ||b - A x|| / ||b|| to Belos's
/// tolerance. Belos stops on its recursively updated residual, which differs
/// from the true one by O(eps * cond(A)): for stiff elasticity matrices with
/// cond(A) ~ 1e6 that is ~1e-10, the default tolerance itself (MUMPS reaches
/// 5e-11 on the test cantilever). A factor 10 absorbs this, while a
/// preconditioner that is not a fixed linear operator (e.g. a wrong parallel
/// coarse solve) leaves a gap of orders of magnitude.
constexpr double kExplicitResidualSlack = 10.0;

bool anyRank(const Teuchos::Comm<int>& comm, bool bad) {
  int l = bad ? 1 : 0, g = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, l, Teuchos::outArg(g));
  return g != 0;
}

/// Check the node-major two-DOFs-per-node layout of `map` (file comment of
/// the header) on every rank; all ranks throw if one fails.
void requireNodeMajorLayout(const Map& map, const std::string& who) {
  const LO n = static_cast<LO>(map.getNodeNumElements());
  std::string why;
  if (n % 2 != 0) {
    why =
        "rank " + std::to_string(map.getComm()->getRank()) + " owns an odd number of rows (" + std::to_string(n) + ")";
  } else {
    for (LO p = 0; p < n; p += 2) {
      const GO g = map.getGlobalElement(p);
      if (g % 2 != 0 || map.getGlobalElement(p + 1) != g + 1) {
        why = "rows " + std::to_string(p) + ", " + std::to_string(p + 1) + " of rank " +
              std::to_string(map.getComm()->getRank()) + " have global indices " + std::to_string(g) + ", " +
              std::to_string(map.getGlobalElement(p + 1)) + " (expected 2k, 2k+1)";
        break;
      }
    }
  }
  if (anyRank(*map.getComm(), !why.empty()))
    throw std::invalid_argument(who +
                                ": the matrix must number its DOFs node-major, two per node (global indices "
                                "2k, 2k+1 for node k, owned by the same rank)" +
                                (why.empty() ? std::string(" on every rank") : "; " + why));
}

}  // namespace

struct IterativeSolver::Impl {
  double tol = 1e-10;
  int maxIters = 1000;
  std::string belosSolver;  // "CG" or "GMRES"
  bool rigidBodyModes = true;
  Teuchos::RCP<const MultiVector> coords;
  Teuchos::RCP<Operator> prec;
  bool fresh = true;  // symbolic() called since the last successful numeric()
  bool ready = false;
  int iterations = 0;
  double residual = 0.0;
  int nNumeric = 0;
};

void IterativeSolver::addCommonParameters(Teuchos::ParameterList& pl, const std::string& solverDoc) {
  pl.set("Convergence Tolerance", 1e-10,
         "Stop when ||b - A x|| / ||b|| <= this (x starts from 0). " + solverDoc +
             " solve() throws SolverError if a right-hand side does not get there.",
         between(0.0, 1.0, Interval::Open));
  pl.set("Maximum Iterations", 1000, "Most Belos iterations per solve() before it throws SolverError.",
         greaterThan(0));
  pl.set("Verbosity", 0,
         "0: silent; 1: Belos final summary and the preconditioner's setup summary; 2: also the residual "
         "of every iteration (rank 0 prints).",
         between(0, 2));
  pl.set("Null Space", std::string(kRigidBodyModes),
         "Near-null space the preconditioner's coarse space reproduces. 'Rigid Body Modes': the 3 rigid-body "
         "modes of 2-D elasticity from the nodal coordinates of setCoordinates() (required before numeric()); "
         "'Translations': the 2 translations only (no coordinates needed; weaker for elasticity).",
         enumValidator({kRigidBodyModes, kTranslations}, "Null Space"));
}

IterativeSolver::IterativeSolver(const Teuchos::ParameterList& params, const std::string& type,
                                 const std::string& belosSolver)
    : type_(type), impl_(std::make_unique<Impl>()) {
  // `params` was validated by the subclass (validateLevel filled the defaults).
  impl_->belosSolver = belosSolver;
  impl_->tol = params.get<double>("Convergence Tolerance");
  impl_->maxIters = params.get<int>("Maximum Iterations");
  verbosity_ = params.get<int>("Verbosity");
  impl_->rigidBodyModes = params.get<std::string>("Null Space") == kRigidBodyModes;
}

IterativeSolver::~IterativeSolver() = default;

void IterativeSolver::setCoordinates(const Teuchos::RCP<const MultiVector>& coords) {
  if (!coords.is_null() && coords->getNumVectors() != 2)
    throw std::invalid_argument(type_ + " setCoordinates(): need 2 columns (x, y), got " +
                                std::to_string(coords->getNumVectors()));
  impl_->coords = coords;
}

int IterativeSolver::lastIterations() const { return impl_->iterations; }
double IterativeSolver::lastResidual() const { return impl_->residual; }
int IterativeSolver::numNumeric() const { return impl_->nNumeric; }

Teuchos::RCP<MultiVector> IterativeSolver::translations2D(const Teuchos::RCP<const Map>& map) {
  requireNodeMajorLayout(*map, "translations2D");
  auto ns = Teuchos::rcp(new MultiVector(map, 2));
  auto tx = ns->getDataNonConst(0), ty = ns->getDataNonConst(1);
  for (LO i = 0; i < LO(map->getNodeNumElements()); ++i) (i % 2 == 0 ? tx : ty)[i] = 1.0;
  return ns;
}

Teuchos::RCP<MultiVector> IterativeSolver::rigidBodyModes2D(const MultiVector& coords) {
  const auto map = coords.getMap();
  requireNodeMajorLayout(*map, "rigidBodyModes2D");
  if (coords.getNumVectors() != 2)
    throw std::invalid_argument("rigidBodyModes2D: need 2 coordinate columns, got " +
                                std::to_string(coords.getNumVectors()));
  // Centre of the nodes: mean over the x-DOF rows (each node counted once).
  const LO n = static_cast<LO>(map->getNodeNumElements());
  auto x = coords.getData(0), y = coords.getData(1);
  double local[3] = {0.0, 0.0, double(n / 2)}, global[3];
  for (LO i = 0; i < n; i += 2) local[0] += x[i], local[1] += y[i];
  Teuchos::reduceAll(*map->getComm(), Teuchos::REDUCE_SUM, 3, local, global);
  const double xc = global[2] > 0 ? global[0] / global[2] : 0.0;
  const double yc = global[2] > 0 ? global[1] / global[2] : 0.0;

  auto out = Teuchos::rcp(new MultiVector(map, 3));
  {
    auto t0 = out->getDataNonConst(0), t1 = out->getDataNonConst(1), rot = out->getDataNonConst(2);
    for (LO i = 0; i < n; i += 2) {
      // u = omega x (X - Xc) for a unit rotation about the z axis.
      t0[i] = 1.0, t1[i + 1] = 1.0;
      rot[i] = -(y[i] - yc);
      rot[i + 1] = x[i] - xc;
    }
  }
  return out;
}

void IterativeSolver::symbolic(const Teuchos::RCP<const CrsMatrix>& A) {
  if (A.is_null()) throw std::invalid_argument(type_ + " symbolic(): null matrix");
  if (!A->isFillComplete()) throw std::invalid_argument(type_ + " symbolic(): matrix is not fill-complete");
  const auto rowMap = A->getRowMap();
  if (!rowMap->isSameAs(*A->getRangeMap()) || !rowMap->isSameAs(*A->getDomainMap()))
    throw std::invalid_argument(type_ + " symbolic(): row, range and domain maps must be the same");
  A_ = A;
  impl_->prec = Teuchos::null;
  impl_->fresh = true;
  impl_->ready = false;
}

void IterativeSolver::numeric() {
  Impl& m = *impl_;
  if (A_.is_null()) throw std::logic_error(type_ + " numeric(): call symbolic() first");
  const auto map = A_->getRowMap();
  requireNodeMajorLayout(*map, type_);
  m.ready = false;

  Teuchos::RCP<MultiVector> nullSpace, nodeCoords;
  if (m.rigidBodyModes) {
    DDC_INPUT_REQUIRE(!m.coords.is_null(),
                      "parameter '" << type_ << "/Null Space' is '" << kRigidBodyModes << "', which needs the nodal "
                                    << "coordinates, but setCoordinates() was not called before numeric(); pass "
                                    << "them, or set '" << type_ << "/Null Space' to '" << kTranslations << "'");
  }
  if (!m.coords.is_null()) {
    if (!m.coords->getMap()->isSameAs(*map))
      throw std::invalid_argument(type_ +
                                  " numeric(): the coordinates of setCoordinates() are not distributed "
                                  "like the matrix rows (their map differs from the row map)");
    // One row per owned node k (DOFs 2k, 2k+1), for MueLu / FROSch.
    const LO n = static_cast<LO>(map->getNodeNumElements());
    std::vector<GO> nodes(n / 2);
    for (LO p = 0; p < n; p += 2) nodes[p / 2] = map->getGlobalElement(p) / 2;
    auto nodeMap = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                        Teuchos::ArrayView<const GO>(nodes), 0, map->getComm()));
    nodeCoords = Teuchos::rcp(new MultiVector(nodeMap, 2));
    for (size_t c = 0; c < 2; ++c) {
      auto src = m.coords->getData(c);
      auto dst = nodeCoords->getDataNonConst(c);
      for (LO p = 0; p < n; p += 2) dst[p / 2] = src[p];
    }
  }
  if (m.rigidBodyModes) {
    nullSpace = rigidBodyModes2D(*m.coords);
  } else {
    nullSpace = translations2D(map);
  }
  m.prec = buildPreconditioner(m.fresh, nullSpace, nodeCoords);
  m.fresh = false;
  m.ready = true;
  ++m.nNumeric;
}

void IterativeSolver::solve(const MultiVector& b, MultiVector& x) {
  Impl& m = *impl_;
  if (!m.ready) throw std::logic_error(type_ + " solve(): no preconditioner; call symbolic() and numeric() first");
  using MV = MultiVector;
  using OP = Operator;
  x.putScalar(0.0);
  auto problem =
      Teuchos::rcp(new Belos::LinearProblem<Scalar, MV, OP>(A_, Teuchos::rcpFromRef(x), Teuchos::rcpFromRef(b)));
  if (rightPreconditioning()) {
    problem->setRightPrec(m.prec);
  } else {
    problem->setLeftPrec(m.prec);
  }
  problem->setProblem();

  auto pl = Teuchos::rcp(new Teuchos::ParameterList);
  pl->set("Convergence Tolerance", m.tol);
  pl->set("Maximum Iterations", m.maxIters);
  int verb = Belos::Errors;
  if (verbosity_ >= 1) verb += Belos::Warnings + Belos::FinalSummary;
  if (verbosity_ >= 2) verb += Belos::IterationDetails + Belos::StatusTestDetails;
  pl->set("Verbosity", verb);
  pl->set("Output Frequency", verbosity_ >= 2 ? 1 : -1);
  pl->set("Output Style", int(Belos::Brief));
  Teuchos::RCP<Belos::SolverManager<Scalar, MV, OP>> solver;
  if (m.belosSolver == "CG") {
    // x0 = 0, so the initial residual is b: the test is ||r|| / ||b||.
    solver = Teuchos::rcp(new Belos::PseudoBlockCGSolMgr<Scalar, MV, OP>(problem, pl));
  } else {
    // Restarted GMRES: a Krylov basis of at most 200 vectors (memory), as
    // many restarts as "Maximum Iterations" allows.
    const int numBlocks = std::min(m.maxIters, 200);
    pl->set("Num Blocks", numBlocks);
    pl->set("Maximum Restarts", m.maxIters / numBlocks + 1);
    pl->set("Implicit Residual Scaling", "Norm of RHS");
    pl->set("Explicit Residual Scaling", "Norm of RHS");
    solver = Teuchos::rcp(new Belos::PseudoBlockGmresSolMgr<Scalar, MV, OP>(problem, pl));
  }
  Belos::ReturnType ret = Belos::Unconverged;
  try {
    ret = solver->solve();
  } catch (const std::exception& e) {
    DDC_THROW(SolverError, name() << " solve failed in Belos " << m.belosSolver << ": " << e.what());
  }
  m.iterations = solver->getNumIters();

  // The true residual, with A applied by Tpetra.
  const size_t k = b.getNumVectors();
  MV r(A_->getRangeMap(), k);
  A_->apply(x, r);
  r.update(1.0, b, -1.0);
  std::vector<double> rn(k), bn(k);
  r.norm2(Teuchos::ArrayView<double>(rn));
  b.norm2(Teuchos::ArrayView<double>(bn));
  m.residual = 0.0;
  for (size_t j = 0; j < k; ++j) m.residual = std::max(m.residual, bn[j] > 0 ? rn[j] / bn[j] : rn[j]);

  // Belos GMRES returns Unconverged with a "loss of accuracy" when its
  // recursive residual met the tolerance but its explicit one did not quite:
  // round-off, accepted within the slack above.
  const bool belosDone = ret == Belos::Converged || solver->isLOADetected();
  if (!belosDone || !(m.residual <= kExplicitResidualSlack * m.tol)) {
    DDC_THROW(SolverError,
              name() << " did not converge: " << m.iterations << " " << m.belosSolver << " iterations, relative "
                     << "residual ||b - A x|| / ||b|| = " << m.residual << " (wanted " << m.tol << ", Belos "
                     << (belosDone ? "reported convergence of its recursive residual: the tolerance may be "
                                     "below the round-off level of this matrix"
                                   : "reached the iteration limit")
                     << "). Raise '" << type_ << "/Maximum Iterations' (now " << m.maxIters << "), loosen '" << type_
                     << "/Convergence Tolerance', or strengthen the preconditioner ('" << type_
                     << (type_ == MueLuSolver::kType ? "/MueLu" : "/FROSch") << "' sublist; is A "
                     << (m.belosSolver == "CG" ? "symmetric positive definite" : "nonsingular") << "?)");
  }
}

void addIterativeSolvers(DirectSolverFactory& factory) {
  factory.add(MueLuSolver::kType,
              {[](const Teuchos::ParameterList& p) -> std::unique_ptr<DirectSolver> {
                 return std::make_unique<MueLuSolver>(p);
               },
               MueLuSolver::getValidParameters(),
               "iterative: Belos CG + MueLu smoothed-aggregation AMG, for SPD 2-D elasticity matrices; needs "
               "setCoordinates()"});
  factory.add(FroschSolver::kType,
              {[](const Teuchos::ParameterList& p) -> std::unique_ptr<DirectSolver> {
                 return std::make_unique<FroschSolver>(p);
               },
               FroschSolver::getValidParameters(),
               "iterative: Belos GMRES + FROSch two-level overlapping Schwarz (GDSW coarse space), one "
               "subdomain per rank; needs setCoordinates()"});
}

}  // namespace ddc
