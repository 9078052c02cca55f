#include "DDC_ContactParameters.hpp"

#include <cmath>

#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

Teuchos::RCP<const Teuchos::ParameterList> ContactOptions::getValidParameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Contact"));
  pl->set("Formulation", "Node-To-Segment",
          "Node-To-Segment: conventional nonlinear node-to-segment element with a Lagrange multiplier, "
          "projection and normal follow the current configuration (the monolithic reference). Decomposed "
          "Node-To-Segment: projection and normal frozen at the last converged configuration, pairs "
          "refreshed at step ends (Fang & Izzuddin eq. 1); its slave and master counterparts may sit in "
          "different subdomains and share only the multiplier, so it works with both Solver/Strategy values "
          "(with FETI-DP each active pair is a row of the constraint operator B).",
          enumValidator({"Node-To-Segment", "Decomposed Node-To-Segment"}, "Formulation"));
  pl->set("Initial Contact State", "In Contact",
          "Active set at the start of each step: In Contact (every slave node with a master segment within "
          "the search radius starts active, as in the paper) or Previous Step (the converged active set of "
          "the previous step).",
          enumValidator({"In Contact", "Previous Step"}, "Initial Contact State"));
  pl->set("Search Radius", 0.0,
          "Slave nodes farther than this from every master segment are not paired. 0: automatic, the mean "
          "master segment length.",
          atLeast(0.0));
  pl->set("Penetration Tolerance", 1e-6,
          "An inactive pair is activated when g_N < -tol * (mean master segment length).", atLeast(0.0));
  Teuchos::ParameterList pairs("Pairs");
  Teuchos::ParameterList pair("<Pair Name>");
  pair.set("Slave", "", "Slave side set 'Body/set' (its nodes carry the Lagrange multipliers).");
  pair.set("Master", "", "Master side set 'Body/set' (2-node segments: Quad4 bodies).");
  setSublist(pairs, "<Pair Name>", pair, "One sublist per contact pair.");
  setSublist(*pl, "Pairs", pairs, "Contact pairs; none means no contact.");
  return pl;
}

ContactOptions ContactOptions::fromParameters(Teuchos::ParameterList& list, const Mesh& mesh,
                                              const std::string& path) {
  const auto valid = getValidParameters();
  validateLevel(list, *valid, path);
  ContactOptions o;
  o.decomposed = list.get<std::string>("Formulation") == "Decomposed Node-To-Segment";
  o.initialInContact = list.get<std::string>("Initial Contact State") == "In Contact";
  const auto& validPair = valid->sublist("Pairs").sublist("<Pair Name>");
  auto& pairs = list.sublist("Pairs");
  double lengthSum = 0.0;
  int segments = 0;
  for (auto it = pairs.begin(); it != pairs.end(); ++it) {
    const std::string name = pairs.name(it);
    const std::string where = path + "/Pairs/" + name;
    DDC_INPUT_REQUIRE(pairs.isSublist(name), "'" << where << "' must be a sublist with Slave and Master");
    auto& p = pairs.sublist(name);
    validateLevel(p, validPair, where);
    ContactPairDefinition d{name, p.get<std::string>("Slave"), p.get<std::string>("Master")};
    for (const auto& [key, set] : {std::pair<const char*, std::string>{"Slave", d.slaveSet}, {"Master", d.masterSet}}) {
      DDC_INPUT_REQUIRE(!set.empty(), "parameter '" << where << "/" << key << "' is required (a side set 'Body/set')");
      try {
        for (const Segment& s : mesh.sideSet(set))
          DDC_INPUT_REQUIRE(s.numNodes == 2, "'" << where << "/" << key << "' = '" << set
                                                 << "': contact surfaces must be sides of Quad4 bodies (2-node "
                                                    "segments); Quad9 contact is not supported yet");
      } catch (const InputError& e) {
        const std::string msg = e.what();
        if (msg.rfind("'" + where, 0) == 0) throw;
        throw InputError("contact pair '" + where + "/" + key + "': " + msg);
      }
    }
    DDC_INPUT_REQUIRE(d.slaveSet != d.masterSet, "contact pair '" << where << "': Slave and Master are the same side set '"
                                                                  << d.slaveSet << "'");
    for (const Segment& s : mesh.sideSet(d.masterSet)) {
      const auto& a = mesh.coord(s.nodes[0]);
      const auto& b = mesh.coord(s.nodes[1]);
      lengthSum += std::hypot(b[0] - a[0], b[1] - a[1]);
      ++segments;
    }
    o.pairs.push_back(d);
  }
  const double h = segments ? lengthSum / segments : 1.0;
  o.searchRadius = list.get<double>("Search Radius");
  if (o.searchRadius == 0.0) o.searchRadius = h;
  const double tol = list.get<double>("Penetration Tolerance");
  o.penetrationTolerance = tol * h;
  return o;
}

}  // namespace ddc
