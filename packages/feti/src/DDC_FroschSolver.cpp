// "Belos-FROSch": Belos GMRES right-preconditioned by FROSch's two-level
// overlapping Schwarz preconditioner with a GDSW coarse space (see
// DDC_IterativeSolvers.hpp for the contract).
//
// Pitfalls of Debian's Trilinos 13.2 (doc/trilinos-notes.md): FROSch headers
// compile only after ShyLU_DDFROSch_config.h and FROSch_Tools_def.hpp, in this order, and
// FROSch_Tools_def.hpp itself needs Xpetra_MapFactory.hpp first (it uses
// Xpetra::MapFactory without including it).
// With HAVE_SHYLU_DDFROSCH_ZOLTAN2, FROSch_Tools_decl.hpp and
// FROSch_CoarseOperator_decl.hpp include Zoltan2 headers, which need
// /usr/include/scotch (ptscotch.h) on the include path. We switch that off
// for this file: it only removes the "Zoltan2" coarse "Distribution" type
// (we gather the coarse problem "linear"ly to one rank) and changes no class
// layout; FROSch is header-only (libtrilinos_shylu_ddfrosch.so exports no
// FROSch symbols) and used by no other file, so nothing else sees a
// different definition.
// clang-format off
#include <Xpetra_MapFactory.hpp>
#include <ShyLU_DDFROSch_config.h>
#undef HAVE_SHYLU_DDFROSCH_ZOLTAN2
#include <FROSch_Tools_def.hpp>
#include <FROSch_TwoLevelPreconditioner_def.hpp>
// clang-format on
#include <Xpetra_CrsMatrixWrap.hpp>
#include <Xpetra_TpetraCrsMatrix.hpp>
#include <Xpetra_TpetraMultiVector.hpp>
#include <iostream>
#include <sstream>

#include "DDC_Error.hpp"
#include "DDC_IterativeSolvers.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

using Operator = IterativeSolver::Operator;

using XMultiVector = Xpetra::MultiVector<Scalar, LO, GO, Node>;
using XTpetraMultiVector = Xpetra::TpetraMultiVector<Scalar, LO, GO, Node>;

/// While alive, std::cout output is dropped (FROSch prints its setup
/// tables on rank 0 whatever its "Verbosity" parameters say).
class MuteStdout {
 public:
  explicit MuteStdout(bool mute) : saved_(mute ? std::cout.rdbuf(nullptr) : nullptr), mute_(mute) {}
  ~MuteStdout() {
    if (mute_) {
      std::cout.rdbuf(saved_);
      std::cout.clear();
    }
  }
  MuteStdout(const MuteStdout&) = delete;
  MuteStdout& operator=(const MuteStdout&) = delete;

 private:
  std::streambuf* saved_;
  bool mute_;
};

/// TwoLevelPreconditioner exposing its coarse operator (for the coarse
/// dimension); nothing else changes.
class TwoLevel : public FROSch::TwoLevelPreconditioner<Scalar, LO, GO, Node> {
 public:
  using Base = FROSch::TwoLevelPreconditioner<Scalar, LO, GO, Node>;
  using Base::Base;
  long long coarseDimension() const {
    if (this->CoarseOperator_.is_null() || this->CoarseOperator_->getCoarseSpace().is_null()) return 0;
    auto map = this->CoarseOperator_->getCoarseSpace()->getBasisMapUnique();
    return map.is_null() ? 0 : static_cast<long long>(map->getGlobalNumElements());
  }
};

/// The FROSch preconditioner (an Xpetra operator) seen as a Tpetra operator,
/// so Belos runs on plain Tpetra types for both iterative back ends.
class FroschOperator : public Operator {
 public:
  FroschOperator(Teuchos::RCP<TwoLevel> prec, Teuchos::RCP<const Map> map)
      : prec_(std::move(prec)), map_(std::move(map)) {}
  Teuchos::RCP<const Map> getDomainMap() const override { return map_; }
  Teuchos::RCP<const Map> getRangeMap() const override { return map_; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             Scalar alpha = Teuchos::ScalarTraits<Scalar>::one(),
             Scalar beta = Teuchos::ScalarTraits<Scalar>::zero()) const override {
    // Xpetra's wrapper needs a non-const RCP; FROSch only reads X.
    XTpetraMultiVector x(Teuchos::rcp_const_cast<MultiVector>(Teuchos::rcpFromRef(X)));
    XTpetraMultiVector y(Teuchos::rcpFromRef(Y));
    prec_->apply(x, y, mode, alpha, beta);
  }

 private:
  Teuchos::RCP<TwoLevel> prec_;
  Teuchos::RCP<const Map> map_;
};

/// Our FROSch defaults (documented in getValidParameters()).
Teuchos::ParameterList defaultFroschList() {
  Teuchos::ParameterList p("FROSch");
  auto klu = [](Teuchos::ParameterList& s) {
    s.set("SolverType", std::string("Amesos2"), "FROSch solver wrapper");
    s.set("Solver", std::string("Klu"), "Amesos2 KLU2 (on a one-rank communicator here: correct)");
  };
  p.set("OverlappingOperator Type", std::string("AlgebraicOverlappingOperator"),
        "first level: subdomains = each rank's rows grown by 'Overlap' layers of the matrix graph");
  p.set("CoarseOperator Type", std::string("IPOUHarmonicCoarseOperator"),
        "second level: interface partition of unity (GDSW) times the near-null space, extended harmonically "
        "into the subdomains; 'GDSWCoarseOperator' is the classical GDSW space (rotations from the node "
        "coordinates instead of the solver's null space)");
  p.set("Null Space Type", std::string("Input"),
        "'Input': the near-null space of the solver's 'Null Space' parameter (do not change)");
  p.set("Level Combination", std::string("Additive"), "first and second level added (symmetric)");
  {
    Teuchos::ParameterList& o = p.sublist("AlgebraicOverlappingOperator", false, "first level");
    o.set("Combine Values in Overlap", std::string("Restricted"),
          "restricted additive Schwarz (each rank keeps its own rows of the local solution); GMRES copes with "
          "the nonsymmetry");
    klu(o.sublist("Solver", false, "subdomain solver (one per rank, on MPI_COMM_SELF)"));
  }
  {
    Teuchos::ParameterList& c = p.sublist("IPOUHarmonicCoarseOperator", false, "second level");
    Teuchos::ParameterList& b = c.sublist("Blocks", false, "one block: all DOFs").sublist("1", false, "");
    b.set("Use For Coarse Space", true, "build a coarse space for this block");
    b.set("Rotations", true, "use the rotation of the null space too");
    Teuchos::ParameterList& ipou = b.sublist("InterfacePartitionOfUnity", false, "interface partition of unity");
    ipou.set("Type", std::string("GDSW"), "GDSW: vertices and edges of the interface as components");
    ipou.sublist("GDSW", false, "").set("Type", std::string("Full"), "all interface components");
    klu(c.sublist("ExtensionSolver", false, "solver of the harmonic extensions (per rank)"));
    Teuchos::ParameterList& d = c.sublist("Distribution", false, "where the coarse problem is solved");
    d.set("Type", std::string("linear"), "gather the coarse matrix ...");
    d.set("NumProcs", 1,
          "... to this many ranks (1: KLU2 on a one-rank communicator, which is correct; "
          "KLU2 on a distributed matrix is wrong in this Trilinos, doc/trilinos-notes.md)");
    klu(c.sublist("CoarseSolver", false, "coarse solver (on the ranks of 'Distribution')"));
  }
  {
    Teuchos::ParameterList& c =
        p.sublist("GDSWCoarseOperator", false, "second level if 'CoarseOperator Type' = 'GDSWCoarseOperator'");
    Teuchos::ParameterList& b = c.sublist("Blocks", false, "one block: all DOFs").sublist("1", false, "");
    b.set("Use For Coarse Space", true, "build a coarse space for this block");
    b.set("Rotations", true, "rotations of the interface components (from the node coordinates)");
    klu(c.sublist("ExtensionSolver", false, "solver of the harmonic extensions (per rank)"));
    Teuchos::ParameterList& d = c.sublist("Distribution", false, "where the coarse problem is solved");
    d.set("Type", std::string("linear"), "gather the coarse matrix ...");
    d.set("NumProcs", 1, "... to this many ranks (1: see IPOUHarmonicCoarseOperator)");
    klu(c.sublist("CoarseSolver", false, "coarse solver (on the ranks of 'Distribution')"));
  }
  return p;
}

/// Paths (joined by '/') of every non-list entry of `user`, recursively.
void collectPaths(const Teuchos::ParameterList& user, const std::string& prefix, std::vector<std::string>& out) {
  for (auto it = user.begin(); it != user.end(); ++it) {
    const std::string path = joinPath(prefix, user.name(it));
    if (user.isSublist(user.name(it))) {
      collectPaths(user.sublist(user.name(it)), path, out);
    } else {
      out.push_back(path);
    }
  }
}

/// The entry at `path` of `list` (nullptr if absent).
const Teuchos::ParameterEntry* entryAt(const Teuchos::ParameterList& list, const std::string& path) {
  const Teuchos::ParameterList* cur = &list;
  size_t start = 0;
  for (;;) {
    const size_t slash = path.find('/', start);
    const std::string part = path.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    if (slash == std::string::npos) return cur->getEntryPtr(part);
    if (!cur->isSublist(part)) return nullptr;
    cur = &cur->sublist(part);
    start = slash + 1;
  }
}

}  // namespace

struct FroschSolver::Impl {
  int overlap = 1;
  Teuchos::ParameterList user;                // the user's "FROSch" sublist, for the unused-entry check
  Teuchos::RCP<Teuchos::ParameterList> live;  // the list FROSch reads
  Teuchos::RCP<TwoLevel> prec;
  Teuchos::RCP<FroschOperator> op;
  bool checkedUnused = false;
};

Teuchos::RCP<const Teuchos::ParameterList> FroschSolver::getValidParameters() {
  static const Teuchos::RCP<const Teuchos::ParameterList> valid = [] {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList(kType));
    addCommonParameters(*pl, "Belos pseudo-block GMRES (restarted after 200 vectors), right-preconditioned.");
    pl->set("Overlap", 1, "layers of matrix-graph neighbours added to each rank's rows to form its subdomain",
            atLeast(0));
    pl->sublist("FROSch", false,
                "FROSch::TwoLevelPreconditioner's parameter list, applied over the defaults shown here entry by entry. "
                "FROSch does not validate it: after the first numeric() every entry you set that FROSch did not read "
                "is an error (misspelt, or not used with the chosen options).")
        .setParameters(defaultFroschList());
    return Teuchos::RCP<const Teuchos::ParameterList>(pl);
  }();
  return valid;
}

FroschSolver::FroschSolver(const Teuchos::ParameterList& params)
    : IterativeSolver(
          [&] {
            Teuchos::ParameterList p(params);
            validateLevel(p, *getValidParameters(), kType);
            return p;
          }(),
          kType, "GMRES"),
      impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  if (params.isParameter("Overlap")) m.overlap = params.get<int>("Overlap");
  if (params.isSublist("FROSch")) m.user = params.sublist("FROSch");
  for (const char* fixed : {"Dimension", "DofsPerNode", "Overlap"})
    DDC_INPUT_REQUIRE(!m.user.isParameter(fixed), "parameter '" << kType << "/FROSch/" << fixed << "' is set by the "
                                                                << "solver (the spatial dimension and DOFs per "
                                                                << "node, 2 or 3, and '" << kType
                                                                << "/Overlap'); remove it");
}

FroschSolver::~FroschSolver() = default;

long long FroschSolver::coarseDimension() const { return impl_->prec.is_null() ? 0 : impl_->prec->coarseDimension(); }

Teuchos::RCP<Operator> FroschSolver::buildPreconditioner(bool first, const Teuchos::RCP<MultiVector>& nullSpace,
                                                         const Teuchos::RCP<MultiVector>& nodeCoords) {
  Impl& m = *impl_;
  const auto map = A_->getRowMap();
  const MuteStdout mute(verbosity_ == 0);
  try {
    if (first || m.prec.is_null()) {
      m.live = Teuchos::rcp(new Teuchos::ParameterList(defaultFroschList()));
      m.live->setParameters(m.user);
      Teuchos::RCP<Xpetra::CrsMatrix<Scalar, LO, GO, Node>> xA =
          Teuchos::rcp(new Xpetra::TpetraCrsMatrix<Scalar, LO, GO, Node>(Teuchos::rcp_const_cast<CrsMatrix>(A_)));
      Teuchos::RCP<const Xpetra::Matrix<Scalar, LO, GO, Node>> K =
          Teuchos::rcp(new Xpetra::CrsMatrixWrap<Scalar, LO, GO, Node>(xA));
      // FROSch 13.2 never finds the Dirichlet rows itself (the result of
      // FindOneEntryOnlyRowsGlobal goes to a shadowing local variable in
      // TwoLevelPreconditioner::initialize), so pass them: rows whose only
      // entry is the diagonal (identity rows).
      auto repeatedMap = FROSch::BuildRepeatedMap<LO, GO, Node>(K->getCrsGraph());
      auto dirichlet = FROSch::FindOneEntryOnlyRowsGlobal<LO, GO, Node>(K->getCrsGraph(), repeatedMap);
      Teuchos::RCP<const XMultiVector> xNull = Teuchos::rcp(new XTpetraMultiVector(nullSpace));
      Teuchos::RCP<const XMultiVector> xNodes;
      if (!nodeCoords.is_null()) xNodes = Teuchos::rcp(new XTpetraMultiVector(nodeCoords));
      m.prec = Teuchos::rcp(new TwoLevel(K, m.live));
      // Dimension and DOFs per node are both d: displacement-only elasticity.
      const int d = dofsPerNode();
      const int ri =
          m.prec->initialize(d, d, m.overlap, xNull, xNodes, FROSch::NodeWise, repeatedMap, Teuchos::null, dirichlet);
      if (ri < 0) DDC_THROW(SolverError, name() << ": FROSch initialize() returned " << ri);
      m.op = Teuchos::rcp(new FroschOperator(m.prec, map));
    }
    const int rc = m.prec->compute();
    if (rc < 0) DDC_THROW(SolverError, name() << ": FROSch compute() returned " << rc);
  } catch (const SolverError&) {
    throw;
  } catch (const std::exception& e) {
    DDC_THROW(SolverError, name() << " setup of the FROSch preconditioner failed: " << lastLineOf(e));
  }
  if (!m.checkedUnused) {
    // Some entries are read on some ranks only (the coarse solver's on the
    // coarse ranks): an entry counts as read if any rank read it, so every
    // rank reaches the same verdict (the user list is the same everywhere).
    std::vector<std::string> paths, unused;
    collectPaths(m.user, "", paths);
    std::vector<int> readLocal(paths.size(), 0), read(paths.size(), 0);
    for (size_t i = 0; i < paths.size(); ++i) {
      const auto* e = entryAt(*m.live, paths[i]);
      readLocal[i] = (e != nullptr && e->isUsed()) ? 1 : 0;
    }
    if (!paths.empty())
      Teuchos::reduceAll(*map->getComm(), Teuchos::REDUCE_MAX, int(paths.size()), readLocal.data(), read.data());
    for (size_t i = 0; i < paths.size(); ++i)
      if (!read[i]) unused.push_back("'" + joinPath(std::string(kType) + "/FROSch", paths[i]) + "'");
    if (!unused.empty()) {
      std::ostringstream os;
      for (size_t i = 0; i < unused.size(); ++i) os << (i ? ", " : "") << unused[i];
      DDC_THROW(InputError, "parameter" << (unused.size() > 1 ? "s " : " ") << os.str() << " not read by FROSch "
                                        << "(misspelt, or not used with the chosen options); valid names are in "
                                        << "the FROSch sources / the defaults of '" << kType << "/FROSch'");
    }
    m.checkedUnused = true;
  }
  return m.op;
}

}  // namespace ddc
