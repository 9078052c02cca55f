// Internal to the feti package: the state of FetiDpSolver and the units
// that own it. Not part of the API (host codes use DDC_FetiDpSolver.hpp);
// installed only because every header of a package is.
//
// The solver is split as PETSc's PCBDDC is (its graph, scaling, coarse and
// FETI-DP operator contexts): each unit owns its state and reads the others'
// through the arguments of its methods (doc/feti-dp.md):
//   Context, Subdomain             the communicator, the DOF maps, and per
//                                  subdomain its DOFs and their roles
//                                  (DDC_FetiDpInterface.cpp, setTopology());
//   JumpOperator                   B~ and B_D: compatibility and extra rows,
//                                  the LM maps, mask and right-hand side
//                                  (DDC_FetiDpInterface.cpp), the scaling
//                                  weights (DDC_FetiDpScaling.cpp);
//   CoarseProblem                  the primal map, S_PiPi and its solver
//                                  (DDC_FetiDpCoarse.cpp);
//   DualOperator                   K~^{-1} by the subdomain factorisations
//                                  and the coarse problem, and F = B K~^{-1}
//                                  B^T (DDC_FetiDpBlocks.cpp: factorisations,
//                                  Phi, S_PiPi^s; DDC_FetiDpOperators.cpp);
//   Preconditioner                 M^{-1} = sum_s B_D^s S^s B_D^sT, the
//                                  Dirichlet blocks K_II, K_ID, K_DD
//                                  (DDC_FetiDpPreconditioner.cpp);
//   InterfaceProblem               BDDC ("Method" = BDDC): the interface
//                                  Schur complement S and the solve on it,
//                                  preconditioned by K~^{-1}
//                                  (DDC_FetiDpBddc.cpp);
//   FetiDpSolver::Impl             the parameters and the driver
//                                  (DDC_FetiDpSolver.cpp), with the
//                                  edge/face change of basis
//                                  (DDC_FetiEdgeFaceConstraints.cpp).
//
// Data layout on each rank: per subdomain, blocks on MPI_COMM_SELF;
// overlapped ("Ov") maps of the DOFs, LMs and coarse DOFs this rank's
// subdomains touch, with Import/Export to the one-to-one owned maps, so that
// every assembly is one Export(ADD) and every distribution one Import. Every
// exchange whose pattern is not a Tpetra map (who shares which DOF, the
// coarse matrix entries) goes through exchangeRecords(), a variable-size
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

/// y[i] += a · Σ v x[j] over the triplets (i, j, v) of `ts`, each run of
/// consecutive triplets of one row summed in a register. The blocks' triplets
/// are stored row by row; updating y[i] entry by entry chained every entry to
/// the store of the one before (such loops were 8 % of a 2,048-subdomain
/// block_3d run in a profile, doc/performance.md).
inline void addTriplets(const std::vector<Triplet>& ts, double a, const double* x, double* y) {
  for (size_t e = 0; e < ts.size();) {
    const LO i = ts[e].i;
    double sum = 0.0;
    for (; e < ts.size() && ts[e].i == i; ++e) sum += ts[e].v * x[ts[e].j];
    y[i] += a * sum;
  }
}

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
  GO lm;        ///< row GID in lmMap
  GO gid;       ///< the DOF
  double full;  ///< the caller's coefficient (in the new basis)
  int side;     ///< the caller's entry's side (Subdomain::sideOf)
};

/// One copy of a split extra-row entry, for local subdomain `localSub`.
struct SplitEntry {
  GO lm;
  int localSub;
  LO dof;
  double full;
  int side;
};

/// A (row, side) key sent to the row's owner.
struct KeyRecord {
  GO key;
};

/// One coarse-matrix entry sent to the owner of its row.
struct CoarseRecord {
  GO row, col;
  double v;
};

/// What every unit reads: the communicator, the parameter path for messages
/// and the DOF maps (owned, and overlapped by this rank's subdomains).
struct Context {
  RCP<const Teuchos::Comm<int>> comm;
  MPI_Comm mpi = MPI_COMM_NULL;
  int rank = 0, size = 1;
  std::string path;
  RCP<const Map> ownedMap, dofOvMap;
  RCP<Import> dofImport;       ///< ownedMap -> dofOvMap
  RCP<Export> dofExport;       ///< dofOvMap -> ownedMap
  std::vector<int> ownedMult;  ///< per owned LID: the number of subdomains having it
  std::string param(const std::string& name) const { return joinPath(path, name); }
};

/// One subdomain as setTopology() leaves it: its DOFs and their roles, the
/// matrix FETI-DP works on, and the diagonals numeric() refreshes.
struct Subdomain {
  int id = -1;
  int index = -1;  ///< rank of id among all subdomain ids (0..number of subdomains - 1)
  /// Per local DOF: the connected part of K^s's graph it lies in (0..). A
  /// METIS subdomain may hold pieces of several bodies that only contact
  /// couples; each piece is one side of a contact row (doc/feti-dp.md
  /// "Extra rows").
  std::vector<int> part;
  int partBase = 0;  ///< global number of part 0: parts are numbered across all subdomains by index
  /// The side of an extra row's entry on local DOF `dof` (a global part number).
  int sideOf(LO dof) const { return partBase + part[size_t(dof)]; }
  std::vector<GO> dofs;
  std::vector<char> primal;
  std::vector<char> constrainable;  ///< per local DOF: extra rows may touch it
  RCP<CrsMatrix> K;      ///< the matrix FETI-DP works on: K^s, or T^T K^s T with edge/face constraints
  RCP<CrsMatrix> Kuser;  ///< the caller's K^s when K is transformed
  ChangeOfBasis cob;     ///< edge/face constraints (identity without)
  LO n = 0;
  // splits (per local DOF -> block index, or kNone)
  std::vector<LO> rIdx, pIdx;  ///< remainder / primal index
  std::vector<LO> rDof, pDof;  ///< block index -> local DOF
  std::vector<LO> dIdx, iIdx;  ///< per remainder index: dual (Delta) / interior index
  std::vector<LO> iR;          ///< interior index -> remainder index
  LO nr = 0, np = 0, nd = 0, ni = 0;
  std::vector<LO> ovLid;        ///< local DOF -> LID in Context::dofOvMap
  std::vector<double> invMult;  ///< local DOF -> 1 / multiplicity
  // values of the last numeric()
  std::vector<double> diag;      ///< K_jj per local DOF (K as FETI-DP works on it)
  std::vector<double> diagUser;  ///< the caller's K^s_jj per local DOF
  int factorizations = 0;        ///< of K_rr (or K^s with Schur rows) since setTopology()
};

/// The block of K (on MPI_COMM_SELF, the contiguous map 0..n-1) of the
/// rows and columns with index[k] != kNone, renumbered index[k] (0..size-1),
/// with K's current values, fill-complete on MPI_COMM_SELF: K_rr or K_II of
/// a subdomain (DDC_FetiDpBlocks.cpp).
RCP<CrsMatrix> extractBlock(const CrsMatrix& K, const std::vector<LO>& index, LO size);

/// A sparse block by rows (CSR): stored row k is LM row `row[k]` (LID in the
/// LM overlapped map) with columns col[ptr[k] .. ptr[k+1]) in the block's
/// local index (remainder, primal or dual index of the subdomain).
struct SparseRows {
  std::vector<LO> row;
  std::vector<size_t> ptr{0};
  std::vector<LO> col;
  std::vector<double> val;
  void clear() {
    row.clear(), col.clear(), val.clear();
    ptr.assign(1, 0);
  }
  /// Append entry (lm, c, v); entries must come sorted by lm.
  void push(LO lm, LO c, double v) {
    if (row.empty() || row.back() != lm) {
      row.push_back(lm);
      ptr.push_back(ptr.back());
    }
    col.push_back(c);
    val.push_back(v);
    ++ptr.back();
  }
  /// y[col] += a * sum over rows of val * x[row]  (B^T x)
  void addTransposed(const double* x, double a, double* y) const {
    for (size_t k = 0; k < row.size(); ++k) {
      const double xk = a * x[row[k]];
      for (size_t e = ptr[k]; e < ptr[k + 1]; ++e) y[col[e]] += val[e] * xk;
    }
  }
  /// y[row] += sum over entries of val * x[col]  (B x)
  void add(const double* x, double* y) const {
    for (size_t k = 0; k < row.size(); ++k) {
      double s = 0.0;
      for (size_t e = ptr[k]; e < ptr[k + 1]; ++e) s += val[e] * x[col[e]];
      y[row[k]] += s;
    }
  }
};

/// The coupling of the extra rows for the next solve()
/// (FetiDpSolver::setConstraintCoupling(), doc/feti-dp.md "Coupled rows"):
/// the multipliers lambda = T x of the dual unknowns x, the equations
/// G (B u) + E x, and the preconditioner's scaling D of the compliant rows.
/// Indices are LIDs of the owned LM map (the rows of a coupling are owned
/// by one rank). T and G differ from the mask P only in the listed rows.
struct RowCoupling {
  struct Term {
    LO i, j;
    double v;
  };
  std::vector<Term> columns;         ///< T(i, j) of the listed rows i
  std::vector<Term> rowsOfG;         ///< G(i, j) of the listed rows i
  std::vector<char> listedT, listedG;  ///< per owned LM LID: row i of T / G is listed
  std::vector<double> compliance;    ///< E's diagonal per owned LM LID (empty: none)
  std::vector<double> scale;         ///< D per owned LM LID (empty: 1)
  bool symmetric = true;             ///< T = Gᵀ on every rank
  /// Whether this rank's rows differ from P (a local question: the
  /// coupling's operations are local to the rank that owns the rows).
  bool any() const { return !columns.empty() || !rowsOfG.empty() || !compliance.empty(); }
};

/// B~ and its weighted B_D: the compatibility rows (one per pair of
/// subdomains sharing a non-primal DOF, +1 / -1), the caller's extra rows,
/// the distributed LM maps, the mask of restrained rows, the right-hand
/// side c, and the scaling weights (doc/feti-dp.md "The jump operator B",
/// "Preconditioner and scaling", "Extra rows").
class JumpOperator {
 public:
  enum class Scaling { Automatic, Multiplicity, Stiffness };

  /// One entry of a constraint row: coefficient `coef` of local DOF `dof` in
  /// LM row `lm` (LID in lmOvMap); `dof` may be a remainder or a primal
  /// DOF; `scaled` = its entry in B_D.
  struct Entry {
    LO lm;
    LO dof;
    double coef;
    double scaled;
    bool extra;  ///< a row from setConstraintRows() (not a compatibility row)
    /// Extra rows: the caller's coefficient before the split over the copies
    /// of a shared dual DOF (coef = full * omega_k), and the LID of the row's
    /// side (Subdomain::sideOf the caller's entry) in sideOvMap.
    double full = 0.0;
    LO sideKey = -1;
    bool split = false;
  };

  /// A constraint entry before the LM maps exist: LM row by its GID in lmMap.
  struct GidEntry {
    GO lm;
    LO dof;
    double coef;
    double full = 0.0;  ///< extra rows: see Entry
    int side = -1;      ///< extra rows: the caller's entry's side (Subdomain::sideOf)
    bool split = false;
  };

  /// The rows of one subdomain: the entries as built, and the sparse blocks
  /// the operators apply (rebuilt by computeWeights()).
  struct Rows {
    std::vector<GidEntry> compat;     ///< compatibility rows (GIDs), from setTopology()
    std::vector<GidEntry> extra;      ///< extra rows in the new basis, split over copies (GIDs)
    std::vector<GidEntry> extraUser;  ///< the caller's extra rows in its basis (GIDs), for the weights
    std::vector<Entry> entries;       ///< all rows (LIDs in lmOvMap), sorted by (lm, dof)
    SparseRows Br, Bp;                ///< B on the remainder / primal DOFs (remainder / primal index)
    SparseRows BDd;                   ///< B_D on the dual DOFs (dual index)
    SparseRows lumped;                ///< extra rows elsewhere: (lm, lm, scaled^2 |K_jj|), a diagonal
  };

  Scaling scaling = Scaling::Automatic;
  std::vector<Rows> rows;  ///< per local subdomain
  RCP<const Map> lmMap, lmOvMap;
  RCP<Import> lmImport;
  RCP<Export> lmExport;
  /// Compatibility rows: GIDs [0, nCompat), this rank's [compatOffset, compatOffset + nCompatOwned).
  GO nCompat = 0, compatOffset = 0, nCompatOwned = 0;
  GO nDual = 0;  ///< non-primal DOFs shared by >= 2 subdomains
  /// Extra rows (setConstraintRows()): GIDs nCompat + extraOffset + (LID in extraRowMap).
  RCP<const Map> extraRowMap;
  GO extraOffset = 0;
  /// On the owner of each shared dual DOF (ownedMap): every copy of it, for
  /// splitting extra rows over the copies.
  std::map<GO, std::vector<ShareRecord>> sharers;
  /// Keys (row GID * sideSpan + side) of the extra rows' sides: owned by the
  /// row's owner (sideMap), and those of this rank's entries (sideOvMap).
  GO sideSpan = 1;
  RCP<const Map> sideMap, sideOvMap;
  RCP<Import> sideImport;
  RCP<Export> sideExport;
  RCP<Vector> mask;        ///< on lmMap: 1 = row in the problem, 0 = restrained to zero (null: all rows)
  RowCoupling coupling;    ///< setConstraintCoupling() (none: T = G = the mask, E = 0)
  RCP<Vector> rhs;         ///< c on lmMap (B u = c); zero on compatibility rows
  RCP<Vector> rowEntries;  ///< number of entries of each row (on lmMap)
  RCP<Vector> lastLambda;  ///< multipliers of the last solve() (on lmMap)
  RCP<Vector> ovWork, work;
  bool weightsCurrent = false;  ///< B_D matches the rows and the last factorised values

  /// The compatibility rows and the LM maps (collective, setTopology()).
  void buildCompatibility(const Context& ctx, const std::vector<Subdomain>& subs);
  /// Extra rows (new basis, LM GIDs) of each local subdomain into
  /// Rows::extra, entries on shared dual DOFs split over all copies.
  /// Returns an error message or "" (collective).
  std::string distributeExtra(const Context& ctx, const std::vector<Subdomain>& subs,
                              const std::vector<std::vector<GidEntry>>& rowsNew);
  /// The LM maps, the entries with LIDs, the side maps, mask, right-hand side
  /// and row counts, from Rows::compat and Rows::extra (collective).
  void finalize(const Context& ctx, const std::vector<Subdomain>& subs);
  /// The weights of B_D and of the split entries, and the sparse blocks
  /// (collective; DDC_FetiDpScaling.cpp).
  void computeWeights(const Context& ctx, const std::vector<Subdomain>& subs);
  /// v <- P v (restrained rows to zero).
  void applyMask(Vector& v) const;
  /// lambda = T x: the multipliers of the dual unknowns x (P x without a
  /// coupling; DDC_FetiDpCoupling.cpp).
  void multipliers(const Vector& x, Vector& lambda) const;
  /// y <- G y (+ E x when x is given): the equations of the dual problem
  /// from the rows' values y = B u (P y without a coupling).
  void equations(Vector& y, const Vector* x) const;
  /// w = D Gᵀ x (P x without a coupling): the preconditioner's input; its
  /// output y <- D G y is equationsScaled().
  void equationsTransposedScaled(const Vector& x, Vector& w) const;
  /// y <- D G y.
  void equationsScaled(Vector& y) const;

 private:
  /// Rows::Br and Bp from the entries, and with `weights` BDd and lumped.
  void assembleBlocks(const std::vector<Subdomain>& subs, bool weights);
};

/// The primal (coarse) problem: the primal DOF map, S_PiPi = sum_s R^T
/// S_PiPi^s R assembled over it, and its distributed direct solver
/// (DDC_FetiDpCoarse.cpp).
class CoarseProblem {
 public:
  /// Where the primal DOFs of one subdomain go.
  struct Indices {
    std::vector<LO> ovLid;   ///< primal index -> LID in ovMap
    std::vector<GO> gid;     ///< primal index -> GID in map
    std::vector<int> owner;  ///< primal index -> rank owning the coarse row
  };
  RCP<const Map> primalMap;  ///< GIDs = DOF ids, owned by the DOF's owner
  RCP<const Map> map;        ///< the same layout numbered 0..n-1 (MUMPS wants that)
  RCP<const Map> ovMap;      ///< the coarse DOFs this rank's subdomains touch
  RCP<Import> import;
  RCP<Export> exporter;
  std::vector<Indices> sub;     ///< per local subdomain
  std::vector<LO> ownedLid;     ///< coarse LID -> ownedMap LID
  std::vector<char> isEdgeFace; ///< coarse LID -> an edge/face constraint value (not a vertex DOF)
  GO n = 0, nEdgeFace = 0;
  RCP<CrsMatrix> matrix;
  std::unique_ptr<DirectSolver> solver;
  RCP<Vector> ovWork, work, sol;
  double tSolve = 0.0;

  /// Maps, the pattern of S_PiPi and the solver (collective).
  void build(const Context& ctx, const std::vector<Subdomain>& subs, const DirectSolverFactory& factory,
             const Teuchos::ParameterList& params);
  /// Sum the S_PiPi^s blocks (dense, column-major, one per local subdomain;
  /// freed afterwards) into the matrix and factorise it (collective).
  /// \throws SolverError if it cannot be factorised.
  void assembleAndFactor(const Context& ctx, std::vector<std::vector<double>>& S, bool analysed);
  /// sol = S_PiPi^{-1} (export of ovWork + fPi), then ovWork = sol on ovMap
  /// (collective).
  void solve(const Vector* fPi);
};

/// The local part of K~^{-1} in one subdomain: the factorisation of K_rr
/// (or of K^s with its primal DOFs as Schur rows, `schur`), Phi^s =
/// K_rr^{-1} K_rPi or the condensation, S_PiPi^s, and work vectors.
struct LocalProblem {
  /// K_rr is not formed: the solver factorises K^s with the primal DOFs as
  /// Schur rows, giving S_PiPi^s directly, and applies K~^{-1} by
  /// condensation / expansion ("Local Schur Complement"); no Phi, K_rPi,
  /// K_Pir or K_PiPi are kept.
  bool schur = false;
  RCP<const Map> rMap;
  RCP<CrsMatrix> Krr;
  std::unique_ptr<DirectSolver> solver;
  std::vector<Triplet> KrP, KPr;  ///< (r, p) and (p, r)
  std::vector<double> KPP;        ///< dense np x np, column-major
  std::vector<double> Phi;        ///< nr x np, column-major (without schur)
  std::vector<double> S;          ///< S_PiPi^s, np x np, column-major (until the coarse assembly)
  double krrNorm1 = 0.0;
  RCP<MultiVector> rB, rX;
  std::vector<double> fr, xr, fp, up;  ///< remainder / primal right-hand side and solution
  std::vector<double> bn, xn;          ///< one value per local DOF (schur: condense / expand)
};

/// K~^{-1} and F = B K~^{-1} B^T: the subdomain factorisations, the coarse
/// problem they feed, and the jump operator around them
/// (DDC_FetiDpBlocks.cpp, DDC_FetiDpOperators.cpp).
class DualOperator {
 public:
  std::vector<LocalProblem> local;  ///< per local subdomain
  bool localSchur = true;           ///< "Local Schur Complement"
  double singularityThreshold = 1e13;
  double tLocalSolve = 0.0;
  int nApply = 0;

  /// The patterns of K_rr and the local solvers.
  void build(const std::vector<Subdomain>& subs, const DirectSolverFactory& factory,
             const Teuchos::ParameterList& localParams, const std::string& where);
  /// Refresh the values of subdomain `ls` from its K (and the diagonals of
  /// Subdomain), factorise, compute Phi^s and S_PiPi^s, check K_rr for
  /// singularity. Returns an error message or "".
  std::string factor(const Context& ctx, Subdomain& s, size_t ls, bool analysed);
  /// (u_r^s, u_Pi) = K~^{-1} (f_r^s, f_Pi), f_Pi = sum_s R^T f_Pi^s + fPi
  /// (fPi on the coarse map, may be null). In: local[].fr, fp; out:
  /// local[].xr, up and coarse.sol.
  void applyKtildeInv(const std::vector<Subdomain>& subs, CoarseProblem& coarse, const Vector* fPi);
  /// f^s (+)= sign B^sT lambda into local[].fr, fp.
  void scatterBt(const JumpOperator& jump, const Vector& lambda, double sign);
  /// y = B u, u = (local[].xr, up).
  void gatherB(const JumpOperator& jump, Vector& y);
  /// y = P F P x.
  void apply(const std::vector<Subdomain>& subs, JumpOperator& jump, CoarseProblem& coarse, const Vector& x,
             Vector& y);
};

/// The preconditioner M^{-1} = sum_s B_D^s S^s B_D^sT (doc/feti-dp.md
/// "Preconditioner and scaling"): Dirichlet, S^s = K_DD - K_DI K_II^{-1}
/// K_ID; lumped, S^s = K_DD; or none (DDC_FetiDpPreconditioner.cpp).
class Preconditioner {
 public:
  enum class Kind { Dirichlet, Lumped, None };
  /// The blocks of one subdomain.
  struct Blocks {
    RCP<const Map> iMap;
    RCP<CrsMatrix> Kii;
    std::unique_ptr<DirectSolver> solver;  ///< K_II (Dirichlet only)
    std::vector<Triplet> KID, KDI, KDD;    ///< (I, Delta), (Delta, I), (Delta, Delta)
    RCP<MultiVector> iB, iX;
    std::vector<double> vd, wd, vi, wi;
  };
  Kind kind = Kind::Dirichlet;
  /// BDDC: factorise K_II in every subdomain with interior DOFs, also those
  /// without dual DOFs (BDDC's S solves with it), and keep none of the
  /// K_ID, K_DI, K_DD blocks (BDDC's preconditioner is K~^{-1}, not this one).
  bool interiorsOnly = false;
  std::vector<Blocks> blocks;  ///< per local subdomain
  double tApply = 0.0, tDirichletSolve = 0.0;
  int nApply = 0;

  /// The patterns of K_II and the solvers.
  void build(const std::vector<Subdomain>& subs, const DirectSolverFactory& factory,
             const Teuchos::ParameterList& localParams, const std::string& where);
  /// Refresh the blocks' values from each K and factorise K_II (collective
  /// error). \throws SolverError naming the subdomain.
  void factor(const Context& ctx, const std::vector<Subdomain>& subs, bool analysed);
  /// y = D G M^{-1} Gᵀ D x (P M^{-1} P x without coupled rows).
  void apply(const std::vector<Subdomain>& subs, const JumpOperator& jump, const Vector& x, Vector& y);
};

/// The interior index of local DOF k of s (kNone for interface DOFs: dual
/// and primal).
inline LO interiorIndex(const Subdomain& s, LO k) { return s.rIdx[k] == kNone ? kNone : s.iIdx[s.rIdx[k]]; }

/// BDDC on FETI-DP's blocks (DDC_FetiDpBddc.cpp, doc/feti-dp.md "BDDC"):
/// the interface problem S u_G = g on the DOFs that are not interior to a
/// subdomain (dual and primal), S = sum_s R^sT (K_GG - K_GI K_II^{-1} K_IG)
/// R^s applied subdomain by subdomain with the Dirichlet preconditioner's
/// K_II factorisations; its preconditioner is K~^{-1} between weighted
/// restrictions (FetiDpSolver::Impl::applyBddcPreconditioner()).
class InterfaceProblem {
 public:
  /// The blocks of one subdomain, in interface (G) and interior (I) index.
  struct Blocks {
    std::vector<LO> gDof;                ///< interface index -> local DOF
    std::vector<LO> gIdx;                ///< local DOF -> interface index (kNone: interior)
    std::vector<Triplet> KIG, KGI, KGG;  ///< (I, G), (G, I), (G, G)
    std::vector<double> xg, wg, vi, zi;  ///< work; zi: K_II^{-1} b_I of the current solve()
  };
  RCP<const Map> map;        ///< the interface DOFs, owned as in Context::ownedMap
  std::vector<LO> ownedLid;  ///< interface LID -> ownedMap LID
  std::vector<Blocks> blocks;  ///< per local subdomain
  RCP<Vector> owned, ov;       ///< work on Context::ownedMap / dofOvMap
  std::vector<double> yOvWork;  ///< applySchur()'s sums on dofOvMap
  int nApply = 0;  ///< applications of S in the last solve()

  /// The interface map and index lists (collective). \throws
  /// std::logic_error if a DOF is interior in one subdomain and shared.
  void build(const Context& ctx, const std::vector<Subdomain>& subs);
  /// K_IG, K_GI, K_GG from each subdomain's current K.
  void refresh(const std::vector<Subdomain>& subs);
  /// owned = x on the interface, 0 elsewhere; ov = its import.
  void scatter(const Context& ctx, const Vector& x);
  /// y = the interface entries of the export (ADD) of yOv.
  void gather(const Context& ctx, const std::vector<double>& yOv, Vector& y);
  /// y = S x (collective).
  void applySchur(const Context& ctx, const std::vector<Subdomain>& subs, Preconditioner& prec, const Vector& x,
                  Vector& y);
};

}  // namespace feti_internal

using namespace feti_internal;

// ---------------------------------------------------------------------------
// Impl: the parameters, the units, and what solve() reports
// ---------------------------------------------------------------------------

struct FetiDpSolver::Impl {
  Context ctx;
  // configuration
  PrimalConstraints primalChoice = PrimalConstraints::VerticesAndEdges;
  bool automaticPrimal = true;  ///< "Primal Constraints" = Automatic (setAutomaticPrimalConstraints())
  bool rotations = true;  ///< "Rotational Constraints"
  std::string belosType = "CG";
  bool belosGmresOnBreakdown = true;
  double belosTol = 1e-10;  ///< "Belos/Convergence Tolerance"
  double solveTol = 1e-10;  ///< the next solve()'s (setSolveTolerance())
  int belosMaxIt = 500;
  int belosVerbosity = 0;
  int belosOutputFrequency = -1;
  Teuchos::ParameterList belosExtra;  ///< other Belos parameters, passed through
  Teuchos::ParameterList localSolverParams, coarseSolverParams;
  DirectSolverFactory factory = DirectSolverFactory::withBuiltins();

  // state
  bool haveTopology = false, analysed = false, factored = false;
  std::vector<Subdomain> subs;
  JumpOperator jump;
  CoarseProblem coarse;
  DualOperator dual;
  Preconditioner prec;
  RCP<Vector> dofOvWork;
  Info setup;
  RCP<Operator> fOp, mOp;

  bool couplingScaled = false;  ///< RowCoupling::scale is that of the current coupling and factorisation
  bool bddc = false;            ///< "Method" = BDDC, or Automatic resolved to it (setAutomaticMethod())
  bool automaticMethod = false;  ///< "Method" = Automatic
  std::string bddcConflict;     ///< the option BDDC cannot honour ("" if none)
  bool coarsePrecisionOpen = false;  ///< a MUMPS coarse solver whose precision the parameters leave open
  InterfaceProblem iface;       ///< BDDC only

  /// DualOperator::local[].fr, fp from b (DDC_FetiDpSolver.cpp).
  void loadForces(const Vector& b);
  /// The same from b on Context::dofOvMap.
  void loadOverlapForces(const Vector& bOv);
  /// The coarse right-hand side at the primal vertex DOFs from b.
  void primalForces(const Vector& b, Vector& fPi) const;
  /// u from the subdomain solutions and the coarse solution (weighted average).
  void assembleDisplacement(Vector& u);
  /// BDDC: z = M^{-1} r on the interface map (DDC_FetiDpBddc.cpp).
  void applyBddcPreconditioner(const Vector& r, Vector& z);
  /// FETI-DP: u from b, iterations into info; returns Belos' seconds
  /// (DDC_FetiDpSolver.cpp).
  double solveDual(const Vector& b, Vector& u, FetiDpSolver::Info& info);
  /// BDDC: u from b, iterations into info; returns Belos' seconds
  /// (DDC_FetiDpBddc.cpp).
  double solveBddc(const Vector& b, Vector& u, FetiDpSolver::Info& info);
  /// x from A x = rhs by Belos with the preconditioner M (may be null);
  /// `system` names it in messages (DDC_FetiDpSolver.cpp).
  void solveByBelos(const RCP<Operator>& A, const RCP<Operator>& M, const RCP<MultiVector>& rhs,
                    const RCP<MultiVector>& x, bool symmetric, const std::string& system, FetiDpSolver::Info& info);

  std::string param(const std::string& name) const { return ctx.param(name); }
  /// RowCoupling::scale of the compliant rows (DDC_FetiDpCoupling.cpp).
  void scaleCompliantRows();

  /// setTopology() (DDC_FetiDpInterface.cpp).
  void buildTopology(std::vector<FetiSubdomain> local, RCP<const Map> owned);
  /// Edge/face constraints by change of basis (DDC_FetiDpInterface.cpp).
  void addEdgeFaceConstraints(const std::vector<std::vector<int>>& components,
                              const std::vector<std::vector<double>>& coords, const std::vector<int>& dims);
  /// fOp and mOp (DDC_FetiDpOperators.cpp).
  void makeOperators();
};

}  // namespace ddc
