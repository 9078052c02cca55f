// Direct-solver factory: names -> creators with their documented parameters
// (Belos SolverFactory style registry with an explicit scope, no globals).
//
// Parameter shape of the {Type, ...} sublist (see
// DirectSolverFactory::validParameters()):
//
//   <ParameterList name="Linear Solver">
//     <Parameter name="Type" type="string" value="MUMPS"/>
//     <ParameterList name="MUMPS">   <!-- options of the MUMPS back end -->
//       <Parameter name="Ordering" type="string" value="PORD"/>
//     </ParameterList>
//     <ParameterList name="Amesos2"> <!-- used only if Type = Amesos2 -->
//       <Parameter name="Solver Name" type="string" value="KLU2"/>
//     </ParameterList>
//   </ParameterList>
//
// One sublist per back end (named like its Type) rather than a flat list, so
// every back end's options can be validated and printed, and switching Type
// from the command line (--set ".../Type=Amesos2") keeps both configurations.
#include <sstream>

#include "DDC_Amesos2Solver.hpp"
#include "DDC_CholmodSolver.hpp"
#include "DDC_DirectSolver.hpp"
#include "DDC_Error.hpp"
#include "DDC_IterativeSolvers.hpp"
#include "DDC_MumpsSolver.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

/// The registered type names for messages and doc strings: "'Amesos2', 'CHOLMOD', 'MUMPS'".
std::string knownNames(const std::vector<std::string>& names) { return quotedNames(names, "(none registered)"); }

}  // namespace

DirectSolverFactory DirectSolverFactory::withBuiltins() {
  DirectSolverFactory f;
  f.add("MUMPS", Entry{[](const Teuchos::ParameterList& p) -> std::unique_ptr<DirectSolver> {
                         return std::make_unique<MumpsSolver>(p);
                       },
                       MumpsSolver::getValidParameters(),
                       "MUMPS 5 (C API): distributed LDL^T / LU on the matrix's communicator"});
  f.add("Amesos2", Entry{[](const Teuchos::ParameterList& p) -> std::unique_ptr<DirectSolver> {
                           return std::make_unique<Amesos2Solver>(p);
                         },
                         Amesos2Solver::getValidParameters(),
                         "Amesos2 (KLU2 by default); a distributed matrix is gathered to rank 0"});
  f.add("CHOLMOD", Entry{[](const Teuchos::ParameterList& p) -> std::unique_ptr<DirectSolver> {
                           return std::make_unique<CholmodSolver>(p);
                         },
                         CholmodSolver::getValidParameters(),
                         "SuiteSparse CHOLMOD: supernodal Cholesky LL^T of a symmetric positive definite matrix "
                         "on one process, e.g. the FETI-DP Local Solver, falling back to MUMPS if indefinite",
                         /*oneProcess=*/true});
  return f;
}

DirectSolverFactory DirectSolverFactory::withIterativeSolvers() {
  DirectSolverFactory f = withBuiltins();
  addIterativeSolvers(f);
  return f;
}

void DirectSolverFactory::requireDistributable(const Teuchos::ParameterList& params, const std::string& where,
                                               int processes) const {
  const std::string type = params.isParameter("Type") ? params.get<std::string>("Type") : kDefaultType;
  if (processes <= 1 || !entry(type, where).oneProcess) return;
  std::vector<std::string> distributed;
  for (const auto& kv : entries_)
    if (!kv.second.oneProcess) distributed.push_back(kv.first);
  DDC_THROW(InputError, "'" << joinPath(where, "Type") << "' = '" << type << "' factorises a matrix on one process, "
                            << "but this one is distributed over the " << processes << " MPI ranks; use "
                            << knownNames(distributed) << " here (" << type
                            << " suits the FETI-DP 'Local Solver'), or run on one rank");
}

void DirectSolverFactory::add(const std::string& type, Entry entry) {
  if (type.empty()) throw std::invalid_argument("DirectSolverFactory::add: empty type name");
  if (!entry.create) throw std::invalid_argument("DirectSolverFactory::add('" + type + "'): no creator");
  if (entries_.count(type))
    throw std::invalid_argument("DirectSolverFactory::add: '" + type + "' is already registered");
  if (entry.validParameters.is_null()) entry.validParameters = Teuchos::rcp(new Teuchos::ParameterList(type));
  entries_.emplace(type, std::move(entry));
}

std::vector<std::string> DirectSolverFactory::names() const {
  std::vector<std::string> out;
  for (const auto& e : entries_) out.push_back(e.first);
  return out;
}

const DirectSolverFactory::Entry& DirectSolverFactory::entry(const std::string& type,
                                                             const std::string& where) const {
  auto it = entries_.find(type);
  DDC_INPUT_REQUIRE(it != entries_.end(), "unknown direct solver '" << type << "' for parameter '"
                                                                    << joinPath(where, "Type")
                                                                    << "'; known types are " << knownNames(names()));
  return it->second;
}

Teuchos::RCP<const Teuchos::ParameterList> DirectSolverFactory::validParameters() const {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Linear Solver"));
  const auto known = names();
  std::string doc = "Direct solver back end:";
  for (const auto& e : entries_) doc += " " + e.first + " (" + e.second.description + ");";
  doc += " its options are in the sublist of the same name.";
  if (!known.empty()) {
    const std::string def = entries_.count(kDefaultType) ? kDefaultType : known.front();
    pl->set("Type", def, doc, enumValidator(known, "Type"));
  }
  for (const auto& e : entries_)
    pl->set(e.first, *e.second.validParameters, "Options of the " + e.first + " back end (used if Type = " +
                                                     e.first + ")");
  return pl;
}

Teuchos::RCP<const Teuchos::ParameterList> DirectSolverFactory::getValidParameters() {
  static const Teuchos::RCP<const Teuchos::ParameterList> valid = withBuiltins().validParameters();
  return valid;
}

std::unique_ptr<DirectSolver> DirectSolverFactory::create(Teuchos::ParameterList& params,
                                                          const std::string& where) const {
  // Type first, so an unknown name gets the "known types" message rather
  // than the generic enumeration one.
  std::string type = kDefaultType;
  if (params.isParameter("Type")) {
    DDC_INPUT_REQUIRE(params.isType<std::string>("Type"),
                      "parameter '" << joinPath(where, "Type") << "' must be a string naming a direct solver; known "
                                    << "types are " << knownNames(names()));
    type = params.get<std::string>("Type");
  }
  const Entry& chosen = entry(type, where);
  const auto valid = validParameters();
  validateLevel(params, *valid, where);  // misspelt names at this level, fills "Type"
  // Validate every back end's sublist that is present (a misspelt option for
  // a back end not chosen now is still an error), then the chosen one, which
  // is created empty if missing so its defaults become visible.
  for (const auto& e : entries_)
    if (e.first != type && params.isSublist(e.first))
      validateLevel(params.sublist(e.first), *e.second.validParameters, joinPath(where, e.first));
  Teuchos::ParameterList& sub = params.sublist(type);
  validateLevel(sub, *chosen.validParameters, joinPath(where, type));
  return chosen.create(sub);
}

}  // namespace ddc
