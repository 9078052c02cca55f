// FETI-DP dual-interface solver (doc/feti-dp.md): see DDC_FetiDpSolver.hpp
// for the method.
//
// Data layout on each rank:
//  - per subdomain (Sub): the split of K^s into remainder (r) / primal (Pi)
//    blocks, K_rr^s as a CrsMatrix on MPI_COMM_SELF with its direct solver,
//    Phi^s = K_rr^{-1} K_rPi (dense, column-major), S_PiPi^s (dense), the
//    Dirichlet split of the remainder into interior (I) / dual (Delta) DOFs,
//    and the constraint entries (LM, local DOF, coefficient) of B^s;
//  - overlapped ("Ov") maps: the DOFs, LMs and coarse DOFs touched by this
//    rank's subdomains, with Import/Export to the one-to-one owned maps, so
//    that every assembly is one Export(ADD) and every distribution one Import.
//
// Every exchange whose pattern is not a Tpetra map (who shares which DOF,
// the coarse matrix entries) goes through exchangeRecords(), a variable-size
// MPI_Alltoallv, to the owner of the DOF in the owned map.
#include "DDC_FetiDpSolver.hpp"

#include <mpi.h>

#include <BelosLinearProblem.hpp>
#include <BelosSolverFactory.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
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
#include "DDC_FetiEdgeFaceConstraints.hpp"
#include "DDC_MapOwners.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

using Operator = Tpetra::Operator<Scalar, LO, GO, Node>;
using Import = Tpetra::Import<LO, GO, Node>;
using Export = Tpetra::Export<LO, GO, Node>;
using Teuchos::RCP;
using Teuchos::rcp;

const Tpetra::global_size_t kInvalidSize = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
constexpr LO kNone = -1;

const std::vector<std::string>& preconditionerNames() {
  static const std::vector<std::string> n{"Dirichlet", "Lumped", "None"};
  return n;
}
const std::vector<std::string>& scalingNames() {
  static const std::vector<std::string> n{"Multiplicity", "Stiffness"};
  return n;
}
const std::vector<std::string>& belosSolverNames() {
  static const std::vector<std::string> n{"CG", "GMRES", "MINRES"};
  return n;
}

/// Sum of `v` over the communicator.
GO sumAll(MPI_Comm comm, GO v) {
  long long l = v, g = 0;
  MPI_Allreduce(&l, &g, 1, MPI_LONG_LONG, MPI_SUM, comm);
  return static_cast<GO>(g);
}

RCP<const Map> makeMap(const std::vector<GO>& gids, GO indexBase, const RCP<const Teuchos::Comm<int>>& comm) {
  return rcp(new Map(kInvalidSize, Teuchos::ArrayView<const GO>(gids.data(), gids.size()), indexBase, comm));
}

/// A sparse block entry in subdomain-local block indices.
struct Triplet {
  LO i, j;
  double v;
};

/// Who shares a DOF: sent to the DOF's owner to build the constraint rows.
struct ShareRecord {
  GO gid;
  int subId;
  int rank;
  int localSub;
  LO dof;
};

/// One entry of B returned to the rank of the subdomain.
struct LmRecord {
  GO lm;
  int localSub;
  LO dof;
  double coef;
};

/// One coarse-matrix entry sent to the owner of its row.
struct CoarseRecord {
  GO row, col;
  double v;
};

}  // namespace

// ---------------------------------------------------------------------------
// Impl
// ---------------------------------------------------------------------------

struct FetiDpSolver::Impl {
  enum class Prec { Dirichlet, Lumped, None };

  /// One entry of a constraint row: coefficient `coef` of local DOF `dof` of
  /// this subdomain in LM row `lm` (LID in lmOvMap). General: `dof` may be a
  /// remainder or a primal DOF. `scaled` = coef times the scaling weight
  /// (B_D of the preconditioner).
  struct BEntry {
    LO lm;
    LO dof;
    double coef;
    double scaled;
    bool extra;  ///< a row from setConstraintRows() (not a compatibility row)
  };

  /// A constraint entry before the LM maps exist: LM row by its GID in lmMap.
  struct GidEntry {
    GO lm;
    LO dof;
    double coef;
  };

  struct Sub {
    int id = -1;
    std::vector<GO> dofs;
    std::vector<char> primal;
    RCP<CrsMatrix> K;      // the matrix FETI-DP works on: K^s, or T^T K^s T with edge/face constraints
    RCP<CrsMatrix> Kuser;  // the caller's K^s when K is transformed
    ChangeOfBasis cob;     // edge/face constraints (identity without)
    LO n = 0;

    // splits (per local DOF -> block index, or kNone)
    std::vector<LO> rIdx, pIdx;   // remainder / primal index
    std::vector<LO> rDof, pDof;   // block index -> local DOF
    std::vector<LO> dIdx, iIdx;   // per remainder index: dual (Delta) / interior index
    std::vector<LO> iR;           // interior index -> remainder index
    LO nr = 0, np = 0, nd = 0, ni = 0;
    std::vector<LO> ovLid;        // local DOF -> LID in dofOvMap
    std::vector<double> invMult;  // local DOF -> 1 / multiplicity
    std::vector<LO> coarseOvLid;  // primal index -> LID in coarseOvMap
    std::vector<GO> coarseGid;    // primal index -> GID in coarseMap
    std::vector<int> coarseOwner; // primal index -> owning rank of the coarse row

    // blocks (values refreshed by numeric())
    RCP<const Map> rMap, iMap;
    RCP<CrsMatrix> Krr, Kii;
    std::unique_ptr<DirectSolver> rSolver, iSolver;
    std::vector<Triplet> KrP, KPr;  // (r, p) and (p, r)
    std::vector<double> KPP;        // dense np x np, column-major
    std::vector<Triplet> KID, KDI, KDD;  // (I, Delta), (Delta, I), (Delta, Delta)
    std::vector<double> diag;       // K^s_jj per local DOF
    double krrNorm1 = 0.0;
    std::vector<double> Phi;        // nr x np, column-major
    std::vector<double> S;          // np x np, column-major

    std::vector<BEntry> B;            // all rows (LIDs in lmOvMap), sorted by (lm, dof)
    std::vector<GidEntry> compatB;    // compatibility rows (GIDs), from setTopology()
    std::vector<GidEntry> extraB;     // rows from setConstraintRows() (GIDs)
    std::vector<char> constrainable;  // per local DOF: extra rows may touch it

    // work
    RCP<MultiVector> rB, rX, iB, iX;
    std::vector<double> fr, xr, fp, up;
    std::vector<double> vd, wd;
  };

  // configuration
  RCP<const Teuchos::Comm<int>> comm;
  MPI_Comm mpi = MPI_COMM_NULL;
  int rank = 0, size = 1;
  std::string path;
  Prec prec = Prec::Dirichlet;
  bool stiffnessScaling = false;
  double singularityThreshold = 1e13;
  PrimalConstraints primalChoice = PrimalConstraints::VerticesEdgesAndFaces;
  bool rotations = true;  // "Rotational Constraints"
  std::string belosType = "CG";
  double belosTol = 1e-10;
  int belosMaxIt = 500;
  int belosVerbosity = 0;
  int belosOutputFrequency = -1;
  Teuchos::ParameterList belosExtra;  // other Belos parameters, passed through
  Teuchos::ParameterList localSolverParams, coarseSolverParams;
  DirectSolverFactory factory = DirectSolverFactory::withBuiltins();

  // topology
  bool haveTopology = false, analysed = false, factored = false;
  std::vector<Sub> subs;
  RCP<const Map> ownedMap, dofOvMap;
  RCP<Import> dofImport;  // ownedMap -> dofOvMap
  RCP<Export> dofExport;  // dofOvMap -> ownedMap
  std::vector<int> ownedMult;  // per owned LID
  RCP<const Map> lmMap, lmOvMap;
  RCP<Import> lmImport;
  RCP<Export> lmExport;
  // compatibility rows: GIDs [0, nCompat), this rank's [compatOffset, compatOffset + nCompatOwned)
  GO nCompat = 0, compatOffset = 0, nCompatOwned = 0;
  // extra rows (setConstraintRows): GIDs nCompat + extraOffset + (LID in extraRowMap)
  RCP<const Map> extraRowMap;
  GO extraOffset = 0;
  RCP<Vector> mask;        // on lmMap: 1 = row in the problem, 0 = restrained to zero (null: all rows)
  RCP<Vector> rhs;         // c on lmMap (B u = c); zero on compatibility rows
  RCP<Vector> rowEntries;  // number of entries of each row (on lmMap)
  RCP<Vector> lastLambda;  // multipliers of the last solve() (on lmMap)
  RCP<const Map> primalMap, coarseMap, coarseOvMap;
  RCP<Import> coarseImport;
  RCP<Export> coarseExport;
  std::vector<LO> coarseOwnedLid;  // coarse LID -> ownedMap LID
  std::vector<char> coarseIsEdgeFace;  // coarse LID -> an edge/face constraint value (not a vertex DOF)
  GO nDual = 0, nCoarse = 0, nEdgeFace = 0;
  RCP<CrsMatrix> coarse;
  std::unique_ptr<DirectSolver> coarseSolver;

  // work vectors
  RCP<Vector> lmOvWork, lmWork, coarseOvWork, coarseWork, coarseSol, dofOvWork;

  // timings
  Info setup;
  mutable double tLocalSolve = 0, tCoarseSolve = 0, tPrec = 0, tDirichletSolve = 0;
  mutable int nApplyF = 0, nApplyM = 0;

  RCP<Operator> fOp, mOp;

  // ---- helpers -------------------------------------------------------------

  std::string param(const std::string& name) const { return joinPath(path, name); }

  void buildTopology(std::vector<FetiSubdomain> local, RCP<const Map> owned);
  void addEdgeFaceConstraints(const std::vector<std::vector<int>>& components,
                              const std::vector<std::vector<double>>& coords, const std::vector<int>& dims);
  void buildConstraints();
  void finalizeLm();
  void applyMask(Vector& v) const;
  void buildCoarse();
  void buildBlocks(Sub& s);
  void refreshBlocks(Sub& s);
  std::string factorSub(Sub& s);
  void computeScaling();
  void assembleCoarse();

  void scatterBt(const Vector& lambda, double sign);
  void applyKtildeInv(const Vector* fPiAssembled);
  void gatherB(Vector& y);
  void applyF(const Vector& x, Vector& y);
  void applyM(const Vector& x, Vector& y);
  void localSolve(DirectSolver& solver, MultiVector& B, MultiVector& X, const std::vector<double>& in,
                  std::vector<double>& out, double& timer) const;
};

namespace {

/// F = B K~^{-1} B^T as a Tpetra operator on the LM map.
class FOperator : public Operator {
 public:
  explicit FOperator(FetiDpSolver::Impl* impl) : impl_(impl) {}
  RCP<const Map> getDomainMap() const override { return impl_->lmMap; }
  RCP<const Map> getRangeMap() const override { return impl_->lmMap; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode, Scalar alpha,
             Scalar beta) const override {
    if (mode != Teuchos::NO_TRANS) throw std::logic_error("FETI-DP F operator: only NO_TRANS is supported");
    Vector tmp(impl_->lmMap);
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      impl_->applyF(*X.getVector(j), tmp);
      ++impl_->nApplyF;
      auto yj = Y.getVectorNonConst(j);
      if (beta == 0.0) yj->putScalar(0.0);  // ignore NaN/Inf in Y (BLAS convention)
      yj->update(alpha, tmp, beta);
    }
  }

 private:
  FetiDpSolver::Impl* impl_;
};

/// Dirichlet / lumped preconditioner M^{-1} = sum_s B_D^s S^s B_D^sT.
class MOperator : public Operator {
 public:
  explicit MOperator(FetiDpSolver::Impl* impl) : impl_(impl) {}
  RCP<const Map> getDomainMap() const override { return impl_->lmMap; }
  RCP<const Map> getRangeMap() const override { return impl_->lmMap; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode, Scalar alpha,
             Scalar beta) const override {
    if (mode != Teuchos::NO_TRANS) throw std::logic_error("FETI-DP preconditioner: only NO_TRANS is supported");
    const double t0 = MPI_Wtime();
    Vector tmp(impl_->lmMap);
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      impl_->applyM(*X.getVector(j), tmp);
      ++impl_->nApplyM;
      auto yj = Y.getVectorNonConst(j);
      if (beta == 0.0) yj->putScalar(0.0);
      yj->update(alpha, tmp, beta);
    }
    impl_->tPrec += MPI_Wtime() - t0;
  }

 private:
  FetiDpSolver::Impl* impl_;
};

}  // namespace

// ---------------------------------------------------------------------------
// topology
// ---------------------------------------------------------------------------

void FetiDpSolver::Impl::buildTopology(std::vector<FetiSubdomain> local, RCP<const Map> owned) {
  haveTopology = analysed = factored = false;
  subs.clear();
  extraRowMap = Teuchos::null;
  extraOffset = 0;
  if (owned.is_null()) throw std::invalid_argument("FetiDpSolver::setTopology: null owned DOF map");
  ownedMap = owned;

  // 1. Per-subdomain sanity (local checks, raised collectively).
  std::ostringstream err;
  subs.resize(local.size());
  std::vector<std::vector<int>> components(local.size());
  std::vector<std::vector<double>> coords(local.size());
  std::vector<int> dims(local.size());
  for (size_t ls = 0; ls < local.size() && err.str().empty(); ++ls) {
    FetiSubdomain& in = local[ls];
    Sub& s = subs[ls];
    s.id = in.id;
    s.n = static_cast<LO>(in.dofs.size());
    s.dofs = std::move(in.dofs);
    s.primal = std::move(in.primal);
    s.constrainable = std::move(in.constrainable);
    if (s.constrainable.empty()) s.constrainable.assign(s.dofs.size(), 0);
    s.K = in.K;
    s.Kuser = Teuchos::null;
    s.cob = ChangeOfBasis();
    components[ls] = std::move(in.component);
    coords[ls] = std::move(in.coordinates);
    dims[ls] = in.dim;
    if (s.primal.size() != s.dofs.size()) {
      err << "subdomain " << s.id << ": " << s.primal.size() << " primal flags for " << s.dofs.size() << " DOFs";
    } else if (s.constrainable.size() != s.dofs.size()) {
      err << "subdomain " << s.id << ": " << s.constrainable.size() << " constrainable flags for " << s.dofs.size()
          << " DOFs";
    } else if (s.K.is_null() || !s.K->isFillComplete()) {
      err << "subdomain " << s.id << ": K must be a fill-complete CrsMatrix";
    } else if (s.K->getRowMap()->getGlobalNumElements() != s.dofs.size() ||
               s.K->getRowMap()->getNodeNumElements() != s.dofs.size() ||
               !s.K->getRowMap()->isSameAs(*s.K->getDomainMap()) ||
               !s.K->getRowMap()->isSameAs(*s.K->getRangeMap()) || s.K->getRowMap()->getIndexBase() != 0 ||
               !s.K->getRowMap()->isContiguous()) {
      err << "subdomain " << s.id << ": K must live on MPI_COMM_SELF with row = range = domain map 0.."
          << s.dofs.size() << "-1 (one row per DOF), got " << s.K->getRowMap()->getGlobalNumElements() << " rows";
    } else {
      std::vector<GO> sorted(s.dofs);
      std::sort(sorted.begin(), sorted.end());
      auto dup = std::adjacent_find(sorted.begin(), sorted.end());
      if (dup != sorted.end()) err << "subdomain " << s.id << ": DOF " << *dup << " appears twice";
    }
  }
  raiseCollectively<std::invalid_argument>(mpi, err.str().empty() ? "" : "FetiDpSolver::setTopology: " + err.str());

  // Subdomain ids unique across ranks.
  {
    int nLocal = static_cast<int>(subs.size());
    std::vector<int> counts(size), displs(size, 0);
    MPI_Allgather(&nLocal, 1, MPI_INT, counts.data(), 1, MPI_INT, mpi);
    for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
    std::vector<int> ids(subs.size()), all(displs[size - 1] + counts[size - 1] + 1);
    for (size_t i = 0; i < subs.size(); ++i) ids[i] = subs[i].id;
    MPI_Allgatherv(ids.empty() ? all.data() : ids.data(), nLocal, MPI_INT, all.data(), counts.data(),
                   displs.data(), MPI_INT, mpi);
    all.pop_back();
    std::sort(all.begin(), all.end());
    auto dup = std::adjacent_find(all.begin(), all.end());
    if (dup != all.end())
      throw std::invalid_argument("FetiDpSolver::setTopology: subdomain id " + std::to_string(*dup) +
                                  " is used twice");
  }

  // 2. Overlapped DOF map of this rank's subdomains; all DOFs in ownedMap.
  {
    std::vector<GO> gids;
    for (const Sub& s : subs) gids.insert(gids.end(), s.dofs.begin(), s.dofs.end());
    std::sort(gids.begin(), gids.end());
    gids.erase(std::unique(gids.begin(), gids.end()), gids.end());
    dofOvMap = makeMap(gids, ownedMap->getIndexBase(), comm);
    std::vector<int> pids;
    std::vector<LO> lids;
    owners(*ownedMap, gids, pids, lids);
    std::string msg;
    for (size_t k = 0; k < gids.size(); ++k)
      if (pids[k] < 0) {
        msg = "FetiDpSolver::setTopology: DOF " + std::to_string(gids[k]) + " of a subdomain on rank " +
              std::to_string(rank) + " is not in the owned DOF map";
        break;
      }
    raiseCollectively<std::invalid_argument>(mpi, msg);
    dofImport = rcp(new Import(ownedMap, dofOvMap));
    dofExport = rcp(new Export(dofOvMap, ownedMap));
    for (Sub& s : subs) {
      s.ovLid.resize(s.n);
      for (LO k = 0; k < s.n; ++k) s.ovLid[k] = dofOvMap->getLocalElement(s.dofs[k]);
    }
  }

  // 3. Multiplicity and primal consistency: counts summed at the owner.
  std::vector<int> ovMult(dofOvMap->getNodeNumElements());
  {
    Vector cOv(dofOvMap), pOv(dofOvMap), cOwned(ownedMap), pOwned(ownedMap);
    {
      auto c = cOv.getDataNonConst();
      auto p = pOv.getDataNonConst();
      for (const Sub& s : subs)
        for (LO k = 0; k < s.n; ++k) {
          c[s.ovLid[k]] += 1.0;
          if (s.primal[k]) p[s.ovLid[k]] += 1.0;
        }
    }
    cOwned.doExport(cOv, *dofExport, Tpetra::ADD);
    pOwned.doExport(pOv, *dofExport, Tpetra::ADD);
    std::string msg;
    {
      auto c = cOwned.getData();
      auto p = pOwned.getData();
      ownedMult.assign(c.size(), 0);
      for (LO l = 0; l < LO(c.size()); ++l) {
        ownedMult[l] = static_cast<int>(std::lround(c[l]));
        const long np = std::lround(p[l]);
        if (np != 0 && np != ownedMult[l] && msg.empty())
          msg = "FetiDpSolver::setTopology: DOF " + std::to_string(ownedMap->getGlobalElement(l)) +
                " is primal in " + std::to_string(np) + " of the " + std::to_string(ownedMult[l]) +
                " subdomains sharing it; a DOF must be primal in all of them or in none";
      }
    }
    raiseCollectively<std::invalid_argument>(mpi, msg);
    cOv.doImport(cOwned, *dofImport, Tpetra::INSERT);
    auto c = cOv.getData();
    for (size_t l = 0; l < ovMult.size(); ++l) ovMult[l] = static_cast<int>(std::lround(c[l]));
  }
  addEdgeFaceConstraints(components, coords, dims);

  // 4. Per-subdomain splits: remainder / primal, and for the Dirichlet
  //    preconditioner the remainder into dual interface (Delta: shared,
  //    non-primal) and interior (I) DOFs.
  for (Sub& s : subs) {
    s.rIdx.assign(s.n, kNone);
    s.pIdx.assign(s.n, kNone);
    s.invMult.assign(s.n, 1.0);
    s.rDof.clear();
    s.pDof.clear();
    for (LO k = 0; k < s.n; ++k) {
      s.invMult[k] = 1.0 / ovMult[s.ovLid[k]];
      if (s.primal[k]) {
        s.pIdx[k] = LO(s.pDof.size());
        s.pDof.push_back(k);
      } else {
        s.rIdx[k] = LO(s.rDof.size());
        s.rDof.push_back(k);
      }
    }
    s.nr = LO(s.rDof.size());
    s.np = LO(s.pDof.size());
    s.dIdx.assign(s.nr, kNone);
    s.iIdx.assign(s.nr, kNone);
    s.iR.clear();
    s.nd = 0;
    for (LO r = 0; r < s.nr; ++r) {
      // Dual: shared with another subdomain, or touched by extra rows (so
      // that the Dirichlet preconditioner sees those rows too).
      if (ovMult[s.ovLid[s.rDof[r]]] >= 2 || s.constrainable[s.rDof[r]]) {
        s.dIdx[r] = s.nd++;
      } else {
        s.iIdx[r] = LO(s.iR.size());
        s.iR.push_back(r);
      }
    }
    s.ni = LO(s.iR.size());
  }

  buildConstraints();
  buildCoarse();
  std::string msg;
  for (Sub& s : subs) {
    try {
      buildBlocks(s);
    } catch (const std::exception& e) {
      msg = "FetiDpSolver::setTopology: subdomain " + std::to_string(s.id) + ": " + e.what();
      break;
    }
  }
  raiseCollectively<std::invalid_argument>(mpi, msg);

  coarseOvWork = rcp(new Vector(coarseOvMap));
  coarseWork = rcp(new Vector(coarseMap));
  coarseSol = rcp(new Vector(coarseMap));
  dofOvWork = rcp(new Vector(dofOvMap));
  fOp = rcp(new FOperator(this));
  mOp = prec == Prec::None ? Teuchos::null : RCP<Operator>(rcp(new MOperator(this)));
  haveTopology = true;
}

/// Edge/face constraints ("Primal Constraints"; doc/feti-dp.md): classify the
/// interface by the subdomains sharing each DOF (findEdgeFaceConstraints()),
/// make the representative DOFs of each group primal and work on K^s in the
/// basis where they hold the group's constraint values (ChangeOfBasis).
void FetiDpSolver::Impl::addEdgeFaceConstraints(const std::vector<std::vector<int>>& components,
                                                const std::vector<std::vector<double>>& coords,
                                                const std::vector<int>& dims) {
  nEdgeFace = 0;
  if (primalChoice == PrimalConstraints::Vertices) return;
  const std::string choice = primalConstraintNames()[size_t(primalChoice)];
  std::string msg;
  int dmin = INT_MAX, dmax = INT_MIN;
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    dmin = std::min(dmin, dims[ls]);
    dmax = std::max(dmax, dims[ls]);
    if (msg.empty() && ((dims[ls] != 2 && dims[ls] != 3) || components[ls].size() != subs[ls].dofs.size()))
      msg = "FetiDpSolver::setTopology: subdomain " + std::to_string(subs[ls].id) + ": '" +
            param("Primal Constraints") + "' = " + choice + " needs FetiSubdomain::dim (2 or 3, got " +
            std::to_string(dims[ls]) + ") and one FetiSubdomain::component per DOF (got " +
            std::to_string(components[ls].size()) + " for " + std::to_string(subs[ls].dofs.size()) +
            " DOFs); or set it to Vertices";
    else if (msg.empty() && rotations && coords[ls].size() != subs[ls].dofs.size() * size_t(dims[ls]))
      msg = "FetiDpSolver::setTopology: subdomain " + std::to_string(subs[ls].id) + ": '" +
            param("Rotational Constraints") + "' = true needs FetiSubdomain::coordinates (" +
            std::to_string(dims[ls]) + " per DOF, got " + std::to_string(coords[ls].size()) + " for " +
            std::to_string(subs[ls].dofs.size()) + " DOFs); or set it to false";
  }
  raiseCollectively<std::invalid_argument>(mpi, msg);
  int loc[2] = {dmin == INT_MAX ? INT_MIN : -dmin, dmax}, glob[2];
  MPI_Allreduce(loc, glob, 2, MPI_INT, MPI_MAX, mpi);
  if (glob[1] == INT_MIN) return;  // no subdomains at all
  if (-glob[0] != glob[1])
    throw std::invalid_argument("FetiDpSolver::setTopology: the subdomains disagree on FetiSubdomain::dim (" +
                                std::to_string(-glob[0]) + " and " + std::to_string(glob[1]) + ")");
  std::vector<EdgeFaceInput> in(subs.size());
  for (size_t ls = 0; ls < subs.size(); ++ls)
    in[ls] = EdgeFaceInput{subs[ls].id, subs[ls].dofs, subs[ls].primal, components[ls],
                           rotations ? coords[ls] : std::vector<double>()};
  const auto groups = findEdgeFaceConstraints(mpi, *ownedMap, in, glob[1], primalChoice, rotations);
  for (size_t ls = 0; ls < subs.size() && msg.empty(); ++ls) {
    Sub& s = subs[ls];
    if (groups[ls].empty()) continue;
    try {
      s.cob = ChangeOfBasis(s.n, groups[ls]);
      for (LO k = 0; k < s.n; ++k)
        if (s.cob.holdsConstraint(k)) s.primal[k] = 1;
      s.Kuser = s.K;
      s.K = s.cob.setPattern(*s.Kuser);
    } catch (const std::exception& e) {
      msg = "FetiDpSolver::setTopology: subdomain " + std::to_string(s.id) + ": change of basis: " + e.what();
    }
  }
  raiseCollectively<std::invalid_argument>(mpi, msg);
}

/// Compatibility constraints: the owner of each shared non-primal DOF
/// receives (DOF, subdomain id, rank, local subdomain, local DOF) from every
/// subdomain having it, creates one row per pair of them (+1 for the smaller
/// id, -1 for the other) and returns the entries to the subdomains' ranks.
void FetiDpSolver::Impl::buildConstraints() {
  std::vector<int> pids;
  std::vector<LO> lids;
  std::vector<std::vector<ShareRecord>> send(size);
  {
    // Owners of the shared non-primal DOFs of this rank's subdomains.
    std::vector<GO> gids;
    std::vector<std::pair<int, LO>> who;  // (local subdomain, local DOF)
    for (size_t ls = 0; ls < subs.size(); ++ls) {
      const Sub& s = subs[ls];
      for (LO r = 0; r < s.nr; ++r)
        if (s.dIdx[r] != kNone && s.invMult[s.rDof[r]] < 1.0) {
          gids.push_back(s.dofs[s.rDof[r]]);
          who.emplace_back(int(ls), s.rDof[r]);
        }
    }
    owners(*ownedMap, gids, pids, lids);
    for (size_t k = 0; k < gids.size(); ++k)
      send[pids[k]].push_back(ShareRecord{gids[k], subs[who[k].first].id, rank, who[k].first, who[k].second});
  }
  std::vector<ShareRecord> recv = exchangeRecords(mpi, send);
  std::sort(recv.begin(), recv.end(), [](const ShareRecord& a, const ShareRecord& b) {
    return a.gid != b.gid ? a.gid < b.gid : a.subId < b.subId;
  });

  // Count rows, then number them contiguously across ranks (rank order).
  GO nRows = 0, nGroups = 0;
  for (size_t a = 0; a < recv.size();) {
    size_t b = a;
    while (b < recv.size() && recv[b].gid == recv[a].gid) ++b;
    const GO m = GO(b - a);
    nRows += m * (m - 1) / 2;
    ++nGroups;
    a = b;
  }
  long long myRows = nRows, offset = 0;
  MPI_Exscan(&myRows, &offset, 1, MPI_LONG_LONG, MPI_SUM, mpi);
  if (rank == 0) offset = 0;
  nDual = sumAll(mpi, nGroups);

  std::vector<std::vector<LmRecord>> reply(size);
  GO next = offset;
  for (size_t a = 0; a < recv.size();) {
    size_t b = a;
    while (b < recv.size() && recv[b].gid == recv[a].gid) ++b;
    for (size_t i = a; i < b; ++i)
      for (size_t j = i + 1; j < b; ++j) {
        reply[recv[i].rank].push_back(LmRecord{next, recv[i].localSub, recv[i].dof, +1.0});
        reply[recv[j].rank].push_back(LmRecord{next, recv[j].localSub, recv[j].dof, -1.0});
        ++next;
      }
    a = b;
  }
  nCompat = sumAll(mpi, nRows);
  compatOffset = offset;
  nCompatOwned = nRows;

  std::vector<LmRecord> entries = exchangeRecords(mpi, reply);
  for (Sub& s : subs) s.compatB.clear();
  for (const auto& e : entries) subs[e.localSub].compatB.push_back(GidEntry{e.lm, e.dof, e.coef});
  finalizeLm();
}

/// The LM maps from the compatibility rows and the extra rows: lmMap owns
/// this rank's compatibility rows and its extra rows (those of its part of
/// extraRowMap); lmOvMap has every row this rank's subdomains touch. Also
/// the per-subdomain B (LIDs), the work vectors, the mask (all rows in) and
/// the row entry counts.
void FetiDpSolver::Impl::finalizeLm() {
  std::vector<GO> owned;
  for (GO k = 0; k < nCompatOwned; ++k) owned.push_back(compatOffset + k);
  const GO nExtraOwned = extraRowMap.is_null() ? 0 : GO(extraRowMap->getNodeNumElements());
  for (GO k = 0; k < nExtraOwned; ++k) owned.push_back(nCompat + extraOffset + k);
  lmMap = makeMap(owned, 0, comm);
  std::vector<GO> lmGids;
  for (const Sub& s : subs) {
    for (const auto& e : s.compatB) lmGids.push_back(e.lm);
    for (const auto& e : s.extraB) lmGids.push_back(e.lm);
  }
  std::sort(lmGids.begin(), lmGids.end());
  lmGids.erase(std::unique(lmGids.begin(), lmGids.end()), lmGids.end());
  lmOvMap = makeMap(lmGids, 0, comm);
  lmImport = rcp(new Import(lmMap, lmOvMap));
  lmExport = rcp(new Export(lmOvMap, lmMap));
  for (Sub& s : subs) {
    s.B.clear();
    for (const auto& e : s.compatB) s.B.push_back(BEntry{lmOvMap->getLocalElement(e.lm), e.dof, e.coef, e.coef, false});
    for (const auto& e : s.extraB) s.B.push_back(BEntry{lmOvMap->getLocalElement(e.lm), e.dof, e.coef, e.coef, true});
    // Deterministic order within a subdomain (by LM, then DOF).
    std::sort(s.B.begin(), s.B.end(),
              [](const BEntry& a, const BEntry& b) { return a.lm != b.lm ? a.lm < b.lm : a.dof < b.dof; });
  }
  lmOvWork = rcp(new Vector(lmOvMap));
  lmWork = rcp(new Vector(lmMap));
  rhs = rcp(new Vector(lmMap));
  lastLambda = rcp(new Vector(lmMap));
  mask = Teuchos::null;
  Vector countOv(lmOvMap);
  {
    auto c = countOv.getDataNonConst();
    for (const Sub& s : subs)
      for (const BEntry& e : s.B) c[e.lm] += 1.0;
  }
  rowEntries = rcp(new Vector(lmMap));
  rowEntries->doExport(countOv, *lmExport, Tpetra::ADD);
}

void FetiDpSolver::Impl::applyMask(Vector& v) const {
  if (!mask.is_null()) v.elementWiseMultiply(1.0, *mask, v, 0.0);
}

/// Primal map (GIDs = DOF ids, owned by the DOF's owner), the contiguous
/// coarse map with the same layout (MUMPS wants 0..N-1), the overlapped
/// coarse map of this rank's subdomains and the coarse matrix pattern.
void FetiDpSolver::Impl::buildCoarse() {
  std::vector<GO> ownedPrimal;
  coarseOwnedLid.clear();
  {
    // A DOF is primal if any (hence every) subdomain having it says so;
    // mark at the owner.
    Vector pOv(dofOvMap), pOwned(ownedMap), aOv(dofOvMap), aOwned(ownedMap);
    {
      auto p = pOv.getDataNonConst();
      auto a = aOv.getDataNonConst();
      for (const Sub& s : subs)
        for (LO k = 0; k < s.n; ++k) {
          if (s.primal[k]) p[s.ovLid[k]] = 1.0;
          if (s.cob.holdsConstraint(k)) a[s.ovLid[k]] = 1.0;
        }
    }
    pOwned.doExport(pOv, *dofExport, Tpetra::ADD);
    aOwned.doExport(aOv, *dofExport, Tpetra::ADD);
    auto p = pOwned.getData();
    auto a = aOwned.getData();
    coarseIsEdgeFace.clear();
    GO myEdgeFace = 0;
    for (LO l = 0; l < LO(p.size()); ++l)
      if (p[l] > 0.0) {
        ownedPrimal.push_back(ownedMap->getGlobalElement(l));
        coarseOwnedLid.push_back(l);
        coarseIsEdgeFace.push_back(a[l] > 0.0);
        myEdgeFace += a[l] > 0.0;
      }
    nEdgeFace = sumAll(mpi, myEdgeFace);
  }
  primalMap = makeMap(ownedPrimal, ownedMap->getIndexBase(), comm);
  coarseMap = rcp(new Map(kInvalidSize, ownedPrimal.size(), 0, comm));
  nCoarse = static_cast<GO>(coarseMap->getGlobalNumElements());
  std::vector<long long> offsets(size);
  {
    long long mine = coarseMap->getNodeNumElements() ? coarseMap->getMinGlobalIndex() : 0;
    MPI_Allgather(&mine, 1, MPI_LONG_LONG, offsets.data(), 1, MPI_LONG_LONG, mpi);
  }

  // Coarse GIDs of every subdomain's primal DOFs.
  std::vector<GO> gids;
  for (const Sub& s : subs)
    for (LO p = 0; p < s.np; ++p) gids.push_back(s.dofs[s.pDof[p]]);
  std::vector<int> pids;
  std::vector<LO> lids;
  owners(*primalMap, gids, pids, lids);
  std::vector<GO> ovGids;
  size_t k = 0;
  for (Sub& s : subs) {
    s.coarseGid.resize(s.np);
    s.coarseOwner.resize(s.np);
    for (LO p = 0; p < s.np; ++p, ++k) {
      DDC_ASSERT(pids[k] >= 0, "primal DOF " << gids[k] << " missing from the primal map");
      s.coarseGid[p] = offsets[pids[k]] + lids[k];
      s.coarseOwner[p] = pids[k];
      ovGids.push_back(s.coarseGid[p]);
    }
  }
  std::sort(ovGids.begin(), ovGids.end());
  ovGids.erase(std::unique(ovGids.begin(), ovGids.end()), ovGids.end());
  coarseOvMap = makeMap(ovGids, 0, comm);
  coarseImport = rcp(new Import(coarseMap, coarseOvMap));
  coarseExport = rcp(new Export(coarseOvMap, coarseMap));
  for (Sub& s : subs) {
    s.coarseOvLid.resize(s.np);
    for (LO p = 0; p < s.np; ++p) s.coarseOvLid[p] = coarseOvMap->getLocalElement(s.coarseGid[p]);
  }

  // Pattern of the coarse matrix: the dense S_PiPi^s blocks, sent to the
  // owners of their rows.
  std::vector<std::vector<CoarseRecord>> send(size);
  for (const Sub& s : subs)
    for (LO p = 0; p < s.np; ++p)
      for (LO q = 0; q < s.np; ++q) send[s.coarseOwner[p]].push_back(CoarseRecord{s.coarseGid[p], s.coarseGid[q], 0.0});
  std::vector<CoarseRecord> recv = exchangeRecords(mpi, send);
  const LO nOwned = LO(coarseMap->getNodeNumElements());
  std::vector<std::set<GO>> cols(nOwned);
  for (const auto& r : recv) cols[coarseMap->getLocalElement(r.row)].insert(r.col);
  std::vector<size_t> counts(nOwned);
  for (LO l = 0; l < nOwned; ++l) counts[l] = cols[l].size();
  coarse = rcp(new CrsMatrix(coarseMap, Teuchos::ArrayView<const size_t>(counts.data(), counts.size())));
  for (LO l = 0; l < nOwned; ++l) {
    std::vector<GO> c(cols[l].begin(), cols[l].end());
    std::vector<double> z(c.size(), 0.0);
    coarse->insertGlobalValues(coarseMap->getGlobalElement(l), Teuchos::ArrayView<const GO>(c.data(), c.size()),
                               Teuchos::ArrayView<const double>(z.data(), z.size()));
  }
  coarse->fillComplete(coarseMap, coarseMap);
  coarseSolver.reset();
  if (nCoarse > 0) {
    Teuchos::ParameterList p(coarseSolverParams);
    coarseSolver = factory.create(p, param("Coarse Solver"));
  }
}

/// Patterns of K_rr and K_II (CrsMatrix on MPI_COMM_SELF) and the solvers.
void FetiDpSolver::Impl::buildBlocks(Sub& s) {
  const auto selfComm = s.K->getComm();
  const auto& rowMap = *s.K->getRowMap();
  const auto& colMap = *s.K->getColMap();
  std::vector<size_t> rCount(s.nr, 0), iCount(s.ni, 0);
  CrsMatrix::local_inds_host_view_type inds;
  CrsMatrix::values_host_view_type vals;
  for (LO lr = 0; lr < s.n; ++lr) {
    const LO row = static_cast<LO>(rowMap.getGlobalElement(lr));
    s.K->getLocalRowView(lr, inds, vals);
    for (size_t e = 0; e < inds.extent(0); ++e) {
      const LO col = static_cast<LO>(colMap.getGlobalElement(inds(e)));
      const LO rr = s.rIdx[row], rc = s.rIdx[col];
      if (rr == kNone || rc == kNone) continue;
      ++rCount[rr];
      if (s.iIdx[rr] != kNone && s.iIdx[rc] != kNone) ++iCount[s.iIdx[rr]];
    }
  }
  s.rMap = rcp(new Map(static_cast<Tpetra::global_size_t>(s.nr), 0, selfComm));
  s.iMap = rcp(new Map(static_cast<Tpetra::global_size_t>(s.ni), 0, selfComm));
  s.Krr = rcp(new CrsMatrix(s.rMap, Teuchos::ArrayView<const size_t>(rCount.data(), rCount.size())));
  s.Kii = rcp(new CrsMatrix(s.iMap, Teuchos::ArrayView<const size_t>(iCount.data(), iCount.size())));
  std::vector<GO> rc, ic;
  std::vector<double> rv, iv;
  for (LO lr = 0; lr < s.n; ++lr) {
    const LO row = static_cast<LO>(rowMap.getGlobalElement(lr));
    const LO rr = s.rIdx[row];
    if (rr == kNone) continue;
    s.K->getLocalRowView(lr, inds, vals);
    rc.clear(), rv.clear(), ic.clear(), iv.clear();
    for (size_t e = 0; e < inds.extent(0); ++e) {
      const LO col = static_cast<LO>(colMap.getGlobalElement(inds(e)));
      const LO c = s.rIdx[col];
      if (c == kNone) continue;
      rc.push_back(c), rv.push_back(vals(e));
      if (s.iIdx[rr] != kNone && s.iIdx[c] != kNone) ic.push_back(s.iIdx[c]), iv.push_back(vals(e));
    }
    s.Krr->insertGlobalValues(rr, Teuchos::ArrayView<const GO>(rc.data(), rc.size()),
                              Teuchos::ArrayView<const double>(rv.data(), rv.size()));
    if (s.iIdx[rr] != kNone)
      s.Kii->insertGlobalValues(s.iIdx[rr], Teuchos::ArrayView<const GO>(ic.data(), ic.size()),
                                Teuchos::ArrayView<const double>(iv.data(), iv.size()));
  }
  s.Krr->fillComplete(s.rMap, s.rMap);
  s.Kii->fillComplete(s.iMap, s.iMap);
  s.rSolver.reset();
  s.iSolver.reset();
  if (s.nr > 0) {
    Teuchos::ParameterList p(localSolverParams);
    s.rSolver = factory.create(p, param("Local Solver"));
  }
  if (prec == Prec::Dirichlet && s.ni > 0 && s.nd > 0) {
    Teuchos::ParameterList p(localSolverParams);
    s.iSolver = factory.create(p, param("Local Solver"));
  }
  s.rB = rcp(new MultiVector(s.rMap, 1));
  s.rX = rcp(new MultiVector(s.rMap, 1));
  s.iB = rcp(new MultiVector(s.iMap, 1));
  s.iX = rcp(new MultiVector(s.iMap, 1));
  s.fr.assign(s.nr, 0.0);
  s.xr.assign(s.nr, 0.0);
  s.fp.assign(s.np, 0.0);
  s.up.assign(s.np, 0.0);
  s.vd.assign(s.nd, 0.0);
  s.wd.assign(s.nd, 0.0);
}

// ---------------------------------------------------------------------------
// numeric
// ---------------------------------------------------------------------------

/// Copy the current K^s values into the blocks (same pattern as setTopology).
void FetiDpSolver::Impl::refreshBlocks(Sub& s) {
  if (s.cob.active()) s.cob.update(*s.Kuser);
  const auto& rowMap = *s.K->getRowMap();
  const auto& colMap = *s.K->getColMap();
  s.Krr->resumeFill();
  s.Krr->setAllToScalar(0.0);
  s.Kii->resumeFill();
  s.Kii->setAllToScalar(0.0);
  s.KrP.clear(), s.KPr.clear(), s.KID.clear(), s.KDI.clear(), s.KDD.clear();
  s.KPP.assign(size_t(s.np) * s.np, 0.0);
  s.diag.assign(s.n, 0.0);
  std::vector<double> colSum(s.nr, 0.0);
  CrsMatrix::local_inds_host_view_type inds;
  CrsMatrix::values_host_view_type vals;
  std::vector<GO> rc, ic;
  std::vector<double> rv, iv;
  bool patternOk = true;
  for (LO lr = 0; lr < s.n; ++lr) {
    const LO row = static_cast<LO>(rowMap.getGlobalElement(lr));
    s.K->getLocalRowView(lr, inds, vals);
    rc.clear(), rv.clear(), ic.clear(), iv.clear();
    const LO rr = s.rIdx[row], pr = s.pIdx[row];
    for (size_t e = 0; e < inds.extent(0); ++e) {
      const LO col = static_cast<LO>(colMap.getGlobalElement(inds(e)));
      const double v = vals(e);
      if (col == row) s.diag[row] += v;
      const LO rcIdx = s.rIdx[col], pc = s.pIdx[col];
      if (rr != kNone && rcIdx != kNone) {
        rc.push_back(rcIdx), rv.push_back(v);
        colSum[rcIdx] += std::abs(v);
        const LO ir = s.iIdx[rr], ic2 = s.iIdx[rcIdx], dr = s.dIdx[rr], dc = s.dIdx[rcIdx];
        if (ir != kNone && ic2 != kNone) ic.push_back(ic2), iv.push_back(v);
        else if (ir != kNone) s.KID.push_back(Triplet{ir, dc, v});
        else if (ic2 != kNone) s.KDI.push_back(Triplet{dr, ic2, v});
        else s.KDD.push_back(Triplet{dr, dc, v});
      } else if (rr != kNone) {
        s.KrP.push_back(Triplet{rr, pc, v});
      } else if (rcIdx != kNone) {
        s.KPr.push_back(Triplet{pr, rcIdx, v});
      } else {
        s.KPP[size_t(pr) + size_t(pc) * s.np] += v;
      }
    }
    if (rr != kNone) {
      patternOk = patternOk && s.Krr->sumIntoGlobalValues(rr, LO(rc.size()), rv.data(), rc.data()) == LO(rc.size());
      if (s.iIdx[rr] != kNone)
        patternOk =
            patternOk && s.Kii->sumIntoGlobalValues(s.iIdx[rr], LO(ic.size()), iv.data(), ic.data()) == LO(ic.size());
    }
  }
  s.Krr->fillComplete(s.rMap, s.rMap);
  s.Kii->fillComplete(s.iMap, s.iMap);
  if (!patternOk)
    throw std::logic_error("the sparsity pattern of K changed since setTopology(); call setTopology() again");
  s.krrNorm1 = colSum.empty() ? 0.0 : *std::max_element(colSum.begin(), colSum.end());
}

/// Factorise K_rr^s, compute Phi^s, S_PiPi^s and check K_rr^s for
/// singularity; factorise K_II^s. Returns an error message or "".
std::string FetiDpSolver::Impl::factorSub(Sub& s) {
  const std::string who = "FETI-DP: subdomain " + std::to_string(s.id) + " (" + std::to_string(s.nr) +
                          " remainder DOFs, " + std::to_string(s.np) + " primal DOFs)";
  const std::string fix =
      ": its remainder stiffness K_rr is singular; the corner rule could not fix this subdomain's rigid modes "
      "(give it more primal DOFs: >= 2 distinct primal nodes in 2-D, or Dirichlet data)";
  try {
    refreshBlocks(s);
  } catch (const std::exception& e) {
    return who + ": " + e.what();
  }
  s.Phi.assign(size_t(s.nr) * s.np, 0.0);
  if (s.nr > 0) {
    try {
      if (!analysed) s.rSolver->symbolic(s.Krr);
      s.rSolver->numeric();
    } catch (const SolverError& e) {
      return who + fix + " [" + e.what() + "]";
    }
    // One multi-RHS solve: the np columns of K_rPi, plus a pseudo-random
    // column z for a condition estimate ||K||_1 ||K^{-1} z||_1 / ||z||_1 (one
    // step of inverse iteration). A singular K_rr that the factorisation did
    // not flag (tiny instead of zero pivots, as LDL^T of a floating
    // subdomain gives) shows up as an estimate near 1/eps.
    MultiVector R(s.rMap, size_t(s.np) + 1), X(s.rMap, size_t(s.np) + 1);
    for (const Triplet& t : s.KrP) R.sumIntoLocalValue(t.i, size_t(t.j), t.v);
    {
      std::mt19937 gen(12345u + static_cast<unsigned>(s.id));
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      auto z = R.getDataNonConst(size_t(s.np));
      for (LO r = 0; r < s.nr; ++r) z[r] = u(gen);
    }
    s.rSolver->solve(R, X);
    for (LO p = 0; p < s.np; ++p) {
      auto x = X.getData(size_t(p));
      std::copy(x.begin(), x.end(), s.Phi.begin() + size_t(p) * s.nr);
    }
    double zn = 0.0, yn = 0.0;
    {
      auto z = R.getData(size_t(s.np));
      auto y = X.getData(size_t(s.np));
      for (LO r = 0; r < s.nr; ++r) zn += std::abs(z[r]), yn += std::abs(y[r]);
    }
    const double est = s.krrNorm1 * yn / zn;
    bool finitePhi = std::isfinite(est);
    for (double v : s.Phi) finitePhi = finitePhi && std::isfinite(v);
    if (!finitePhi || (singularityThreshold > 0.0 && est > singularityThreshold)) {
      std::ostringstream os;
      os << who << fix << " [condition estimate of K_rr " << std::scientific << est << " > '"
         << param("Local Singularity Threshold") << "' = " << singularityThreshold << "]";
      return os.str();
    }
  }
  // S_PiPi^s = K_PiPi - K_Pir Phi
  s.S = s.KPP;
  for (const Triplet& t : s.KPr)
    for (LO q = 0; q < s.np; ++q) s.S[size_t(t.i) + size_t(q) * s.np] -= t.v * s.Phi[size_t(t.j) + size_t(q) * s.nr];
  return "";
}

/// Scaling weights of B_D: the entry of subdomain s in the row between s and
/// t at DOF j is multiplied by w_t(j) / sum_k w_k(j), with w = 1
/// ("Multiplicity": 1/m_j) or w = K^k_jj ("Stiffness", rho-scaling). The
/// partner's weight is the row sum of the weights minus the own one.
void FetiDpSolver::Impl::computeScaling() {
  auto weight = [&](const Sub& s, LO dof) { return stiffnessScaling ? std::abs(s.diag[dof]) : 1.0; };
  Vector wOv(dofOvMap), wOwned(ownedMap), rowOv(lmOvMap), row(lmMap);
  {
    auto w = wOv.getDataNonConst();
    auto rs = rowOv.getDataNonConst();
    for (const Sub& s : subs) {
      for (LO r = 0; r < s.nr; ++r)
        if (s.dIdx[r] != kNone) w[s.ovLid[s.rDof[r]]] += weight(s, s.rDof[r]);
      for (const BEntry& e : s.B)
        if (!e.extra) rs[e.lm] += weight(s, e.dof);
    }
  }
  wOwned.doExport(wOv, *dofExport, Tpetra::ADD);
  wOv.doImport(wOwned, *dofImport, Tpetra::INSERT);
  row.doExport(rowOv, *lmExport, Tpetra::ADD);
  rowOv.doImport(row, *lmImport, Tpetra::INSERT);
  auto w = wOv.getData();
  auto rs = rowOv.getData();
  for (Sub& s : subs)
    for (BEntry& e : s.B) {
      if (e.extra) {
        // An extra (contact) row joins two sides (slave and master), like a
        // compatibility row between two copies: weight 1/2 on each side.
        e.scaled = 0.5 * e.coef;
        continue;
      }
      const double sum = w[s.ovLid[e.dof]];
      const double other = rs[e.lm] - weight(s, e.dof);
      // A zero diagonal (degenerate input) falls back to multiplicity.
      e.scaled = sum > 0.0 && other >= 0.0 ? e.coef * other / sum : e.coef * s.invMult[e.dof];
    }
}

/// Sum the S_PiPi^s blocks into the distributed coarse matrix (entries sent
/// to the owners of their rows).
void FetiDpSolver::Impl::assembleCoarse() {
  std::vector<std::vector<CoarseRecord>> send(size);
  for (const Sub& s : subs)
    for (LO p = 0; p < s.np; ++p)
      for (LO q = 0; q < s.np; ++q)
        send[s.coarseOwner[p]].push_back(
            CoarseRecord{s.coarseGid[p], s.coarseGid[q], s.S[size_t(p) + size_t(q) * s.np]});
  std::vector<CoarseRecord> recv = exchangeRecords(mpi, send);
  coarse->resumeFill();
  coarse->setAllToScalar(0.0);
  for (const auto& r : recv) coarse->sumIntoGlobalValues(r.row, 1, &r.v, &r.col);
  coarse->fillComplete(coarseMap, coarseMap);
}

// ---------------------------------------------------------------------------
// operators
// ---------------------------------------------------------------------------

void FetiDpSolver::Impl::localSolve(DirectSolver& solver, MultiVector& B, MultiVector& X,
                                    const std::vector<double>& in, std::vector<double>& out, double& timer) const {
  const double t0 = MPI_Wtime();
  {
    auto b = B.getDataNonConst(0);
    std::copy(in.begin(), in.end(), b.begin());
  }
  solver.solve(B, X);
  auto x = X.getData(0);
  out.assign(x.begin(), x.end());
  timer += MPI_Wtime() - t0;
}

/// f_r^s += sign * (B^sT lambda)_r and f_Pi^s += sign * (B^sT lambda)_Pi.
void FetiDpSolver::Impl::scatterBt(const Vector& lambda, double sign) {
  lmOvWork->doImport(lambda, *lmImport, Tpetra::INSERT);
  auto l = lmOvWork->getData();
  for (Sub& s : subs)
    for (const BEntry& e : s.B) {
      const double v = sign * e.coef * l[e.lm];
      if (s.rIdx[e.dof] != kNone) s.fr[s.rIdx[e.dof]] += v;
      else s.fp[s.pIdx[e.dof]] += v;
    }
}

/// (u_r^s, u_Pi) = K~^{-1} (f_r^s, f_Pi) where f_Pi = sum_s R^T f_Pi^s +
/// fPiAssembled (the latter on coarseMap, may be null). Inputs in s.fr,
/// s.fp; outputs in s.xr (= u_r^s), s.up (= u_Pi^s) and coarseSol.
void FetiDpSolver::Impl::applyKtildeInv(const Vector* fPiAssembled) {
  for (Sub& s : subs)
    if (s.nr > 0) localSolve(*s.rSolver, *s.rB, *s.rX, s.fr, s.xr, tLocalSolve);
  if (nCoarse == 0) {
    for (Sub& s : subs) std::fill(s.up.begin(), s.up.end(), 0.0);
    return;
  }
  const double t0 = MPI_Wtime();
  // g_Pi = f_Pi - sum_s R_Pi^T K_Pir x_r
  coarseOvWork->putScalar(0.0);
  {
    auto g = coarseOvWork->getDataNonConst();
    for (Sub& s : subs) {
      std::vector<double> gp(s.fp);
      for (const Triplet& t : s.KPr) gp[t.i] -= t.v * s.xr[t.j];
      for (LO p = 0; p < s.np; ++p) g[s.coarseOvLid[p]] += gp[p];
    }
  }
  coarseWork->putScalar(0.0);
  coarseWork->doExport(*coarseOvWork, *coarseExport, Tpetra::ADD);
  if (fPiAssembled) coarseWork->update(1.0, *fPiAssembled, 1.0);
  coarseSolver->solve(*coarseWork, *coarseSol);
  coarseOvWork->doImport(*coarseSol, *coarseImport, Tpetra::INSERT);
  tCoarseSolve += MPI_Wtime() - t0;
  auto u = coarseOvWork->getData();
  for (Sub& s : subs) {
    for (LO p = 0; p < s.np; ++p) s.up[p] = u[s.coarseOvLid[p]];
    // u_r = x_r - Phi u_Pi^s
    for (LO q = 0; q < s.np; ++q) {
      const double uq = s.up[q];
      const double* phi = s.Phi.data() + size_t(q) * s.nr;
      for (LO r = 0; r < s.nr; ++r) s.xr[r] -= phi[r] * uq;
    }
  }
}

/// y = B u with u = (s.xr, s.up) per subdomain.
void FetiDpSolver::Impl::gatherB(Vector& y) {
  lmOvWork->putScalar(0.0);
  {
    auto l = lmOvWork->getDataNonConst();
    for (const Sub& s : subs)
      for (const BEntry& e : s.B)
        l[e.lm] += e.coef * (s.rIdx[e.dof] != kNone ? s.xr[s.rIdx[e.dof]] : s.up[s.pIdx[e.dof]]);
  }
  y.putScalar(0.0);
  y.doExport(*lmOvWork, *lmExport, Tpetra::ADD);
}

/// y = P F P x, P = the mask (restrained rows out).
void FetiDpSolver::Impl::applyF(const Vector& x, Vector& y) {
  for (Sub& s : subs) {
    std::fill(s.fr.begin(), s.fr.end(), 0.0);
    std::fill(s.fp.begin(), s.fp.end(), 0.0);
  }
  if (mask.is_null()) {
    scatterBt(x, 1.0);
  } else {
    lmWork->elementWiseMultiply(1.0, *mask, x, 0.0);
    scatterBt(*lmWork, 1.0);
  }
  applyKtildeInv(nullptr);
  gatherB(y);
  applyMask(y);
}

/// M^{-1} x = sum_s B_D^s S^s B_D^sT x, S^s = K_DD - K_DI K_II^{-1} K_ID
/// (Dirichlet) or K_DD (lumped). Primal DOFs count as fixed, so entries of
/// compatibility rows on primal DOFs do not enter; entries of extra rows on
/// primal or interior DOFs enter lumped and diagonal (scaled^2 K_jj).
void FetiDpSolver::Impl::applyM(const Vector& x, Vector& y) {
  if (mask.is_null()) {
    lmOvWork->doImport(x, *lmImport, Tpetra::INSERT);
  } else {
    lmWork->elementWiseMultiply(1.0, *mask, x, 0.0);
    lmOvWork->doImport(*lmWork, *lmImport, Tpetra::INSERT);
  }
  std::vector<double> yOv(lmOvMap->getNodeNumElements(), 0.0);
  {
    auto l = lmOvWork->getData();
    std::vector<double> vi, wi;
    for (Sub& s : subs) {
      std::fill(s.vd.begin(), s.vd.end(), 0.0);
      for (const BEntry& e : s.B) {
        const LO r = s.rIdx[e.dof];
        if (r != kNone && s.dIdx[r] != kNone) {
          s.vd[s.dIdx[r]] += e.scaled * l[e.lm];
        } else if (e.extra) {
          // An extra row's entry on a primal (or interior) DOF: lumped,
          // diagonal, B_D K_jj B_D^T. Without it a row lying on primal DOFs
          // only (a slave node on a primal master node) has no
          // preconditioner at all and CG breaks down.
          yOv[e.lm] += e.scaled * e.scaled * std::abs(s.diag[e.dof]) * l[e.lm];
        }
      }
      std::fill(s.wd.begin(), s.wd.end(), 0.0);
      for (const Triplet& t : s.KDD) s.wd[t.i] += t.v * s.vd[t.j];
      if (s.iSolver) {
        vi.assign(s.ni, 0.0);
        for (const Triplet& t : s.KID) vi[t.i] += t.v * s.vd[t.j];
        localSolve(*s.iSolver, *s.iB, *s.iX, vi, wi, tDirichletSolve);
        for (const Triplet& t : s.KDI) s.wd[t.i] -= t.v * wi[t.j];
      }
      for (const BEntry& e : s.B) {
        const LO r = s.rIdx[e.dof];
        if (r != kNone && s.dIdx[r] != kNone) yOv[e.lm] += e.scaled * s.wd[s.dIdx[r]];
      }
    }
  }
  {
    auto l = lmOvWork->getDataNonConst();
    std::copy(yOv.begin(), yOv.end(), l.begin());
  }
  y.putScalar(0.0);
  y.doExport(*lmOvWork, *lmExport, Tpetra::ADD);
  applyMask(y);
}

// ---------------------------------------------------------------------------
// public API
// ---------------------------------------------------------------------------

Teuchos::RCP<const Teuchos::ParameterList> FetiDpSolver::getValidParameters() {
  static const RCP<const Teuchos::ParameterList> valid = [] {
    auto pl = rcp(new Teuchos::ParameterList("FETI-DP"));
    pl->set("Preconditioner", std::string("Dirichlet"),
            "Preconditioner of F on the LM space, M^{-1} = sum_s B_D^s S^s B_D^sT: Dirichlet (S^s = K_DD - K_DI "
            "K_II^{-1} K_ID, the Schur complement on the subdomain's dual interface DOFs with its primal DOFs fixed; "
            "one more factorisation per subdomain), Lumped (S^s ~ K_DD, cheaper, more iterations), None.",
            enumValidator(preconditionerNames(), "Preconditioner"));
    pl->set("Scaling", std::string("Multiplicity"),
            "Weights of B_D: Multiplicity (the entry of subdomain s in the row between s and t at DOF j is scaled "
            "by 1/m_j, m_j = number of subdomains sharing j) or Stiffness (rho-scaling from diagonal entries: by "
            "K^t_jj / sum_k K^k_jj; better for jumping coefficients).",
            enumValidator(scalingNames(), "Scaling"));
    pl->set("Primal Constraints", std::string("Vertices, Edges and Faces"),
            "Primal (coarse) constraints besides the caller's vertex DOFs: Vertices (none), Vertices and Edges "
            "(plus the average of each displacement component over each edge: in 2-D a subdomain-subdomain "
            "interface, in 3-D the interface DOFs shared by >= 3 subdomains), Vertices, Edges and Faces (plus "
            "the averages over the 3-D faces, DOFs shared by exactly 2 subdomains; in 2-D the same as Vertices "
            "and Edges). The constraint values (averages; rotations: 'Rotational Constraints') enter by a change of "
            "basis (doc/feti-dp.md, 'Primal constraints').",
            enumValidator(primalConstraintNames(), "Primal Constraints"));
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
    Teuchos::ParameterList belos("Belos");
    belos.set("Solver Type", std::string("CG"),
              "Belos solver for F lambda = d (Belos::SolverFactory names): CG (symmetric tangents, the "
              "preconditioner applied as Belos left preconditioner), GMRES (nonsymmetric), MINRES (symmetric "
              "indefinite F).",
              enumValidator(belosSolverNames(), "Solver Type"));
    belos.set("Convergence Tolerance", 1e-10,
              "Relative residual ||d - F lambda|| / ||d|| at which Belos stops (its implicit residual).",
              between(0.0, 1.0));
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
    pl->sublist("Local Solver", false,
                "Direct solver {Type, ...} for the subdomain matrices K_rr and K_II (on MPI_COMM_SELF).")
        .setParameters(*DirectSolverFactory::getValidParameters());
    pl->sublist("Coarse Solver", false,
                "Direct solver {Type, ...} for the coarse matrix S_PiPi, distributed over all ranks (MUMPS "
                "factorises it in parallel; Amesos2 gathers it to rank 0, because KLU2 is wrong on distributed "
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
  m.comm = comm;
  m.mpi = rawComm(comm);
  MPI_Comm_rank(m.mpi, &m.rank);
  MPI_Comm_size(m.mpi, &m.size);
  m.path = path;
  const auto valid = getValidParameters();
  validateLevel(params, *valid, path);
  const std::string prec = params.get<std::string>("Preconditioner");
  m.prec = prec == "Dirichlet" ? Impl::Prec::Dirichlet : prec == "Lumped" ? Impl::Prec::Lumped : Impl::Prec::None;
  m.stiffnessScaling = params.get<std::string>("Scaling") == "Stiffness";
  m.singularityThreshold = params.get<double>("Local Singularity Threshold");
  m.primalChoice = primalConstraintsFromName(params.get<std::string>("Primal Constraints"));
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
  m.belosTol = belos.get<double>("Convergence Tolerance");
  m.belosMaxIt = belos.get<int>("Maximum Iterations");
  m.belosVerbosity = belos.get<int>("Verbosity");
  m.belosOutputFrequency = belos.get<int>("Output Frequency");
  // Creating a solver validates the sublist (unknown Type, misspelt options)
  // now rather than at the first numeric().
  m.factory.create(params.sublist("Local Solver"), joinPath(path, "Local Solver"));
  m.factory.create(params.sublist("Coarse Solver"), joinPath(path, "Coarse Solver"));
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
  const double t0 = MPI_Wtime();
  Info& st = m.setup;
  st = Info{};

  std::string msg;
  for (auto& s : m.subs) {
    msg = m.factorSub(s);
    if (!msg.empty()) break;
  }
  const double t1 = MPI_Wtime();
  st.localFactorSeconds = t1 - t0;
  raiseCollectively<SolverError>(m.mpi, msg);

  m.computeScaling();

  if (m.prec == Impl::Prec::Dirichlet) {
    for (auto& s : m.subs) {
      if (!s.iSolver) continue;
      try {
        if (!m.analysed) s.iSolver->symbolic(s.Kii);
        s.iSolver->numeric();
      } catch (const SolverError& e) {
        msg = "FETI-DP: subdomain " + std::to_string(s.id) +
              ": the interior stiffness K_II of the Dirichlet preconditioner is singular (an interior part not "
              "connected to the interface, primal DOFs or Dirichlet data?) [" +
              e.what() + "]; or use '" + m.param("Preconditioner") + "' = Lumped";
        break;
      }
    }
  }
  const double t2 = MPI_Wtime();
  st.dirichletFactorSeconds = t2 - t1;
  raiseCollectively<SolverError>(m.mpi, msg);

  if (m.nCoarse > 0) {
    m.assembleCoarse();
    try {
      if (!m.analysed) m.coarseSolver->symbolic(m.coarse);
      m.coarseSolver->numeric();
    } catch (const SolverError& e) {
      // The coarse solver's errors are collective (same INFOG on every rank).
      DDC_THROW(SolverError, "FETI-DP: the coarse matrix S_PiPi (" << m.nCoarse
                                                                    << " primal DOFs) could not be factorised: "
                                                                    << e.what()
                                                                    << " (is the whole structure floating?)");
    }
  }
  const double t3 = MPI_Wtime();
  st.coarseFactorSeconds = t3 - t2;
  st.setupSeconds = t3 - t0;
  double loc[4] = {st.localFactorSeconds, st.dirichletFactorSeconds, st.coarseFactorSeconds, st.setupSeconds};
  double glob[4];
  MPI_Allreduce(loc, glob, 4, MPI_DOUBLE, MPI_MAX, m.mpi);
  st.localFactorSeconds = glob[0];
  st.dirichletFactorSeconds = glob[1];
  st.coarseFactorSeconds = glob[2];
  st.setupSeconds = glob[3];
  m.analysed = true;
  m.factored = true;
}

FetiDpSolver::Info FetiDpSolver::solve(const Vector& b, Vector& u) {
  Impl& m = *impl_;
  if (!m.factored) throw std::logic_error("FetiDpSolver::solve() called without a successful numeric()");
  const double t0 = MPI_Wtime();
  m.tLocalSolve = m.tCoarseSolve = m.tPrec = m.tDirichletSolve = 0.0;
  m.nApplyF = m.nApplyM = 0;
  Info info = m.setup;

  const bool sameMaps = b.getMap()->isSameAs(*m.ownedMap) && u.getMap()->isSameAs(*m.ownedMap);
  if (!sameMaps) throw std::invalid_argument("FetiDpSolver::solve: b and u must be on the owned DOF map");
  {
    auto bv = b.getData();
    std::string msg;
    for (LO l = 0; l < LO(bv.size()); ++l)
      if (m.ownedMult[l] == 0 && bv[l] != 0.0) {
        std::ostringstream os;
        os << "FetiDpSolver::solve: b = " << bv[l] << " on DOF " << m.ownedMap->getGlobalElement(l)
           << ", which belongs to no subdomain";
        msg = os.str();
        break;
      }
    raiseCollectively<std::invalid_argument>(m.mpi, msg);
  }

  // f~: interior DOFs as is, dual copies b_j / m_j, primal DOFs assembled
  // directly into the coarse right-hand side.
  // With edge/face constraints, f^s = T^T (b_j / m_j): the constraint DOFs get their
  // share in f_Pi^s, summed over the subdomains by the coarse assembly.
  m.dofOvWork->doImport(b, *m.dofImport, Tpetra::INSERT);
  std::vector<std::vector<double>> frBase(m.subs.size()), fpBase(m.subs.size());
  {
    auto bo = m.dofOvWork->getData();
    std::vector<double> f;
    for (size_t ls = 0; ls < m.subs.size(); ++ls) {
      auto& s = m.subs[ls];
      std::fill(s.fp.begin(), s.fp.end(), 0.0);
      if (s.cob.active()) {
        f.resize(s.n);
        for (LO k = 0; k < s.n; ++k) f[k] = bo[s.ovLid[k]] * s.invMult[k];
        s.cob.forceToNew(f);
        for (LO r = 0; r < s.nr; ++r) s.fr[r] = f[s.rDof[r]];
        for (LO p = 0; p < s.np; ++p)
          if (s.cob.holdsConstraint(s.pDof[p])) s.fp[p] = f[s.pDof[p]];
      } else {
        for (LO r = 0; r < s.nr; ++r) s.fr[r] = bo[s.ovLid[s.rDof[r]]] * s.invMult[s.rDof[r]];
      }
      frBase[ls] = s.fr;
      fpBase[ls] = s.fp;
    }
  }
  Vector fPi(m.coarseMap);
  {
    auto bv = b.getData();
    auto f = fPi.getDataNonConst();
    for (size_t k = 0; k < m.coarseOwnedLid.size(); ++k)
      f[k] = m.coarseIsEdgeFace[k] ? 0.0 : bv[m.coarseOwnedLid[k]];
  }

  // d = B K~^{-1} f~ (the compatibility constraints have zero right-hand side)
  auto d = rcp(new MultiVector(m.lmMap, 1));
  auto lambda = rcp(new MultiVector(m.lmMap, 1));
  m.applyKtildeInv(&fPi);
  m.gatherB(*d->getVectorNonConst(0));
  // d = P (B K~^{-1} f~ - c)
  d->getVectorNonConst(0)->update(-1.0, *m.rhs, 1.0);
  m.applyMask(*d->getVectorNonConst(0));

  double dNorm = 0.0;
  {
    Teuchos::Array<double> n(1);
    d->norm2(n());
    dNorm = n[0];
  }
  const double tb0 = MPI_Wtime();
  if (m.lmMap->getGlobalNumElements() > 0 && dNorm > 0.0) {
    Belos::SolverFactory<Scalar, MultiVector, Operator> factory;
    auto bp = Teuchos::parameterList();
    bp->set("Convergence Tolerance", m.belosTol);
    bp->set("Maximum Iterations", m.belosMaxIt);
    bp->set("Verbosity", m.belosVerbosity);
    bp->set("Output Frequency", m.belosOutputFrequency);
    bp->setParameters(m.belosExtra);
    auto solver = factory.create(m.belosType, bp);
    auto problem = rcp(new Belos::LinearProblem<Scalar, MultiVector, Operator>(m.fOp, lambda, d));
    if (!m.mOp.is_null()) problem->setLeftPrec(m.mOp);
    problem->setProblem();
    solver->setProblem(problem);
    Belos::ReturnType ret = Belos::Unconverged;
    std::string failure;
    try {
      ret = solver->solve();
    } catch (const std::exception& e) {
      failure = e.what();
    }
    info.iterations = solver->getNumIters();
    try {
      info.relativeResidual = solver->achievedTol();
    } catch (const std::exception&) {
      info.relativeResidual = -1.0;
    }
    if (!failure.empty() || ret != Belos::Converged) {
      std::ostringstream os;
      os << "FETI-DP: Belos " << m.belosType << " did not converge on F lambda = d (" << m.lmMap->getGlobalNumElements()
         << " Lagrange multipliers): " << info.iterations << " iterations, achieved relative residual "
         << std::scientific << info.relativeResidual << ", tolerance " << m.belosTol;
      if (!failure.empty()) os << "; Belos reported: " << failure;
      os << ". Raise '" << m.param("Belos/Maximum Iterations") << "' (" << m.belosMaxIt << "), loosen '"
         << m.param("Belos/Convergence Tolerance") << "', or change '" << m.param("Preconditioner") << "' / '"
         << m.param("Belos/Solver Type") << "'";
      throw SolverError(os.str());
    }
  }
  const double tb1 = MPI_Wtime();

  m.applyMask(*lambda->getVectorNonConst(0));  // restrained rows: exactly zero
  m.lastLambda->assign(*lambda->getVector(0));

  // u = K~^{-1} (f~ - B^T lambda)
  for (size_t ls = 0; ls < m.subs.size(); ++ls) {
    auto& s = m.subs[ls];
    s.fr = frBase[ls];
    s.fp = fpBase[ls];
  }
  m.scatterBt(*lambda->getVector(0), -1.0);
  m.applyKtildeInv(&fPi);

  // Assemble u: copies of dual DOFs averaged (weights 1/m_j), vertex DOFs
  // from the coarse solution. With edge/face constraints, u^s = T û^s
  // first; the DOFs that held constraint values are then averaged like dual
  // DOFs.
  m.dofOvWork->putScalar(0.0);
  {
    auto uo = m.dofOvWork->getDataNonConst();
    std::vector<double> us;
    for (auto& s : m.subs) {
      if (!s.cob.active()) {
        for (LO r = 0; r < s.nr; ++r) uo[s.ovLid[s.rDof[r]]] += s.xr[r] * s.invMult[s.rDof[r]];
        continue;
      }
      us.assign(s.n, 0.0);
      for (LO r = 0; r < s.nr; ++r) us[s.rDof[r]] = s.xr[r];
      for (LO p = 0; p < s.np; ++p) us[s.pDof[p]] = s.up[p];
      s.cob.displacementToOld(us);
      for (LO k = 0; k < s.n; ++k)
        if (s.rIdx[k] != kNone || s.cob.holdsConstraint(k)) uo[s.ovLid[k]] += us[k] * s.invMult[k];
    }
  }
  u.putScalar(0.0);
  u.doExport(*m.dofOvWork, *m.dofExport, Tpetra::ADD);
  if (m.nCoarse > 0) {
    auto uv = u.getDataNonConst();
    auto c = m.coarseSol->getData();
    for (size_t k = 0; k < m.coarseOwnedLid.size(); ++k)
      if (!m.coarseIsEdgeFace[k]) uv[m.coarseOwnedLid[k]] = c[k];
  }

  const double t1 = MPI_Wtime();
  double loc[5] = {t1 - t0, tb1 - tb0, m.tLocalSolve, m.tCoarseSolve, m.tPrec};
  double glob[5];
  MPI_Allreduce(loc, glob, 5, MPI_DOUBLE, MPI_MAX, m.mpi);
  info.solveSeconds = glob[0];
  info.belosSeconds = glob[1];
  info.localSolveSeconds = glob[2];
  info.coarseSolveSeconds = glob[3];
  info.preconditionerSeconds = glob[4];
  info.operatorApplications = m.nApplyF;
  info.preconditionerApplications = m.nApplyM;
  return info;
}

void FetiDpSolver::setConstraintRows(Teuchos::RCP<const Map> rowMap,
                                     const std::vector<std::vector<ConstraintEntry>>& entries) {
  Impl& m = *impl_;
  if (!m.haveTopology) throw std::logic_error("FetiDpSolver::setConstraintRows() called before setTopology()");
  std::string msg;
  if (rowMap.is_null() || rowMap->getComm()->getSize() != m.size || !rowMap->isOneToOne())
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
  raiseCollectively<std::invalid_argument>(m.mpi, msg);

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
  std::vector<long long> counts(m.size), offsets(m.size, 0);
  MPI_Allgather(&mine, 1, MPI_LONG_LONG, counts.data(), 1, MPI_LONG_LONG, m.mpi);
  for (int r = 1; r < m.size; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<GO> rows;
  for (const auto& list : *use)
    for (const auto& e : list) rows.push_back(e.row);
  std::vector<int> pids;
  std::vector<LO> lids;
  owners(*rowMap, rows, pids, lids);
  size_t k = 0;
  for (size_t ls = 0; ls < use->size(); ++ls) {
    auto& s = m.subs[ls];
    s.extraB.clear();
    for (size_t i = 0; i < (*use)[ls].size(); ++i, ++k) {
      const ConstraintEntry& e = (*use)[ls][i];
      if (pids[k] < 0) {
        if (msg.empty()) msg = "FetiDpSolver::setConstraintRows: row " + std::to_string(e.row) + " (subdomain " +
                               std::to_string(s.id) + ") is not in the row map";
        continue;
      }
      s.extraB.push_back(Impl::GidEntry{m.nCompat + offsets[pids[k]] + lids[k], e.dof, e.coef});
    }
  }
  raiseCollectively<std::invalid_argument>(m.mpi, msg);
  m.extraRowMap = rowMap;
  m.extraOffset = offsets[m.rank];
  m.finalizeLm();
  m.factored = false;  // the scaling of B_D is recomputed by numeric()
}

void FetiDpSolver::setConstraintState(const std::vector<char>& active, const std::vector<double>& rhs) {
  Impl& m = *impl_;
  const size_t n = m.extraRowMap.is_null() ? 0 : m.extraRowMap->getNodeNumElements();
  std::string msg;
  if (active.size() != n || rhs.size() != n)
    msg = "FetiDpSolver::setConstraintState: one active flag and one right-hand side per owned row of the row map (" +
          std::to_string(n) + ")";
  raiseCollectively<std::invalid_argument>(m.mpi, msg);
  if (n == 0 && m.extraRowMap.is_null()) return;
  m.mask = rcp(new Vector(m.lmMap));
  m.mask->putScalar(1.0);
  m.rhs->putScalar(0.0);
  auto mk = m.mask->getDataNonConst();
  auto c = m.rhs->getDataNonConst();
  auto cnt = m.rowEntries->getData();
  for (size_t k = 0; k < n; ++k) {
    const size_t l = size_t(m.nCompatOwned) + k;
    mk[l] = active[k] ? 1.0 : 0.0;
    c[l] = active[k] ? rhs[k] : 0.0;
    if (active[k] && cnt[l] == 0.0 && msg.empty())
      msg = "FETI-DP: constraint row " + std::to_string(m.extraRowMap->getGlobalElement(LO(k))) +
            " is active but has no entry on a free DOF of any subdomain (all its DOFs are prescribed), so it "
            "cannot be enforced";
  }
  raiseCollectively<SolverError>(m.mpi, msg);
}

Teuchos::RCP<const Vector> FetiDpSolver::constraintMultipliers() const {
  const Impl& m = *impl_;
  if (m.extraRowMap.is_null()) return Teuchos::null;
  auto out = rcp(new Vector(m.extraRowMap));
  auto o = out->getDataNonConst();
  auto l = m.lastLambda->getData();
  for (size_t k = 0; k < o.size(); ++k) o[k] = l[size_t(m.nCompatOwned) + k];
  return out;
}

const FetiDpSolver::Info& FetiDpSolver::setupInfo() const { return impl_->setup; }

Teuchos::RCP<const Map> FetiDpSolver::lmMap() const { return impl_->lmMap; }
Teuchos::RCP<const Map> FetiDpSolver::primalMap() const { return impl_->primalMap; }
GO FetiDpSolver::numDualDofs() const { return impl_->nDual; }
GO FetiDpSolver::numEdgeFaceConstraints() const { return impl_->nEdgeFace; }

Teuchos::RCP<Vector> FetiDpSolver::applyB(const std::vector<std::vector<double>>& field) const {
  Impl& m = *impl_;
  if (!m.haveTopology) throw std::logic_error("FetiDpSolver::applyB() called before setTopology()");
  bool bad = field.size() != m.subs.size();
  for (size_t ls = 0; !bad && ls < field.size(); ++ls) bad = field[ls].size() != size_t(m.subs[ls].n);
  if (bad) throw std::invalid_argument("FetiDpSolver::applyB: one value per local DOF of each local subdomain");
  for (size_t ls = 0; ls < field.size(); ++ls) {
    auto& s = m.subs[ls];
    std::vector<double> f(field[ls]);
    s.cob.displacementToNew(f);  // B acts on û
    for (LO r = 0; r < s.nr; ++r) s.xr[r] = f[s.rDof[r]];
    for (LO p = 0; p < s.np; ++p) s.up[p] = f[s.pDof[p]];
  }
  auto y = rcp(new Vector(m.lmMap));
  m.gatherB(*y);
  return y;
}

Teuchos::RCP<const Tpetra::Operator<Scalar, LO, GO, Node>> FetiDpSolver::fOperator() const { return impl_->fOp; }
Teuchos::RCP<const Tpetra::Operator<Scalar, LO, GO, Node>> FetiDpSolver::preconditioner() const {
  return impl_->mOp;
}

}  // namespace ddc
