// "Belos-MueLu": Belos CG preconditioned by one MueLu smoothed-aggregation
// V-cycle (see DDC_IterativeSolvers.hpp for the contract).
#include <MueLu_CreateTpetraPreconditioner.hpp>
#include <MueLu_Hierarchy.hpp>
#include <MueLu_MasterList.hpp>
#include <MueLu_ParameterListInterpreter.hpp>
#include <MueLu_TpetraOperator.hpp>
#include <sstream>
#include <type_traits>

#include "DDC_Error.hpp"
#include "DDC_IterativeSolvers.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

using Operator = IterativeSolver::Operator;

/// Our MueLu defaults for elasticity (documented in getValidParameters()).
Teuchos::ParameterList defaultMueLuList() {
  Teuchos::ParameterList p("MueLu");
  p.set("verbosity", std::string("none"),
        "MueLu output ('none', 'low', 'medium', 'high', 'extreme'); "
        "'low' if Verbosity >= 1 and this is not set");
  p.set("number of equations", 2,
        "DOFs per node (aggregation works on nodes): set by the solver to the spatial dimension, 2 or 3 "
        "(setDofsPerNode() / the coordinates' columns); do not set");
  p.set("multigrid algorithm", std::string("sa"), "smoothed aggregation");
  p.set("max levels", 10, "most levels of the hierarchy");
  p.set("aggregation: type", std::string("uncoupled"), "aggregates do not cross rank boundaries");
  p.set("aggregation: drop tol", 0.0, "no dropping of weak connections (structured, isotropic meshes)");
  p.set("smoother: type", std::string("CHEBYSHEV"),
        "Chebyshev polynomial smoothing: symmetric (CG needs a symmetric preconditioner) and identical on "
        "any number of ranks");
  {
    Teuchos::ParameterList& s = p.sublist("smoother: params", false, "Ifpack2 parameters of the smoother");
    s.set("chebyshev: degree", 2, "polynomial degree (smoothing sweeps per application)");
    // The polynomial is built on [lambdaMax/20, boost*lambdaMax] of D^-1 A; a
    // lambdaMax below the true one makes the V-cycle indefinite and CG
    // breaks down ("non-positive p^H*A*p"). Ifpack2's 10 power iterations
    // reached 0.86 of the true 3.09 on 3-D Hex8 elasticity (block_3d, 107k
    // DOFs): 2.67 * 1.1 < 3.09. 30 iterations gave 0.92-0.95 from 107k to
    // 1.1M DOFs, so the boost of 1.2 keeps a 10 % margin (doc/performance.md).
    s.set("chebyshev: eigenvalue max iterations", 30,
          "power iterations estimating the largest eigenvalue of D^-1 A (Ifpack2's default: 10)");
    s.set("chebyshev: boost factor", 1.2,
          "the estimate is multiplied by this (Ifpack2's default: 1.1): an underestimate makes the "
          "preconditioner indefinite");
  }
  p.set("transpose: use implicit", true,
        "the restriction R = P^T is applied as a transpose product of P instead of being stored: less memory "
        "at the same iterations (doc/performance.md, \"The matrix assembled in place\")");
  // With 1000, block_3d's hierarchy on 8-16 ranks (uncoupled aggregates
  // stop at rank boundaries) had a level of about 1300 rows coarsened once
  // more to 24: CG took 29-31 iterations against 20 on one rank; solving
  // that level directly gives 20-22 on 1-16 ranks at the same memory and
  // set-up time (doc/performance.md, "Belos-MueLu on more ranks").
  p.set("coarse: max size", 2000, "stop coarsening below this many rows");
  p.set("coarse: type", std::string("KLU2"),
        "exact coarse solve; correct in parallel only because repartitioning moves the coarse level to one "
        "rank (KLU2 on a distributed matrix is wrong in this Trilinos, doc/trilinos-notes.md)");
  p.set("repartition: enable", true,
        "rebalance levels with too few rows per rank; with 'repartition: use subcommunicators' a level of "
        "fewer than 'repartition: min rows per proc' rows ends up on a one-rank communicator");
  p.set("repartition: partitioner", std::string("zoltan2"), "Zoltan2 (geometric, from the node coordinates)");
  {
    Teuchos::ParameterList& z = p.sublist("repartition: params", false, "Zoltan2 parameters");
    z.set("algorithm", std::string("multijagged"), "geometric partitioner using the node coordinates");
  }
  p.set("repartition: start level", 1, "repartition from level 1 (the fine level stays as given)");
  p.set("repartition: min rows per proc", 2000,
        "a rank should own at least this many rows; a level with fewer rows in total goes to one rank, "
        "so the coarsest level (<= 'coarse: max size') always does");
  p.set("repartition: max imbalance", 1.2, "repartition when max/mean rows per rank exceeds this");
  p.set("repartition: use subcommunicators", true, "levels on fewer ranks get their own communicator");
  return p;
}

/// KLU2 solves the coarsest level right only on one rank (doc/trilinos-notes.md):
/// repartitioning puts a level of fewer than 'repartition: min rows per
/// proc' rows on one rank, so the coarsest (at most 'coarse: max size'
/// rows) must not be larger. \throws InputError naming both parameters.
void requireOneRankCoarseLevel(const Teuchos::ParameterList& list) {
  auto value = [&](const char* name, const auto& fallback) {
    using T = std::decay_t<decltype(fallback)>;
    return list.isType<T>(name) ? list.get<T>(name) : fallback;
  };
  if (value("coarse: type", std::string("KLU2")) != "KLU2" || !value("repartition: enable", true)) return;
  const int maxSize = value("coarse: max size", 2000), minRows = value("repartition: min rows per proc", 2000);
  DDC_INPUT_REQUIRE(maxSize <= minRows,
                    "parameter '" << MueLuSolver::kType << "/MueLu/coarse: max size' (" << maxSize
                                  << ") is above 'repartition: min rows per proc' (" << minRows
                                  << "): a coarsest level of up to " << maxSize
                                  << " rows could be spread over several ranks, where the coarse solver KLU2 is "
                                     "wrong in this Trilinos (doc/trilinos-notes.md); raise 'repartition: min rows "
                                     "per proc' with it, or choose another 'coarse: type'");
}

}  // namespace

struct MueLuSolver::Impl {
  Teuchos::ParameterList mueluList;  // defaults overridden by the user's entries
  bool reuse = false;                // "reuse: type" != "none"
  bool userSetRepartition = false;   // the user's list has "repartition: enable"
  bool userSetCoarse = false;        // ... "coarse: type"
  Teuchos::RCP<MueLu::TpetraOperator<Scalar, LO, GO, Node>> prec;
};

Teuchos::RCP<const Teuchos::ParameterList> MueLuSolver::getValidParameters() {
  static const Teuchos::RCP<const Teuchos::ParameterList> valid = [] {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList(kType));
    addCommonParameters(*pl, "Belos pseudo-block CG, preconditioned by one MueLu V-cycle.");
    pl->sublist("MueLu", false,
                "MueLu's own parameter list (MueLu user guide, 'simple' parameter names), applied over the defaults "
                "shown here entry by entry and validated by MueLu itself when the solver is created. The near-null "
                "space and coordinates are set by the solver ('user data'): do not set them.")
        .setParameters(defaultMueLuList());
    return Teuchos::RCP<const Teuchos::ParameterList>(pl);
  }();
  return valid;
}

MueLuSolver::MueLuSolver(const Teuchos::ParameterList& params)
    : IterativeSolver(
          [&] {
            Teuchos::ParameterList p(params);
            validateLevel(p, *getValidParameters(), kType);
            return p;
          }(),
          kType, "CG"),
      impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.mueluList = defaultMueLuList();
  if (params.isSublist("MueLu")) {
    const Teuchos::ParameterList& user = params.sublist("MueLu");
    DDC_INPUT_REQUIRE(!user.isSublist("user data") && !user.isParameter("user data"),
                      "parameter '" << kType << "/MueLu/user data' is set by the solver (near-null space, "
                                    << "coordinates); remove it");
    DDC_INPUT_REQUIRE(!user.isParameter("number of equations"),
                      "parameter '" << kType << "/MueLu/number of equations' is set by the solver (the DOFs per "
                                    << "node: 2 in 2-D, 3 in 3-D); remove it");
    // A user who changes a method keeps none of our options for the old
    // one (e.g. "chebyshev: degree" would be rejected by a RELAXATION smoother).
    for (const auto& [method, options] : {std::pair<const char*, const char*>{"smoother: type", "smoother: params"},
                                          {"coarse: type", "coarse: params"},
                                          {"repartition: partitioner", "repartition: params"}})
      if (user.isParameter(method)) m.mueluList.remove(options, /*throwIfNotExists=*/false);
    m.mueluList.setParameters(user);
    m.userSetRepartition = user.isParameter("repartition: enable");
    m.userSetCoarse = user.isParameter("coarse: type");
  }
  requireOneRankCoarseLevel(m.mueluList);
  if (verbosity_ >= 1 && !(params.isSublist("MueLu") && params.sublist("MueLu").isParameter("verbosity")))
    m.mueluList.set("verbosity", "low");
  // Let MueLu validate the list now (its master list, top level and
  // "level N" sublists), so a misspelt name fails at input time.
  // (MueLu's default verbosity would print its spelling suggestions.)
  const auto verb = MueLu::VerboseObject::GetDefaultVerbLevel();
  MueLu::VerboseObject::SetDefaultVerbLevel(MueLu::None);
  try {
    Teuchos::ParameterList copy(m.mueluList);
    MueLu::ParameterListInterpreter<Scalar, LO, GO, Node> check(copy);
  } catch (const std::exception& e) {
    MueLu::VerboseObject::SetDefaultVerbLevel(verb);
    DDC_THROW(InputError, "invalid parameter in '" << kType << "/MueLu' (MueLu says: " << lastLineOf(e) << ")");
  }
  MueLu::VerboseObject::SetDefaultVerbLevel(verb);
  m.reuse = m.mueluList.isParameter("reuse: type") && m.mueluList.get<std::string>("reuse: type") != "none";
}

MueLuSolver::~MueLuSolver() = default;

int MueLuSolver::numLevels() const {
  if (impl_->prec.is_null()) return 0;
  return impl_->prec->GetHierarchy()->GetNumLevels();
}

Teuchos::RCP<Operator> MueLuSolver::buildPreconditioner(bool first, const Teuchos::RCP<MultiVector>& nullSpace,
                                                        const Teuchos::RCP<MultiVector>& nodeCoords) {
  Impl& m = *impl_;
  // MueLu needs a non-const matrix type but does not modify it.
  auto A = Teuchos::rcp_const_cast<CrsMatrix>(A_);
  try {
    if (!first && m.reuse && !m.prec.is_null()) {
      MueLu::ReuseTpetraPreconditioner(A, *m.prec);
    } else {
      Teuchos::ParameterList list(m.mueluList);
      if (nodeCoords.is_null() && !m.userSetRepartition) {
        // Repartitioning needs coordinates (geometric partitioner, and MueLu
        // transfers them level by level). Without them: no repartitioning,
        // and, since KLU2 on a distributed coarse matrix is wrong here
        // (doc/trilinos-notes.md), a Chebyshev polynomial as coarse solver (symmetric,
        // so CG still applies), unless the user chose one.
        list.set("repartition: enable", false);
        if (!m.userSetCoarse) {
          list.set("coarse: type", "CHEBYSHEV");
          list.sublist("coarse: params").set("chebyshev: degree", 10);
        }
      }
      list.set("number of equations", dofsPerNode());
      Teuchos::ParameterList& user = list.sublist("user data");
      user.set("Nullspace", nullSpace);
      if (!nodeCoords.is_null()) user.set("Coordinates", nodeCoords);
      m.prec = MueLu::CreateTpetraPreconditioner(Teuchos::RCP<Operator>(A), list);
    }
  } catch (const std::exception& e) {
    DDC_THROW(SolverError, name() << " setup of the MueLu hierarchy failed: " << lastLineOf(e));
  }
  return m.prec;
}

}  // namespace ddc
