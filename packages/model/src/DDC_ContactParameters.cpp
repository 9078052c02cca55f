#include "DDC_ContactParameters.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <sstream>
#include <utility>

#include "DDC_ContactSurface.hpp"
#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

/// A facet compared by its corner nodes' ids in the whole mesh, sorted:
/// orientation and the middle nodes of quadratic facets do not matter for
/// "the same facet" (as Mesh::facetKey()).
using FacetKey = std::vector<Mesh::GlobalId>;

/// The corner nodes of a side-set facet: start and end in 2-D (Line2, Line3),
/// the face corners in 3-D.
std::vector<int> cornersOf(const Mesh& mesh, const Segment& s, const std::string& set) {
  const int corners = referenceCell(contactFacetType(mesh.dim(), s.numNodes, set)).numCorners;
  return std::vector<int>(s.nodes.begin(), s.nodes.begin() + corners);
}

/// Sorted and without repeats.
template <class T>
void sortUnique(std::vector<T>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

/// The facets of side set `set` as keys, sorted and unique; of the whole
/// mesh, gathered over `comm` when `mesh` is a part of it.
std::vector<FacetKey> facetsOf(const Mesh& mesh, const std::string& set, MPI_Comm comm) {
  struct Record {
    Mesh::GlobalId corner[4];
  };
  std::vector<Record> mine;
  for (const Segment& s : mesh.sideSet(set)) {
    Record r{{-1, -1, -1, -1}};
    const std::vector<int> c = cornersOf(mesh, s, set);
    for (size_t i = 0; i < c.size(); ++i) r.corner[i] = mesh.nodeId(c[i]);
    std::sort(r.corner, r.corner + c.size());
    mine.push_back(r);
  }
  if (mesh.isPart()) mine = allGather(comm, mine);
  std::vector<FacetKey> out(mine.size());
  for (size_t i = 0; i < mine.size(); ++i)
    for (Mesh::GlobalId id : mine[i].corner)
      if (id >= 0) out[i].push_back(id);
  sortUnique(out);
  return out;
}

/// The ids of `nodes` (of this mesh), of the whole mesh's when `mesh` is a
/// part of it (gathered over `comm`), sorted and unique.
std::vector<Mesh::GlobalId> nodeIdsOf(const Mesh& mesh, const std::vector<int>& nodes, MPI_Comm comm) {
  std::vector<Mesh::GlobalId> ids;
  for (int n : nodes) ids.push_back(mesh.nodeId(n));
  if (mesh.isPart()) ids = allGather(comm, ids);
  sortUnique(ids);
  return ids;
}

/// Mesh::coordText() of the node with id `id` in the whole mesh: on a part,
/// from a rank that holds it. Collective on `comm` for a part.
std::string coordTextOf(const Mesh& mesh, Mesh::GlobalId id, MPI_Comm comm) {
  if (!mesh.isPart()) return mesh.coordText(int(id));
  const int n = mesh.localNode(id);
  std::array<double, 3> x;
  x.fill(std::numeric_limits<double>::infinity());
  if (n >= 0) x = mesh.coord(n);
  MPI_Allreduce(MPI_IN_PLACE, x.data(), 3, MPI_DOUBLE, MPI_MIN, comm);
  std::ostringstream os;
  os << x[0] << ", " << x[1];
  if (mesh.dim() == 3) os << ", " << x[2];
  return os.str();
}

/// The automatic length scale of one master facet (header): 2-D the length
/// start → end (the chord of a Line3 segment), 3-D the square root of the area
/// of the polygon through the face's corners, ½|(x_1 − x_0) × (x_2 − x_0)| for
/// a triangle and ½|(x_2 − x_0) × (x_3 − x_1)| (the diagonals) for a
/// quadrilateral.
double facetSize(const Mesh& mesh, const Segment& s, const std::string& set) {
  const std::vector<int> c = cornersOf(mesh, s, set);
  if (mesh.dim() == 2) {
    const auto& a = mesh.coord(c[0]);
    const auto& b = mesh.coord(c[1]);
    return std::hypot(b[0] - a[0], b[1] - a[1]);
  }
  auto x = [&](int i) { return Eigen::Vector3d(mesh.coord(c[i]).data()); };
  const Eigen::Vector3d twiceArea = c.size() == 3 ? Eigen::Vector3d((x(1) - x(0)).cross(x(2) - x(0)))
                                                  : Eigen::Vector3d((x(2) - x(0)).cross(x(3) - x(1)));
  return std::sqrt(0.5 * twiceArea.norm());
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
/// overlap"); the comparison is by nodes and facets (segments in 2-D, faces in
/// 3-D), so two side sets of different names over the same surface count as
/// the same surface.
void checkPairsDoNotOverlap(const std::vector<ContactPairDefinition>& pairs, const Mesh& mesh,
                            const std::string& path, MPI_Comm comm) {
  // By ids in the whole mesh; a part of a mesh gathers the surfaces (the
  // contact component holds them all as well), so every rank decides alike.
  struct Sets {
    std::vector<Mesh::GlobalId> slaveNodes;  // the pair's slave nodes: not on its master surface
    std::vector<FacetKey> slaveFacets, masterFacets;
  };
  std::vector<Sets> sets;
  for (const auto& d : pairs) {
    Sets s;
    s.slaveFacets = facetsOf(mesh, d.slaveSet, comm);
    s.masterFacets = facetsOf(mesh, d.masterSet, comm);
    std::vector<int> masterNodes;
    for (const Segment& f : mesh.sideSet(d.masterSet))
      masterNodes.insert(masterNodes.end(), f.nodes.begin(), f.nodes.begin() + f.numNodes);
    const std::vector<Mesh::GlobalId> master = nodeIdsOf(mesh, masterNodes, comm);
    for (Mesh::GlobalId n : nodeIdsOf(mesh, mesh.nodeSet(d.slaveSet), comm))
      if (!std::binary_search(master.begin(), master.end(), n)) s.slaveNodes.push_back(n);
    sets.push_back(std::move(s));
  }
  auto where = [&](size_t i) { return "'" + path + "/Pairs/" + pairs[i].name + "'"; };
  // "segment of nodes a-b at (x, y)-(x, y)" in 2-D, "facet of nodes a-b-c-d
  // at (x, y, z)" (the first corner) in 3-D.
  const char* noun = mesh.dim() == 2 ? "segment" : "facet";
  auto facet = [&](const FacetKey& k) {
    std::ostringstream os;
    os << noun << " of nodes " << k[0];
    for (size_t i = 1; i < k.size(); ++i) os << "-" << k[i];
    os << " at (" << coordTextOf(mesh, k[0], comm) << ")";
    if (mesh.dim() == 2) os << "-(" << coordTextOf(mesh, k[1], comm) << ")";
    return os.str();
  };
  for (size_t i = 0; i < pairs.size(); ++i)
    for (size_t j = i + 1; j < pairs.size(); ++j) {
      Mesh::GlobalId node = -1;
      FacetKey e, f;
      // Duplicated: a slave node of both pairs and a master facet of both.
      // Its nearest facet may then be the same in both pairs: two identical
      // constraint rows, singular whenever both are active.
      DDC_INPUT_REQUIRE(!(firstCommon(sets[i].slaveNodes, sets[j].slaveNodes, node) &&
                          firstCommon(sets[i].masterFacets, sets[j].masterFacets, e)),
                        "contact pairs " << where(i) << " and " << where(j) << " duplicate each other: slave node "
                                         << node << " at (" << coordTextOf(mesh, node, comm) << ") is a slave of both (Slave '"
                                         << pairs[i].slaveSet << "' and '" << pairs[j].slaveSet
                                         << "') and their master surfaces ('" << pairs[i].masterSet << "' and '"
                                         << pairs[j].masterSet << "') share the " << facet(e)
                                         << ", so the node could get two identical contact constraints (a singular "
                                            "system); a slave node may belong to several pairs only if their master "
                                            "surfaces share no "
                                         << noun << ": remove the duplicated pair");
      // Mirrored: each pair's slave surface overlaps the other's master
      // surface (two-pass contact): with Lagrange multipliers the constraints
      // of the two passes are dependent on matching meshes (identical up to
      // sign: singular) and over-constrain the interface otherwise.
      DDC_INPUT_REQUIRE(!(firstCommon(sets[i].slaveFacets, sets[j].masterFacets, e) &&
                          firstCommon(sets[i].masterFacets, sets[j].slaveFacets, f)),
                        "contact pairs " << where(i) << " and " << where(j) << " mirror each other: the slave "
                                         << "surface of the first ('" << pairs[i].slaveSet << "') and the master "
                                         << "surface of the second ('" << pairs[j].masterSet << "') share the "
                                         << facet(e) << ", and the master surface of the first ('" << pairs[i].masterSet
                                         << "') and the slave surface of the second ('" << pairs[j].slaveSet
                                         << "') share the " << facet(f) << "; contact on one interface in both "
                                         << "directions (two-pass "
                                         << (mesh.dim() == 2 ? "node-to-segment" : "node-to-surface")
                                         << ") over-constrains it: the Lagrange-multiplier rows of the two passes are "
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
          "(with FETI-DP each active pair is a row of the constraint operator B). Node-To-Surface and "
          "Decomposed Node-To-Surface are the same two formulations by the names that fit facets of any "
          "type (3-node segments in 2-D, faces in 3-D).",
          enumValidator({"Node-To-Segment", "Decomposed Node-To-Segment", "Node-To-Surface",
                         "Decomposed Node-To-Surface"},
                        "Formulation"));
  pl->set("Initial Contact State", "Automatic",
          "Active set at the start of each step: In Contact (every slave node with a master segment within "
          "the search radius starts active, as in the paper) or Previous Step (the converged active set of "
          "the previous step). Automatic: In Contact in a quasi-static analysis (with friction: in a step "
          "that starts with no slave node active, Previous Step otherwise), Previous Step in a dynamic one, "
          "whose time steps change the active set little (doc/user-guide.md, \"Contact in dynamics\").",
          enumValidator({"Automatic", "In Contact", "Previous Step"}, "Initial Contact State"));
  pl->set("Pairing Cycles", "Freeze",
          "Conventional formulation only (the decomposed one keeps its pairing over each step anyway): what "
          "Newton does when a slave node's pairing returns to a facet it left earlier in the same increment, "
          "as at a facet edge where the closest point jumps between two facets and the gap has a kink. "
          "Freeze: keep the pairing of that iteration for the rest of the increment (the projection onto "
          "each paired facet, extended past its edges, stays smooth) and refresh it at the step end. Fail: "
          "the increment fails as a cycling active set does (bisection).",
          enumValidator({"Freeze", "Fail"}, "Pairing Cycles"));
  pl->set("Search Radius", 0.0,
          "Slave nodes farther than this from every master facet are not paired. 0: automatic, h = the mean "
          "master facet size: in 2-D the length of a segment from its start to its end node (the chord of a "
          "3-node segment), in 3-D the square root of a face's area (of the polygon through its corners).",
          atLeast(0.0));
  pl->set("Penetration Tolerance", 1e-6,
          "An inactive pair is activated when g_N < -tol * h, h the mean master facet size (Search Radius).",
          atLeast(0.0));
  Teuchos::ParameterList pairs("Pairs");
  Teuchos::ParameterList pair("<Pair Name>");
  pair.set("Slave", "", "Slave side set 'Body/set' (its nodes carry the Lagrange multipliers).");
  pair.set("Master", "",
           "Master side set 'Body/set': sides of 2-D bodies (2-node segments of Quad4, 3-node of Quad9) or faces "
           "of 3-D bodies (Tri3, Tri6, Quad4, Quad8, Quad9 faces of Tet4, Tet10, Hex8, Hex20, Hex27).");
  // Finite and bounded: μ enters the cone μ p, and a coefficient beyond
  // kMaxFriction is no friction law anyone measured (a bonded pair is a
  // tie, not friction).
  constexpr double kMaxFriction = 1e3;
  pair.set("Friction Coefficient", 0.0,
           "Coulomb friction coefficient mu >= 0 of the pair (doc/contact.md, 'Friction'): a slave node in contact "
           "sticks while its tangential force is below mu times its normal force and slips along the master "
           "surface against a force of mu times it otherwise, decided exactly in Newton's method (no penalty). 0: "
           "frictionless (today's element, one multiplier per slave node). Each slave node of a frictional pair "
           "has dim - 1 tangential multipliers more. At most 1e3.",
           between(0.0, kMaxFriction));
  setSublist(pairs, "<Pair Name>", pair, "One sublist per contact pair.");
  setSublist(*pl, "Pairs", pairs, "Contact pairs; none means no contact.");
  return pl;
}

ContactOptions ContactOptions::fromParameters(Teuchos::ParameterList& list, const Mesh& mesh,
                                              const std::string& path, MPI_Comm comm) {
  const auto valid = getValidParameters();
  validateLevel(list, *valid, path);
  ContactOptions o;
  const std::string formulation = list.get<std::string>("Formulation");
  o.decomposed = formulation == "Decomposed Node-To-Segment" || formulation == "Decomposed Node-To-Surface";
  // Automatic is In Contact here; a dynamic analysis turns it into
  // Previous Step (it knows it is one).
  o.initialInContact = list.get<std::string>("Initial Contact State") != "Previous Step";
  o.freezeCyclingPairing = list.get<std::string>("Pairing Cycles") == "Freeze";
  const auto& validPair = valid->sublist("Pairs").sublist("<Pair Name>");
  auto& pairs = list.sublist("Pairs");
  double sizeSum = 0.0;
  int facets = 0;
  for (auto it = pairs.begin(); it != pairs.end(); ++it) {
    const std::string name = pairs.name(it);
    const std::string where = path + "/Pairs/" + name;
    DDC_INPUT_REQUIRE(pairs.isSublist(name), "'" << where << "' must be a sublist with Slave and Master");
    auto& p = pairs.sublist(name);
    // A coefficient set (a --set, a typo in the pair's name) for a pair the
    // deck does not define: no such pair.
    DDC_INPUT_REQUIRE(!p.isParameter("Friction Coefficient") || p.isParameter("Slave") || p.isParameter("Master"),
                      "'" << where << "/Friction Coefficient' is given, but the deck defines no contact pair '"
                          << name << "' (no Slave and Master): name one of the pairs in '" << path << "/Pairs'");
    validateLevel(p, validPair, where);
    ContactPairDefinition d{name, p.get<std::string>("Slave"), p.get<std::string>("Master"),
                            p.get<double>("Friction Coefficient")};
    for (const auto& [key, set] : {std::pair<const char*, std::string>{"Slave", d.slaveSet}, {"Master", d.masterSet}}) {
      DDC_INPUT_REQUIRE(!set.empty(), "parameter '" << where << "/" << key << "' is required (a side set 'Body/set')");
      // A node set (a generator's "all" or corner, a Gmsh physical point) has
      // no facets, hence no outward normals to take contact on.
      DDC_INPUT_REQUIRE(mesh.hasSideSet(set) || !mesh.hasNodeSet(set),
                        "contact pair '" << where << "/" << key << "': '" << set
                                         << "' is a node set, not a side set; a contact surface must be a side set of "
                                         << (mesh.dim() == 2 ? "element sides (a generator's named side, a Gmsh "
                                                               "physical curve of a 2-D body)"
                                                             : "element faces (a generator's named face, a Gmsh "
                                                               "physical surface of a 3-D body)")
                                         << ", whose facets give the surface and its outward normals");
      try {
        for (const Segment& s : mesh.sideSet(set)) contactFacetType(mesh.dim(), s.numNodes, set);
      } catch (const InputError& e) {
        throw InputError("contact pair '" + where + "/" + key + "': " + e.what());
      }
    }
    DDC_INPUT_REQUIRE(d.slaveSet != d.masterSet, "contact pair '" << where << "': Slave and Master are the same side set '"
                                                                  << d.slaveSet << "'");
    for (const Segment& s : mesh.sideSet(d.masterSet)) {
      sizeSum += facetSize(mesh, s, d.masterSet);
      ++facets;
    }
    o.pairs.push_back(d);
  }
  checkPairsDoNotOverlap(o.pairs, mesh, path, comm);
  if (mesh.isPart()) {
    MPI_Allreduce(MPI_IN_PLACE, &sizeSum, 1, MPI_DOUBLE, MPI_SUM, comm);
    MPI_Allreduce(MPI_IN_PLACE, &facets, 1, MPI_INT, MPI_SUM, comm);
  }
  const double h = facets ? sizeSum / facets : 1.0;
  o.length = h;
  o.searchRadius = list.get<double>("Search Radius");
  if (o.searchRadius == 0.0) o.searchRadius = h;
  const double tol = list.get<double>("Penetration Tolerance");
  o.penetrationTolerance = tol * h;
  // With friction, Automatic starts a step from the previous active set
  // once there is one: reactivating every paired node costs the Newton
  // iterations to release them again, about half of each step's
  // (doc/user-guide.md, "The active set at the start of a step").
  o.inContactOnlyWhenNoneActive = list.get<std::string>("Initial Contact State") == "Automatic" && o.frictional();
  return o;
}

}  // namespace ddc
