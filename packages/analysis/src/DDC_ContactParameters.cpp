#include "DDC_ContactParameters.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

using Edge = std::pair<int, int>;

/// The segments of side set `set` as sorted node pairs, sorted (orientation
/// does not matter for "the same segment").
std::vector<Edge> segmentsOf(const Mesh& mesh, const std::string& set) {
  std::vector<Edge> out;
  for (const Segment& s : mesh.sideSet(set))
    out.emplace_back(std::min(s.nodes[0], s.nodes[1]), std::max(s.nodes[0], s.nodes[1]));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// The first element common to two sorted ranges, if any.
template <class T>
bool firstCommon(const std::vector<T>& a, const std::vector<T>& b, T& out) {
  auto i = a.begin();
  auto j = b.begin();
  while (i != a.end() && j != b.end()) {
    if (*i < *j) {
      ++i;
    } else if (*j < *i) {
      ++j;
    } else {
      out = *i;
      return true;
    }
  }
  return false;
}

/// Pairs must not constrain one thing twice (doc/contact.md "Pairs that
/// overlap"); the comparison is by nodes and segments, so two side sets of
/// different names over the same curve count as the same surface.
void checkPairsDoNotOverlap(const std::vector<ContactPairDefinition>& pairs, const Mesh& mesh,
                            const std::string& path) {
  struct Sets {
    std::vector<int> slaveNodes;  // the pair's slave nodes: not on its master surface
    std::vector<Edge> slaveSegments, masterSegments;
  };
  std::vector<Sets> sets;
  for (const auto& d : pairs) {
    Sets s;
    s.slaveSegments = segmentsOf(mesh, d.slaveSet);
    s.masterSegments = segmentsOf(mesh, d.masterSet);
    std::vector<int> master;
    for (const Edge& e : s.masterSegments) master.insert(master.end(), {e.first, e.second});
    std::sort(master.begin(), master.end());
    for (int n : mesh.nodeSet(d.slaveSet))
      if (!std::binary_search(master.begin(), master.end(), n)) s.slaveNodes.push_back(n);
    std::sort(s.slaveNodes.begin(), s.slaveNodes.end());
    sets.push_back(std::move(s));
  }
  auto where = [&](size_t i) { return "'" + path + "/Pairs/" + pairs[i].name + "'"; };
  auto segment = [&](const Edge& e) {
    std::ostringstream os;
    os << "nodes " << e.first << "-" << e.second << " at (" << mesh.coord(e.first)[0] << ", " << mesh.coord(e.first)[1]
       << ")-(" << mesh.coord(e.second)[0] << ", " << mesh.coord(e.second)[1] << ")";
    return os.str();
  };
  for (size_t i = 0; i < pairs.size(); ++i)
    for (size_t j = i + 1; j < pairs.size(); ++j) {
      int node = -1;
      Edge e{-1, -1}, f{-1, -1};
      // Duplicated: a slave node of both pairs and a master segment of both.
      // Its nearest segment may then be the same in both pairs: two identical
      // constraint rows, singular whenever both are active.
      DDC_INPUT_REQUIRE(!(firstCommon(sets[i].slaveNodes, sets[j].slaveNodes, node) &&
                          firstCommon(sets[i].masterSegments, sets[j].masterSegments, e)),
                        "contact pairs " << where(i) << " and " << where(j) << " duplicate each other: slave node "
                                         << node << " at (" << mesh.coord(node)[0] << ", " << mesh.coord(node)[1]
                                         << ") is a slave of both (Slave '" << pairs[i].slaveSet << "' and '"
                                         << pairs[j].slaveSet << "') and their master surfaces ('" << pairs[i].masterSet
                                         << "' and '" << pairs[j].masterSet << "') share the segment of " << segment(e)
                                         << ", so the node could get two identical contact constraints (a singular "
                                            "system); a slave node may belong to several pairs only if their master "
                                            "surfaces share no segment: remove the duplicated pair");
      // Mirrored: each pair's slave surface overlaps the other's master
      // surface (two-pass node-to-segment): with Lagrange multipliers the
      // constraints of the two passes are dependent on matching meshes
      // (identical up to sign: singular) and over-constrain the interface
      // otherwise.
      DDC_INPUT_REQUIRE(!(firstCommon(sets[i].slaveSegments, sets[j].masterSegments, e) &&
                          firstCommon(sets[i].masterSegments, sets[j].slaveSegments, f)),
                        "contact pairs " << where(i) << " and " << where(j) << " mirror each other: the slave "
                                         << "surface of the first ('" << pairs[i].slaveSet << "') and the master "
                                         << "surface of the second ('" << pairs[j].masterSet << "') share the segment of "
                                         << segment(e) << ", and the master surface of the first ('"
                                         << pairs[i].masterSet << "') and the slave surface of the second ('"
                                         << pairs[j].slaveSet << "') share the segment of " << segment(f)
                                         << "; contact on one interface in both directions (two-pass node-to-segment) "
                                            "over-constrains it: the Lagrange-multiplier rows of the two passes are "
                                            "dependent on matching meshes (a singular system) and conflict otherwise, "
                                            "and the reported contact force adds both directions: keep one of the two "
                                            "pairs");
    }
}

}  // namespace

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
    // Node-to-segment contact is 2-D; the 3-D node-to-facet element is not
    // available yet (doc/contact.md).
    DDC_INPUT_REQUIRE(mesh.dim() == 2, "contact pair '" << where << "': the mesh is 3-D (body '" << mesh.body(0).name
                                                        << "' has " << cellTypeName(mesh.body(0).cellType)
                                                        << " cells); contact is available for 2-D meshes only");
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
  checkPairsDoNotOverlap(o.pairs, mesh, path);
  const double h = segments ? lengthSum / segments : 1.0;
  o.searchRadius = list.get<double>("Search Radius");
  if (o.searchRadius == 0.0) o.searchRadius = h;
  const double tol = list.get<double>("Penetration Tolerance");
  o.penetrationTolerance = tol * h;
  return o;
}

}  // namespace ddc
