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
#include "DDC_MpiRecords.hpp"
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

/// "2k, 2k+1" (d = 2), "3k, 3k+1, 3k+2" (d = 3): the global indices of the
/// DOFs of node k, for messages.
std::string dofIndexPattern(int d) {
  std::string out;
  for (int c = 0; c < d; ++c) out += (c ? ", " : "") + std::to_string(d) + "k" + (c ? "+" + std::to_string(c) : "");
  return out;
}

/// Check the node-major layout with `d` DOFs per node of `map` (file comment
/// of the header) on every rank; all ranks throw if one fails.
void requireNodeMajorLayout(const Map& map, int d, const std::string& who) {
  const LO n = static_cast<LO>(map.getNodeNumElements());
  const std::string rank = std::to_string(map.getComm()->getRank());
  std::string why;
  if (n % d != 0) {
    why = "rank " + rank + " owns " +
          (d == 2 ? std::string("an odd number of rows") : "a number of rows not divisible by " + std::to_string(d)) +
          " (" + std::to_string(n) + ")";
  } else {
    for (LO p = 0; p < n && why.empty(); p += d) {
      const GO g = map.getGlobalElement(p);
      bool ok = g % d == 0;
      for (int c = 1; c < d; ++c) ok = ok && map.getGlobalElement(p + c) == g + c;
      if (ok) continue;
      std::string rows, found;
      for (int c = 0; c < d; ++c) {
        rows += (c ? ", " : "") + std::to_string(p + c);
        found += (c ? ", " : "") + std::to_string(map.getGlobalElement(p + c));
      }
      why = "rows " + rows + " of rank " + rank + " have global indices " + found + " (expected " + dofIndexPattern(d) +
            ")";
    }
  }
  if (anyRank(rawComm(*map.getComm()), !why.empty()))
    throw std::invalid_argument(who + ": the matrix must number its DOFs node-major, " + (d == 2 ? "two" : "three") +
                                " per node (global indices " + dofIndexPattern(d) +
                                " for node k, owned by the same rank)" +
                                (why.empty() ? std::string(" on every rank") : "; " + why));
}

/// The spatial dimension d of `coords` (its column count).
/// \throws std::invalid_argument naming `who` and the count unless 2 or 3.
int coordinateDimension(const MultiVector& coords, const std::string& who) {
  const size_t d = coords.getNumVectors();
  if (d != 2 && d != 3)
    throw std::invalid_argument(who + ": need 2 (x, y) or 3 (x, y, z) coordinate columns, got " + std::to_string(d));
  return static_cast<int>(d);
}

}  // namespace

struct IterativeSolver::Impl {
  double tol = 1e-10;       // "Convergence Tolerance"
  double solveTol = 1e-10;  // this solve's (setSolveTolerance())
  int maxIters = 1000;
  std::string belosSolver;  // "CG" or "GMRES"
  bool rigidBodyModes = true;
  Teuchos::RCP<const MultiVector> coords;
  int dim = 2;                 // DOFs per node = spatial dimension
  bool dimFromCaller = false;  // setDofsPerNode() was called
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
         "Near-null space the preconditioner's coarse space reproduces. 'Rigid Body Modes': the rigid-body "
         "modes of elasticity (3 in 2-D, 6 in 3-D) from the nodal coordinates of setCoordinates() (required "
         "before numeric()); 'Translations': the 2 or 3 translations only (no coordinates needed; weaker for "
         "elasticity).",
         enumValidator({kRigidBodyModes, kTranslations}, "Null Space"));
}

IterativeSolver::IterativeSolver(const Teuchos::ParameterList& params, const std::string& type,
                                 const std::string& belosSolver)
    : type_(type), impl_(std::make_unique<Impl>()) {
  // `params` was validated by the subclass (validateLevel filled the defaults).
  impl_->belosSolver = belosSolver;
  impl_->tol = impl_->solveTol = params.get<double>("Convergence Tolerance");
  impl_->maxIters = params.get<int>("Maximum Iterations");
  verbosity_ = params.get<int>("Verbosity");
  impl_->rigidBodyModes = params.get<std::string>("Null Space") == kRigidBodyModes;
}

IterativeSolver::~IterativeSolver() = default;

void IterativeSolver::setCoordinates(const Teuchos::RCP<const MultiVector>& coords) {
  Impl& m = *impl_;
  if (!coords.is_null()) {
    const int d = coordinateDimension(*coords, type_ + " setCoordinates()");
    if (m.dimFromCaller && d != m.dim)
      throw std::invalid_argument(type_ + " setCoordinates(): " + std::to_string(d) +
                                  " coordinate columns, but setDofsPerNode() said " + std::to_string(m.dim) +
                                  " DOFs per node; the two must agree (the spatial dimension)");
    m.dim = d;
  }
  m.coords = coords;
}

void IterativeSolver::setDofsPerNode(int d) {
  Impl& m = *impl_;
  if (d != 2 && d != 3)
    throw std::invalid_argument(type_ + " setDofsPerNode(): " + std::to_string(d) +
                                " DOFs per node; only 2-D and 3-D elasticity (2 or 3) are supported");
  if (!m.coords.is_null() && int(m.coords->getNumVectors()) != d)
    throw std::invalid_argument(type_ + " setDofsPerNode(): " + std::to_string(d) + " DOFs per node, but the " +
                                "coordinates of setCoordinates() have " + std::to_string(m.coords->getNumVectors()) +
                                " columns; the two must agree (the spatial dimension)");
  m.dim = d;
  m.dimFromCaller = true;
}

int IterativeSolver::dofsPerNode() const { return impl_->dim; }

int IterativeSolver::lastIterations() const { return impl_->iterations; }
double IterativeSolver::relativeTolerance() const { return impl_->tol; }
void IterativeSolver::setSolveTolerance(double tol) {
  if (!(tol >= impl_->tol && tol < 1.0))
    throw std::invalid_argument(type_ + " setSolveTolerance(" + std::to_string(tol) + "): expected a value in [" +
                                std::to_string(impl_->tol) + " (Convergence Tolerance), 1)");
  impl_->solveTol = tol;
}
double IterativeSolver::lastResidual() const { return impl_->residual; }
int IterativeSolver::numNumeric() const { return impl_->nNumeric; }

Teuchos::RCP<MultiVector> IterativeSolver::translations(const Teuchos::RCP<const Map>& map, int dofsPerNode) {
  if (dofsPerNode != 2 && dofsPerNode != 3)
    throw std::invalid_argument("translations: " + std::to_string(dofsPerNode) + " DOFs per node (2 or 3 supported)");
  const int d = dofsPerNode;
  requireNodeMajorLayout(*map, d, "translations");
  auto ns = Teuchos::rcp(new MultiVector(map, d));
  for (int c = 0; c < d; ++c) {
    auto t = ns->getDataNonConst(c);
    for (LO i = c; i < LO(map->getNodeNumElements()); i += d) t[i] = 1.0;
  }
  return ns;
}

Teuchos::RCP<MultiVector> IterativeSolver::rigidBodyModes(const MultiVector& coords) {
  const auto map = coords.getMap();
  const int d = coordinateDimension(coords, "rigidBodyModes");
  requireNodeMajorLayout(*map, d, "rigidBodyModes");
  // Centre of the nodes: mean over the x-DOF rows (each node counted once).
  const LO n = static_cast<LO>(map->getNodeNumElements());
  std::vector<Teuchos::ArrayRCP<const Scalar>> X(d);
  for (int c = 0; c < d; ++c) X[c] = coords.getData(c);
  std::vector<double> local(d + 1, 0.0), global(d + 1);
  local[d] = double(n / d);
  for (int c = 0; c < d; ++c)
    for (LO i = 0; i < n; i += d) local[c] += X[c][i];
  Teuchos::reduceAll(*map->getComm(), Teuchos::REDUCE_SUM, d + 1, local.data(), global.data());
  std::vector<double> Xc(d, 0.0);
  for (int c = 0; c < d; ++c) Xc[c] = global[d] > 0 ? global[c] / global[d] : 0.0;

  // Translations, then u = omega x (X - Xc) for unit rotations: about z in
  // 2-D; about x, y, z in 3-D.
  const int nRot = d == 2 ? 1 : 3;
  auto out = Teuchos::rcp(new MultiVector(map, d + nRot));
  std::vector<Teuchos::ArrayRCP<Scalar>> col(d + nRot);
  for (int j = 0; j < d + nRot; ++j) col[j] = out->getDataNonConst(j);
  for (LO i = 0; i < n; i += d) {
    for (int c = 0; c < d; ++c) col[c][i + c] = 1.0;
    if (d == 2) {
      col[2][i] = -(X[1][i] - Xc[1]);
      col[2][i + 1] = X[0][i] - Xc[0];
    } else {
      const double r[3] = {X[0][i] - Xc[0], X[1][i] - Xc[1], X[2][i] - Xc[2]};
      // omega = e_a: (e_a x r)_b = eps_abc r_c, i.e. component (a+2)%3 gets
      // r_(a+1)%3 and component (a+1)%3 gets -r_(a+2)%3.
      for (int a = 0; a < 3; ++a) {
        col[3 + a][i + (a + 1) % 3] = -r[(a + 2) % 3];
        col[3 + a][i + (a + 2) % 3] = r[(a + 1) % 3];
      }
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
  const int d = m.dim;
  requireNodeMajorLayout(*map, d, type_);
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
    // One row per owned node k (DOFs d k .. d k + d-1), for MueLu / FROSch.
    const LO n = static_cast<LO>(map->getNodeNumElements());
    std::vector<GO> nodes(n / d);
    for (LO p = 0; p < n; p += d) nodes[p / d] = map->getGlobalElement(p) / d;
    auto nodeMap = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                        Teuchos::ArrayView<const GO>(nodes), 0, map->getComm()));
    nodeCoords = Teuchos::rcp(new MultiVector(nodeMap, d));
    for (int c = 0; c < d; ++c) {
      auto src = m.coords->getData(c);
      auto dst = nodeCoords->getDataNonConst(c);
      for (LO p = 0; p < n; p += d) dst[p / d] = src[p];
    }
  }
  if (m.rigidBodyModes) {
    nullSpace = rigidBodyModes(*m.coords);
  } else {
    nullSpace = translations(map, d);
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
  pl->set("Convergence Tolerance", m.solveTol);
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
  if (!belosDone || !(m.residual <= kExplicitResidualSlack * m.solveTol)) {
    DDC_THROW(SolverError,
              name() << " did not converge: " << m.iterations << " " << m.belosSolver << " iterations, relative "
                     << "residual ||b - A x|| / ||b|| = " << m.residual << " (wanted " << m.solveTol << ", Belos "
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
               "iterative: Belos CG + MueLu smoothed-aggregation AMG, for SPD 2-D / 3-D elasticity matrices; "
               "needs setCoordinates()"});
  factory.add(FroschSolver::kType,
              {[](const Teuchos::ParameterList& p) -> std::unique_ptr<DirectSolver> {
                 return std::make_unique<FroschSolver>(p);
               },
               FroschSolver::getValidParameters(),
               "iterative: Belos GMRES + FROSch two-level overlapping Schwarz (GDSW coarse space), one "
               "subdomain per rank; needs setCoordinates()"});
}

}  // namespace ddc
