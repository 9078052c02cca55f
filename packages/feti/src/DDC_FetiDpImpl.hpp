// Internal to the feti package: the state of FetiDpSolver (its Impl) and the
// helpers its units share. Not part of the API (host codes use
// DDC_FetiDpSolver.hpp); installed only because every header of a package is.
//
// The solver is split into units a reader can hold one at a time
// (doc/feti-dp.md):
//   DDC_FetiDpInterface.cpp  interface classification, the jump operator B~
//                            (compatibility rows) and the LM maps;
//   DDC_FetiEdgeFaceConstraints.cpp  primal edge/face constraints, change of basis;
//   DDC_FetiDpBlocks.cpp     subdomain blocks K_rr, K_rPi, K_PiPi, K_II, ... and
//                            their factorisations, Phi and S_PiPi;
//   DDC_FetiDpCoarse.cpp     the primal (coarse) map, matrix and solver;
//   DDC_FetiDpScaling.cpp    the scaling weights of B_D;
//   DDC_FetiDpOperators.cpp  F = B K~^{-1} B^T and the preconditioner M^{-1};
//   DDC_FetiDpSolver.cpp     parameters and the solve driver (setTopology,
//                            numeric, solve, constraint rows).
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
#pragma once

#include <mpi.h>

#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "DDC_FetiDpSolver.hpp"
#include "DDC_FetiEdgeFaceConstraints.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace feti_internal {

using Operator = Tpetra::Operator<Scalar, LO, GO, Node>;
using Import = Tpetra::Import<LO, GO, Node>;
using Export = Tpetra::Export<LO, GO, Node>;
using Teuchos::RCP;
using Teuchos::rcp;

const Tpetra::global_size_t kInvalidSize = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
constexpr LO kNone = -1;

/// Sum of `v` over the communicator.
inline GO sumAll(MPI_Comm comm, GO v) {
  long long l = v, g = 0;
  MPI_Allreduce(&l, &g, 1, MPI_LONG_LONG, MPI_SUM, comm);
  return static_cast<GO>(g);
}

inline RCP<const Map> makeMap(const std::vector<GO>& gids, GO indexBase, const RCP<const Teuchos::Comm<int>>& comm) {
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

/// An extra-row entry on a shared dual DOF, sent to the DOF's owner, which
/// forwards it to every copy (SplitEntry).
struct SplitRequest {
  GO lm;       ///< row GID in lmMap
  GO gid;      ///< the DOF
  double full; ///< the caller's coefficient (in the new basis)
  int side;    ///< the caller's subdomain id (the side of the row it belongs to)
};

/// One copy of a split extra-row entry, for local subdomain `localSub`.
struct SplitEntry {
  GO lm;
  int localSub;
  LO dof;
  double full;
  int side;
};

/// A (row, side) key and the value that goes with it (scaling exchange).
struct KeyRecord {
  GO key;
};

/// One coarse-matrix entry sent to the owner of its row.
struct CoarseRecord {
  GO row, col;
  double v;
};

}  // namespace feti_internal

using namespace feti_internal;

// ---------------------------------------------------------------------------
// Impl
// ---------------------------------------------------------------------------

struct FetiDpSolver::Impl {
  enum class Prec { Dirichlet, Lumped, None };
  enum class Scaling { Automatic, Multiplicity, Stiffness };

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
    /// Extra rows: the caller's coefficient before the split over the copies
    /// of a shared dual DOF (coef = full * omega_k), and the LID of the
    /// row's side (the caller's subdomain of the entry) in sideOvMap.
    double full = 0.0;
    LO sideKey = -1;
    bool split = false;
  };

  /// A constraint entry before the LM maps exist: LM row by its GID in lmMap.
  struct GidEntry {
    GO lm;
    LO dof;
    double coef;
    double full = 0.0;  ///< extra rows: see BEntry
    int side = -1;      ///< extra rows: the caller's subdomain id of the entry
    bool split = false;
  };

  struct Sub {
    int id = -1;
    int index = -1;  ///< rank of id among all subdomain ids (0..sideSpan-1)
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
    /// K_rr is not formed: rSolver factorises K^s itself with the primal
    /// DOFs as Schur rows, giving S_PiPi^s directly, and applies K~^{-1} by
    /// condensation / expansion ("Local Schur Complement"); no Phi, K_rPi,
    /// K_Pir or K_PiPi are kept.
    bool schur = false;
    RCP<const Map> rMap, iMap;
    RCP<CrsMatrix> Krr, Kii;
    std::unique_ptr<DirectSolver> rSolver, iSolver;
    std::vector<Triplet> KrP, KPr;  // (r, p) and (p, r)
    std::vector<double> KPP;        // dense np x np, column-major
    std::vector<Triplet> KID, KDI, KDD;  // (I, Delta), (Delta, I), (Delta, Delta)
    std::vector<double> diag;       // K^s_jj per local DOF
    double krrNorm1 = 0.0;
    int factorizations = 0;         // of K_rr (or K^s with Schur rows) since setTopology()
    std::vector<double> Phi;        // nr x np, column-major (without schur)
    std::vector<double> S;          // np x np, column-major

    std::vector<BEntry> B;            // all rows (LIDs in lmOvMap), sorted by (lm, dof)
    std::vector<GidEntry> compatB;    // compatibility rows (GIDs), from setTopology()
    std::vector<GidEntry> extraB;     // rows from setConstraintRows() (GIDs)
    std::vector<GidEntry> extraUserB; // the same rows in the caller's basis (before T)
    std::vector<double> diagUser;     // K^s_jj of the caller's K^s per local DOF
    std::vector<char> constrainable;  // per local DOF: extra rows may touch it

    // work
    RCP<MultiVector> rB, rX, iB, iX;
    std::vector<double> fr, xr, fp, up;
    std::vector<double> vd, wd;
    std::vector<double> bn, xn;  // one value per local DOF (schur: condense / expand)
  };

  // configuration
  RCP<const Teuchos::Comm<int>> comm;
  MPI_Comm mpi = MPI_COMM_NULL;
  int rank = 0, size = 1;
  std::string path;
  Prec prec = Prec::Dirichlet;
  Scaling scaling = Scaling::Automatic;
  double singularityThreshold = 1e13;
  bool localSchur = true;  ///< "Local Schur Complement"
  PrimalConstraints primalChoice = PrimalConstraints::VerticesEdgesAndFaces;
  bool rotations = true;  // "Rotational Constraints"
  std::string belosType = "CG";
  bool belosGmresOnBreakdown = true;
  double belosTol = 1e-10;  ///< "Belos/Convergence Tolerance"
  double solveTol = 1e-10;  ///< the next solve()'s (setSolveTolerance())
  int belosMaxIt = 500;
  int belosVerbosity = 0;
  int belosOutputFrequency = -1;
  Teuchos::ParameterList belosExtra;  // other Belos parameters, passed through
  Teuchos::ParameterList localSolverParams, coarseSolverParams;
  DirectSolverFactory factory = DirectSolverFactory::withBuiltins();

  // topology
  bool haveTopology = false, analysed = false, factored = false;
  bool scalingCurrent = false;  ///< B_D matches the rows and the last factorised values
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
  /// On the owner of each shared dual DOF (ownedMap): every copy of it
  /// (subdomain id, rank, local subdomain, local DOF), for splitting extra
  /// rows over the copies (doc/feti-dp.md "Extra rows").
  std::map<GO, std::vector<ShareRecord>> sharers;
  /// Keys (row GID * sideSpan + side subdomain id) of the extra rows' sides:
  /// owned by the row's owner (sideMap), and those of this rank's entries.
  GO sideSpan = 1;
  RCP<const Map> sideMap, sideOvMap;
  RCP<Import> sideImport;
  RCP<Export> sideExport;
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
  /// Extra rows in the new basis -> Sub::extraB, entries on shared dual
  /// DOFs split over all copies (collective).
  std::string distributeExtraRows(const std::vector<std::vector<GidEntry>>& rows);
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
  /// fOp and mOp (DDC_FetiDpOperators.cpp).
  void makeOperators();
};

}  // namespace ddc
