#include "DDC_MeshInRanges.hpp"

#include <Teuchos_XMLParameterListHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "DDC_AnalysisParameters.hpp"
#include "DDC_Error.hpp"
#include "DDC_ExodusMesh.hpp"
#include "DDC_Gmsh.hpp"
#include "DDC_InputDeck.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_ModelSetUp.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

using PL = Teuchos::ParameterList;

namespace {

/// Whether a body of this Generator is read from a file (in ranges).
bool readsFile(const std::string& generator) { return generator == "Exodus" || generator == "Gmsh"; }

}  // namespace

bool readsByRange(const std::string& generator) { return generatesByRange(generator) || readsFile(generator); }

bool meshBuiltInRanges(const PL& params) {
  if (!params.isSublist("Partition") || !params.isSublist("Mesh")) return false;
  const PL& partition = params.sublist("Partition");
  if (partition.get<bool>("Mesh On Every Rank") || partition.get<std::string>("Method") != "PT-Scotch") return false;
  const PL& mesh = params.sublist("Mesh");
  if (!mesh.isSublist("Bodies") || mesh.sublist("Bodies").numParams() == 0) return false;
  const PL& bodies = mesh.sublist("Bodies");
  for (auto it = bodies.begin(); it != bodies.end(); ++it) {
    if (!bodies.isSublist(bodies.name(it))) return false;  // buildMesh() says what is wrong
    const PL& body = bodies.sublist(bodies.name(it));
    // An unset Generator is Rectangle (bodyValidParameters()).
    const std::string generator =
        body.isType<std::string>("Generator") ? body.get<std::string>("Generator") : std::string("Rectangle");
    if (body.isParameter("Generator") && !body.isType<std::string>("Generator")) return false;
    if (!readsByRange(generator)) return false;
  }
  return true;
}

MeshOrigin meshOrigin(const PL& params) {
  return meshBuiltInRanges(params) ? MeshOrigin::Ranges : MeshOrigin::EveryRank;
}

std::shared_ptr<Mesh> buildMeshOnRankZero(PL& meshParams, const ElementFactory& factory,
                                          const std::string& baseDirectory, const MemoryLimit* budget,
                                          const std::string& budgetHint, MPI_Comm comm) {
  // The parameters are read on every rank (defaults filled in place); their
  // errors are the same on every rank.
  PL& bodies = validatedBodies(meshParams);
  const auto validBody = bodyValidParameters(factory);
  for (auto it = bodies.begin(); it != bodies.end(); ++it) readBody(bodies, bodies.name(it), factory, *validBody);
  std::shared_ptr<Mesh> whole;
  runCollectively<InputError>(comm, [&] {
    if (commRank(comm) == 0) whole = buildMesh(meshParams, factory, baseDirectory, budget, budgetHint, MPI_COMM_SELF);
  });
  // The generators and readers filled their defaults on rank 0: every rank
  // continues with rank 0's parameters.
  std::string xml;
  if (commRank(comm) == 0) {
    std::ostringstream os;
    Teuchos::writeParameterListToXmlOStream(meshParams, os);
    xml = os.str();
  }
  long long length = static_cast<long long>(xml.size());
  MPI_Bcast(&length, 1, MPI_LONG_LONG, 0, comm);
  xml.resize(size_t(length));
  MPI_Bcast(xml.data(), int(length), MPI_CHAR, 0, comm);
  if (commRank(comm) != 0) meshParams = *Teuchos::getParametersFromXmlString(xml);
  const long long elements = commRank(comm) == 0 ? whole->numElements() : 0;
  Activity activity("sending each rank an even range of the mesh's elements (" + std::to_string(elements) +
                    " elements on rank 0)");
  return std::make_shared<Mesh>(Mesh::scatteredInRanges(comm, 0, whole.get()));
}

std::shared_ptr<Mesh> buildMeshInRanges(PL& meshParams, const ElementFactory& factory, const MemoryLimit* budget,
                                        const std::string& budgetHint, MPI_Comm comm,
                                        const std::string& baseDirectory) {
  PL& bodies = validatedBodies(meshParams);
  const auto validBody = bodyValidParameters(factory);
  // Every body and its element count before any is made: the even range
  // needs the total. The parameters are the same on every rank, and so are
  // the files' headers: so are these errors.
  std::vector<BodyInput> inputs;
  long long total = 0;
  for (auto it = bodies.begin(); it != bodies.end(); ++it) {
    inputs.push_back(readBody(bodies, bodies.name(it), factory, *validBody));
    const BodyInput& in = inputs.back();
    DDC_CHECK(readsByRange(in.generator), "buildMeshInRanges() of a " << in.generator << " body");
    const std::string at = in.path + "/" + in.generator;
    if (in.generator == "Exodus")
      runCollectively<InputError>(comm, [&] {
        total += exodusBodyElementCount(*in.generatorParams, in.name, in.cellType, at, baseDirectory);
      });
    else if (in.generator == "Gmsh")  // collective; agrees on its errors itself
      total += gmshBodyElementCount(*in.generatorParams, in.name, in.cellType, at, baseDirectory, comm);
    else
      total += structuredElementCount(in.generator, in.cellType, *in.generatorParams, at);
  }
  const auto [first, last] = evenShare(total, comm);
  const ElementRange range{first, last};
  auto mesh = std::make_shared<Mesh>(Mesh::startPart());
  if (budget && std::isfinite(budget->bytes)) mesh->setMemoryBudget(budget->bytes, budget->source, budgetHint);
  {
    const bool reads =
        std::any_of(inputs.begin(), inputs.end(), [](const BodyInput& in) { return readsFile(in.generator); });
    Activity activity(std::string(reads ? "reading" : "generating") + " the mesh in ranges of elements (" +
                      std::to_string(total) + " elements, " + std::to_string(range.last - range.first) +
                      " on this rank)");
    for (const BodyInput& in : inputs) {
      const std::string at = in.path + "/" + in.generator;
      PL& gp = *in.generatorParams;
      // The reader is collective and agrees on its errors itself.
      if (in.generator == "Exodus") {
        readExodusBodyInRange(*mesh, in.name, in.cellType, gp, at, baseDirectory, range, comm);
        continue;
      }
      if (in.generator == "Gmsh") {
        readGmshBodyInRange(*mesh, in.name, in.cellType, gp, at, baseDirectory, range, comm);
        continue;
      }
      runCollectively<InputError>(comm, [&] {
        if (in.generator == "Box")
          generateBox(*mesh, in.name, in.cellType, gp, at, range);
        else if (in.generator == "Annular Sector")
          generateAnnularSector(*mesh, in.name, in.cellType, gp, at, range);
        else if (in.generator == "Cylindrical Shell Sector")
          generateCylindricalShellSector(*mesh, in.name, in.cellType, gp, at, range);
        else if (in.generator == "Sphere Octant")
          generateSphereOctant(*mesh, in.name, in.cellType, gp, at, range);
        else
          generateRectangle(*mesh, in.name, in.cellType, gp, at, range);
      });
    }
  }
  for (int b = 0; b < mesh->numBodies(); ++b) requireBodyExtent(*mesh, b, inputs[b], comm);
  runCollectively<InputError>(comm, [&] {
    mesh->checkConnectivity();
    mesh->checkShapes(0, mesh->numElements());
  });
  return mesh;
}

}  // namespace ddc
