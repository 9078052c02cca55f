#include "DDC_ModelSetUp.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <utility>

#include "DDC_AnalysisParameters.hpp"
#include "DDC_Error.hpp"
#include "DDC_ExodusMesh.hpp"
#include "DDC_Gmsh.hpp"
#include "DDC_InputDeck.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_NodeDirectory.hpp"
#include "DDC_ParallelPartition.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

using PL = Teuchos::ParameterList;

namespace {
/// Poisson's ratio from which a body is reported nearly incompressible
/// (lambda/mu >= 49): displacement elements lock noticeably.
constexpr double kNearlyIncompressible = 0.49;
/// The range of a body's extent and coordinates buildMesh() accepts.
constexpr double kMinBodyExtent = 1e-100;
constexpr double kMaxCoordinate = Mesh::kMaxCoordinate;

/// check(first, last) on this rank's share of the elements of `mesh`: an
/// even share of a whole mesh, all of a part's (Mesh::isPart()); the
/// InputError of the lowest rank that throws one is thrown on every rank
/// (on a whole mesh, or parts in ranges of ids in rank order, the error of
/// the lowest element).
template <class Check>
void checkShareCollectively(const Mesh& mesh, MPI_Comm comm, const Check& check) {
  // The lowest rank that finds an error has the lowest element.
  const auto [first, last] =
      mesh.isPart() ? std::pair<long long, long long>(0, mesh.numElements()) : evenShare(mesh.numElements(), comm);
  runCollectively<InputError>(comm, [&] { check(int(first), int(last)); });
}
}  // namespace

PL& validatedBodies(PL& meshParams) {
  PL validMesh("Mesh");
  validMesh.sublist("Bodies");
  validateLevel(meshParams, validMesh, "Mesh");
  DDC_INPUT_REQUIRE(meshParams.isSublist("Bodies") && meshParams.sublist("Bodies").numParams() > 0,
                    "sublist 'Mesh/Bodies' is required and must describe at least one body");
  return meshParams.sublist("Bodies");
}

BodyInput readBody(PL& bodies, const std::string& name, const ElementFactory& factory, const PL& validBody) {
  BodyInput in;
  in.name = name;
  in.path = "Mesh/Bodies/" + name;
  const std::string& path = in.path;
  DDC_INPUT_REQUIRE(bodies.isSublist(name), "'" << path << "' must be a sublist describing a body");
  PL& body = bodies.sublist(name);
  validateLevel(body, validBody, path);
  in.generator = body.get<std::string>("Generator");
  for (const auto& g : kMeshGenerators)
    DDC_INPUT_REQUIRE(g == in.generator || !body.isSublist(g), "sublist '" << path << "/" << g
                                                                           << "' does not apply: Generator is '"
                                                                           << in.generator << "'");
  DDC_INPUT_REQUIRE(body.isSublist("Element"), "sublist '" << path << "/Element' is required (Type, Material)");
  PL& elem = body.sublist("Element");
  DDC_INPUT_REQUIRE(elem.isParameter("Type"), "parameter '" << path << "/Element/Type' is required");
  const auto& entry = factory.entry(elem.get<std::string>("Type"), path + "/Element");
  DDC_INPUT_REQUIRE(!entry.contact, "'" << path << "/Element/Type' = '" << elem.get<std::string>("Type")
                                        << "' is a contact element (the contact component makes those for "
                                           "Contact/Pairs); a body needs one of "
                                        << quotedNames(factory.bodyNames(), "(none registered)"));
  // The mesh cell type of the element: the one of its dimension and node count.
  const auto& cells = elementCellTypes();
  const auto cellIt = std::find_if(cells.begin(), cells.end(), [&](CellType c) {
    return cellDimension(c) == entry.dim && numCellNodes(c) == entry.numNodes;
  });
  DDC_INPUT_REQUIRE(cellIt != cells.end(), "element type '" << elem.get<std::string>("Type") << "' of '" << path
                                                             << "' is " << entry.dim << "-D with " << entry.numNodes
                                                             << " nodes, which no mesh cell type has (bodies need "
                                                                "Quad4, Quad9, Hex8, Hex20, Hex27, Tet4 or Tet10 "
                                                                "cells)");
  in.cellType = *cellIt;
  in.generatorParams = &body.sublist(in.generator);
  return in;
}

void requireBodyExtent(const Mesh& mesh, int body, const BodyInput& in, MPI_Comm comm) {
  // Lengths far from 1 under- or overflow in the element arithmetic
  // (Jacobians are cubes of lengths in 3-D, stiffnesses divide by them):
  // a body's extent must lie in [1e-100, 1e100].
  const Body& b = mesh.body(body);
  std::array<double, 6> box{{1e308, 1e308, 1e308, 1e308, 1e308, 1e308}};  // -hi, lo per axis
  for (int n = b.firstNode; n < b.firstNode + b.numNodes; ++n)
    for (int c = 0; c < 3; ++c) box[c] = std::min(box[c], mesh.coord(n)[c]), box[3 + c] = std::min(box[3 + c], -mesh.coord(n)[c]);
  if (mesh.isPart()) MPI_Allreduce(MPI_IN_PLACE, box.data(), 6, MPI_DOUBLE, MPI_MIN, comm);
  double extent = 1e308, far = 0.0;  // the smallest extent over the axes
  for (int c = 0; c < mesh.dim(); ++c) {
    const double lo = box[c], hi = -box[3 + c];
    extent = std::min(extent, hi - lo);
    far = std::max({far, std::abs(lo), std::abs(hi)});
  }
  DDC_INPUT_REQUIRE(mesh.bodyGlobalNodes(body) == 0 || (extent >= kMinBodyExtent && far <= kMaxCoordinate),
                    "'" << in.path << "/" << in.generator << "': body '" << in.name << "' spans " << extent
                        << " along its thinnest axis, with coordinates up to " << far
                        << " in magnitude; its extent must lie in [" << kMinBodyExtent << ", " << kMaxCoordinate
                        << "] and its coordinates within " << kMaxCoordinate
                        << " (lengths this far from 1 under- or overflow in the element arithmetic): choose other "
                           "length units");
}

std::shared_ptr<Mesh> buildMesh(Teuchos::ParameterList& meshParams, const ElementFactory& factory,
                                const std::string& baseDirectory, const MemoryLimit* budget,
                                const std::string& budgetHint, MPI_Comm comm) {
  PL& bodies = validatedBodies(meshParams);
  const auto validBody = bodyValidParameters(factory);
  auto mesh = std::make_shared<Mesh>();
  if (budget && std::isfinite(budget->bytes)) mesh->setMemoryBudget(budget->bytes, budget->source, budgetHint);
  for (auto it = bodies.begin(); it != bodies.end(); ++it) {
    const std::string name = bodies.name(it);
    Activity activity("building the mesh of body '" + name + "' (" + std::to_string(mesh->numNodes()) +
                      " nodes before it)");
    const BodyInput in = readBody(bodies, name, factory, *validBody);
    PL& gp = *in.generatorParams;
    const std::string at = in.path + "/" + in.generator;
    if (in.generator == "Rectangle")
      generateRectangle(*mesh, name, in.cellType, gp, at);
    else if (in.generator == "Annular Sector")
      generateAnnularSector(*mesh, name, in.cellType, gp, at);
    else if (in.generator == "Box")
      generateBox(*mesh, name, in.cellType, gp, at);
    else if (in.generator == "Cylindrical Shell Sector")
      generateCylindricalShellSector(*mesh, name, in.cellType, gp, at);
    else if (in.generator == "Sphere Octant")
      generateSphereOctant(*mesh, name, in.cellType, gp, at);
    else if (in.generator == "Exodus")
      readExodusBody(*mesh, name, in.cellType, gp, at, baseDirectory);
    else
      readGmshBody(*mesh, name, in.cellType, gp, in.path + "/Gmsh", baseDirectory);
    requireBodyExtent(*mesh, mesh->numBodies() - 1, in, comm);
  }
  mesh->checkConnectivity();
  checkShareCollectively(*mesh, comm, [&](int first, int last) { mesh->checkShapes(first, last); });
  return mesh;
}

namespace {

/// METIS or PT-Scotch: a partition of the dual graph into any count.
bool isGraphPartitioner(const std::string& method) { return method == "METIS" || method == "PT-Scotch"; }

int automaticSubdomainCount(const Mesh& mesh, const PL& partition, const std::string& strategy, int ranks) {
  if (strategy != "FETI-DP" || !isGraphPartitioner(partition.get<std::string>("Method"))) return ranks;
  // Measured on block_3d at 421k DOFs (1650 DOFs per subdomain against 840
  // and 3300) and the 2-D elastic block at 822k (doc/performance.md): local
  // factorisations grow faster than linearly in the subdomain size, the
  // coarse problem with the number of subdomains.
  int size = partition.get<int>("Subdomain Size");
  if (size == 0) size = mesh.dim() == 3 ? 1650 : 3200;
  const double dofs = double(mesh.numGlobalNodes()) * mesh.dim();
  const double count = std::min(std::round(dofs / size), double(std::max<Mesh::GlobalId>(mesh.numGlobalElements(), 1)));
  return std::max(ranks, int(count));
}

}  // namespace

std::vector<std::shared_ptr<const Element>> makeBodyElements(const Mesh& mesh, PL& meshParams,
                                                             const ElementFactory& factory) {
  std::vector<std::shared_ptr<const Element>> elements;
  for (int b = 0; b < mesh.numBodies(); ++b) {
    const std::string& name = mesh.body(b).name;
    elements.push_back(factory.create(meshParams.sublist("Bodies").sublist(name).sublist("Element"),
                                      "Mesh/Bodies/" + name + "/Element"));
  }
  return elements;
}

std::string nearlyIncompressibleBodies(const Mesh& mesh, const PL& meshParams) {
  std::string text;
  for (int b = 0; b < mesh.numBodies(); ++b) {
    const std::string& name = mesh.body(b).name;
    const PL& el = meshParams.sublist("Bodies").sublist(name).sublist("Element");
    if (!el.isSublist("Material") || !el.sublist("Material").isType<double>("Poisson's Ratio")) continue;
    const double nu = el.sublist("Material").get<double>("Poisson's Ratio");
    if (nu < kNearlyIncompressible) continue;
    std::ostringstream os;
    os.precision(12);
    os << (text.empty() ? "" : "; ") << "body '" << name << "' is nearly incompressible ('Mesh/Bodies/" << name
       << "/Element/Material/Poisson's Ratio' = " << nu << ", lambda/mu = " << std::setprecision(3)
       << 2.0 * nu / (1.0 - 2.0 * nu)
       << "): the elements are displacement-only, with no mixed (u-p) formulation, so they lock: results too "
          "stiff and Newton slow to converge or stagnating; use a Poisson's ratio below "
       << kNearlyIncompressible;
    text += os.str();
  }
  return text;
}

namespace {

/// Elements [first, last) of `mesh` (the inverted or degenerate ones by the
/// element's own Jacobian).
void requireAdmissibleShare(const Mesh& mesh, const std::vector<std::shared_ptr<const Element>>& elements, int first,
                            int last) {
  const int d = mesh.dim();
  for (int e = first; e < last; ++e) {
    const int nn = mesh.elementNumNodes(e);
    Eigen::MatrixXd X(nn, d);
    for (int i = 0; i < nn; ++i)
      for (int c = 0; c < d; ++c) X(i, c) = mesh.coord(mesh.elementNodes(e)[i])[c];
    const double detJ = elements[mesh.elementBody(e)]->minReferenceJacobian(X);
    DDC_INPUT_REQUIRE(detJ > 0.0, "mesh: element " << mesh.elementId(e) << " of body '" << mesh.body(mesh.elementBody(e)).name
                                                  << "' is inverted or degenerate (min det J = " << detJ << "); "
                                                  << (d == 2 ? "its nodes must run counter-clockwise"
                                                             : "its nodes must follow the Gmsh order with a "
                                                               "positive orientation")
                                                  << ", first node at (" << mesh.coordText(mesh.elementNodes(e)[0])
                                                  << ")");
  }
}

}  // namespace

void requireAdmissibleElements(const Mesh& mesh, const std::vector<std::shared_ptr<const Element>>& elements,
                               MPI_Comm comm) {
  checkShareCollectively(mesh, comm, [&](int first, int last) { requireAdmissibleShare(mesh, elements, first, last); });
}

namespace {

/// What the prescribed displacements of one body hold: how many nodes,
/// in which directions, and whether those nodes span more than a line.
struct BodySupport {
  long long nodes = 0;
  std::array<bool, 3> fixed{{false, false, false}};
  bool enoughNodes = false;
};

/// The support of each body from the nodes `held` (per body, node indices
/// ascending) of this rank's mesh. On a part of a mesh (Mesh::isPart())
/// the ranks' nodes are taken together (collective over `comm`), each node
/// once, and the answer is the whole mesh's. Two distinct nodes hold a 2-D
/// body's rotation; a 3-D body needs three not on one line (two leave the
/// rotation about their line free): the node of lowest id a, the node b
/// farthest from it (the lowest id on ties), and the largest area a node
/// makes with them, relative to |b - a|^2.
std::vector<BodySupport> bodySupports(const Mesh& mesh, const std::vector<std::set<int>>& held,
                                      const std::vector<std::array<bool, 3>>& fixedDir, MPI_Comm comm) {
  const bool parts = mesh.isPart();
  auto allMin = [&](long long v) {
    if (parts) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_LONG_LONG, MPI_MIN, comm);
    return v;
  };
  auto allMax = [&](double v) {
    if (parts) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MAX, comm);
    return v;
  };
  // The coordinates of the node of id `id`, from the ranks that hold it.
  auto coordOf = [&](long long id) {
    std::array<double, 3> x{{-1e308, -1e308, -1e308}};
    const int n = mesh.localNode(id);
    if (n >= 0) x = mesh.coord(n);
    if (parts) MPI_Allreduce(MPI_IN_PLACE, x.data(), 3, MPI_DOUBLE, MPI_MAX, comm);
    return Eigen::Vector3d(x.data());
  };
  std::unique_ptr<NodeDirectory> directory;
  if (parts) directory = std::make_unique<NodeDirectory>(comm, mesh);
  int me = 0;
  MPI_Comm_rank(comm, &me);
  constexpr long long kNone = std::numeric_limits<long long>::max();
  std::vector<BodySupport> out(held.size());
  for (size_t b = 0; b < held.size(); ++b) {
    BodySupport& sup = out[b];
    long long count = 0;  // each node counted by its lowest holder
    for (int n : held[b]) count += !parts || directory->lowestHolder()[n] == me ? 1 : 0;
    std::array<int, 3> dirs{{fixedDir[b][0], fixedDir[b][1], fixedDir[b][2]}};
    if (parts) {
      MPI_Allreduce(MPI_IN_PLACE, &count, 1, MPI_LONG_LONG, MPI_SUM, comm);
      MPI_Allreduce(MPI_IN_PLACE, dirs.data(), 3, MPI_INT, MPI_MAX, comm);
    }
    sup.nodes = count;
    for (int c = 0; c < 3; ++c) sup.fixed[c] = dirs[c] != 0;
    if (mesh.dim() == 2 || count < 3) {
      sup.enoughNodes = count >= (mesh.dim() == 2 ? 2 : 3);
      continue;
    }
    const Eigen::Vector3d a = coordOf(allMin(held[b].empty() ? kNone : mesh.nodeId(*held[b].begin())));
    double far = 0.0;
    long long farId = kNone;
    for (int n : held[b]) {
      const double d = (Eigen::Vector3d(mesh.coord(n).data()) - a).norm();
      if (d > far) far = d, farId = mesh.nodeId(n);
    }
    const double farAll = allMax(far);
    if (farAll == 0.0) continue;  // every node at one point
    const Eigen::Vector3d bFar = coordOf(allMin(far == farAll ? farId : kNone));
    double area = 0.0;
    for (int n : held[b]) area = std::max(area, (bFar - a).cross(Eigen::Vector3d(mesh.coord(n).data()) - a).norm());
    sup.enoughNodes = allMax(area) > 1e-12 * farAll * farAll;  // relative to the set's extent: not collinear
  }
  return out;
}

}  // namespace

void requireSupportedBodies(const Mesh& mesh, const BoundaryConditions& bcs, const ContactOptions& contact,
                            bool feti, bool dynamic, MPI_Comm comm) {
  // In dynamics the mass holds every body (K + c M is nonsingular): a free
  // body is legal there.
  if (dynamic) return;
  // A pair between two surfaces of one body (self-contact) cannot hold it:
  // its forces are internal to the body.
  std::vector<char> inContact(mesh.numBodies(), 0);
  for (const auto& pr : contact.pairs) {
    const int slaveBody = mesh.bodyIndex(pr.slaveSet.substr(0, pr.slaveSet.find('/')));
    const int masterBody = mesh.bodyIndex(pr.masterSet.substr(0, pr.masterSet.find('/')));
    if (slaveBody != masterBody) inContact[slaveBody] = inContact[masterBody] = 1;
  }
  const int dim = mesh.dim();
  std::vector<std::set<int>> fixedNodes(mesh.numBodies());
  std::vector<std::array<bool, 3>> fixedDir(mesh.numBodies(), {false, false, false});
  for (const auto& d : bcs.displacements)
    for (int n : mesh.nodeSet(d.setName)) {
      int b = 0;
      while (!(n >= mesh.body(b).firstNode && n < mesh.body(b).firstNode + mesh.body(b).numNodes)) ++b;
      fixedNodes[b].insert(n);
      for (int c = 0; c < dim; ++c) fixedDir[b][c] = fixedDir[b][c] || d.fix[c];
    }
  const std::vector<BodySupport> support = bodySupports(mesh, fixedNodes, fixedDir, comm);
  for (int b = 0; b < mesh.numBodies(); ++b) {
    const BodySupport& s = support[b];
    const bool supported = s.nodes > 0 && s.enoughNodes && s.fixed[0] && s.fixed[1] && (dim == 2 || s.fixed[2]);
    // FETI-DP: contact rows are dual constraints; they cannot remove the
    // rigid modes of K~ (the coarse problem would be singular).
    DDC_INPUT_REQUIRE(supported || !inContact[b] || !feti,
                      "body '" << mesh.body(b).name
                               << "' is held only by contact: with Solver/Strategy = FETI-DP every body must be "
                                  "supported by its own prescribed displacements (Boundary Conditions: "
                               << (dim == 2 ? "x and y, at least two nodes" : "x, y and z, at least three nodes not on one line")
                               << "), because the contact rows are dual constraints and cannot "
                                  "fix the rigid-body modes of the subdomain problems; use Solver/Strategy = "
                                  "Monolithic, or prescribe displacements on the body");
    DDC_INPUT_REQUIRE(inContact[b] || supported,
                      "body '" << mesh.body(b).name
                               << "' is not supported: its prescribed displacements (Boundary Conditions) must "
                               << (dim == 2 ? "act in both x and y and on at least two nodes"
                                            : "act in x, y and z and on at least three nodes not on one line")
                               << " to remove its rigid-body motion, and no contact pair joins it to another "
                                  "body");
  }
}

Partition partitionModel(const Mesh& mesh, const PL& part, const std::string& strategy, MPI_Comm comm,
                         const std::string& baseDirectory) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  int nsub = part.get<int>("Number of Subdomains");
  if (nsub == 0) nsub = automaticSubdomainCount(mesh, part, strategy, ranks);
  Partition partition;
  const std::string method = part.get<std::string>("Method");
  // Parts of a mesh come from buildMeshInRanges() (or buildMeshOnRankZero()
  // in a host code), which PT-Scotch alone partitions (meshOrigin()).
  DDC_CHECK(!mesh.isPart() || method == "PT-Scotch", "partitionModel() of a part of a mesh with Method " << method);
  auto requireCount = [&](int count) {
    const int given = part.get<int>("Number of Subdomains");
    DDC_INPUT_REQUIRE(given == 0 || given == count, "'Partition/Number of Subdomains' = "
                                                        << given << " contradicts Method = " << method << ", which gives "
                                                        << count << " subdomains (use 0 or " << count << ")");
  };
  if (method == "Box Grid") {
    partition = partitionBoxGrid(mesh, part.get<int>("Box Grid X"), part.get<int>("Box Grid Y"),
                                 part.get<int>("Box Grid Z"));
    requireCount(partition.numSubdomains);
  } else if (method == "Element Map File") {
    std::string file = part.get<std::string>("Element Map File");
    DDC_INPUT_REQUIRE(!file.empty(), "parameter 'Partition/Element Map File' is required with Method = Element Map File");
    file = resolveDeckFile(file, baseDirectory);
    partition = partitionFromFile(mesh, file);
    requireCount(partition.numSubdomains);
  } else if (method == "By Body") {
    partition = partitionByBody(mesh);
    requireCount(partition.numSubdomains);
  } else {
    Activity activity("partitioning " + std::to_string(mesh.numGlobalElements()) + " elements into " +
                      std::to_string(nsub) + " subdomains (" + method + ")");
    if (mesh.isPart())
      partition = partitionRangePtScotch(mesh, nsub, comm);
    else
      partition = method == "PT-Scotch" ? partitionPtScotch(mesh, nsub, comm) : partitionMetis(mesh, nsub);
  }
  DDC_INPUT_REQUIRE(partition.numSubdomains >= ranks,
                    "'Partition/Number of Subdomains' (" << partition.numSubdomains
                                                         << ") must be at least the number of MPI ranks (" << ranks
                                                         << ")");
  return partition;
}

std::string partitionSummary(const Mesh& mesh, const Partition& partition, const std::string& method,
                             MPI_Comm comm) {
  std::vector<long long> count(partition.numSubdomains, 0);
  for (int s : partition.elementSubdomain) ++count[s];
  if (mesh.isPart())
    MPI_Allreduce(MPI_IN_PLACE, count.data(), partition.numSubdomains, MPI_LONG_LONG, MPI_SUM, comm);
  const long long largest = count.empty() ? 0 : *std::max_element(count.begin(), count.end());
  const double mean = partition.numSubdomains ? double(mesh.numGlobalElements()) / partition.numSubdomains : 0.0;
  std::ostringstream os;
  os << "partition: " << partition.numSubdomains << " subdomains by " << method << ", edge cut "
     << partition.edgeCut << " facets, largest subdomain " << largest << " elements (mean " << std::fixed
     << std::setprecision(1) << mean << ")";
  return os.str();
}

Partition balancedPartition(const Mesh& mesh, const PL& part, const std::string& strategy, int ranks) {
  Partition partition;
  if (!isGraphPartitioner(part.get<std::string>("Method"))) return partition;
  int nsub = part.get<int>("Number of Subdomains");
  if (nsub == 0) nsub = automaticSubdomainCount(mesh, part, strategy, ranks);
  const long long ne = mesh.numGlobalElements();
  partition.numSubdomains = std::max(1, static_cast<int>(std::min<long long>(nsub, std::max(ne, 1LL))));
  partition.elementSubdomain.resize(mesh.numElements());
  for (int e = 0; e < mesh.numElements(); ++e)
    partition.elementSubdomain[e] = static_cast<int>(mesh.elementId(e) * partition.numSubdomains / ne);
  return partition;
}

}  // namespace ddc
