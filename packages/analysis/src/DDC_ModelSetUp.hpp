// From the validated parameters to a Model: the mesh of every body, the
// element evaluators, the checks a model must pass before anything is
// solved (inverted elements, bodies nothing supports), and the partition.
// Each is a function of its own, in the order the Analysis calls them.
#pragma once

#include <Teuchos_Comm.hpp>
#include <mpi.h>
#include <Teuchos_ParameterList.hpp>
#include <memory>
#include <string>
#include <vector>

#include "DDC_BoundaryConditions.hpp"
#include "DDC_ContactParameters.hpp"
#include "DDC_Element.hpp"
#include "DDC_ElementFactory.hpp"
#include "DDC_Memory.hpp"
#include "DDC_Mesh.hpp"
#include "DDC_Partition.hpp"

namespace ddc {

/// A body of Mesh/Bodies, validated: its generator, the generator's
/// sublist and the mesh cell type of its element.
struct BodyInput {
  std::string name, path, generator;  ///< path: "Mesh/Bodies/<name>"
  CellType cellType = CellType::Quad4;
  Teuchos::ParameterList* generatorParams = nullptr;
};

/// "Mesh" validated at its level, and its sublist Bodies.
/// \throws InputError if Mesh/Bodies is missing or empty
Teuchos::ParameterList& validatedBodies(Teuchos::ParameterList& meshParams);

/// Mesh/Bodies/<name> validated against `validBody` (bodyValidParameters()),
/// with the cell type of its element in `factory`.
/// \throws InputError naming the parameter that is missing or wrong
BodyInput readBody(Teuchos::ParameterList& bodies, const std::string& name, const ElementFactory& factory,
                   const Teuchos::ParameterList& validBody);

/// Refuse body `body` of `mesh` if its extent or coordinates are so far
/// from 1 that the element arithmetic under- or overflows. On a part
/// (Mesh::isPart()) the ranks' nodes are taken together; collective.
void requireBodyExtent(const Mesh& mesh, int body, const BodyInput& input, MPI_Comm comm = MPI_COMM_SELF);

/// Build the mesh described by "Mesh" (validated in place). Exposed for tools
/// and tests. Cell types follow each body's element type in `factory`.
/// \param budget if given, the memory a rank may use for the replicated mesh
///        (Mesh::setMemoryBudget(): generators refuse a body that does not fit)
/// \param budgetHint what the user can do about it, for that message
/// \param comm the ranks that share the per-element checks (Mesh::checkShapes):
///        each checks an even share, and an error found on any of them is
///        thrown on all (that of the lowest element); collective over comm
std::shared_ptr<Mesh> buildMesh(Teuchos::ParameterList& meshParams, const ElementFactory& factory,
                                const std::string& baseDirectory, const MemoryLimit* budget = nullptr,
                                const std::string& budgetHint = "", MPI_Comm comm = MPI_COMM_SELF);

/// One element evaluator per body (index = body index), from
/// Mesh/Bodies/<body>/Element.
std::vector<std::shared_ptr<const Element>> makeBodyElements(const Mesh& mesh, Teuchos::ParameterList& meshParams,
                                                             const ElementFactory& factory);

/// The bodies whose Poisson's ratio makes them nearly incompressible, as a
/// warning for the user ("" if none): the elements are displacement-only
/// (no mixed u-p formulation), so they lock.
std::string nearlyIncompressibleBodies(const Mesh& mesh, const Teuchos::ParameterList& meshParams);

/// Refuse inverted or degenerate elements. The ranks of `comm` check an even
/// share of the elements each (of a part, Mesh::isPart(), each rank its
/// own); collective over comm.
/// \throws InputError on every rank, naming the lowest such element, its
///         body and its first node
void requireAdmissibleElements(const Mesh& mesh, const std::vector<std::shared_ptr<const Element>>& elements,
                               MPI_Comm comm = MPI_COMM_SELF);

/// Refuse a quasi-static model with a body that its prescribed
/// displacements do not hold and no contact pair joins to another body, and
/// under FETI-DP a body held only by contact (the contact rows are dual and
/// cannot remove the rigid modes of the subdomain problems). In dynamics
/// the mass holds every body. On a part of a mesh (Mesh::isPart()) the
/// ranks of `comm` take their nodes together and give the whole mesh's
/// verdict on every rank (collective).
/// \throws InputError naming the body and what it needs
void requireSupportedBodies(const Mesh& mesh, const BoundaryConditions& bcs, const ContactOptions& contact,
                            bool feti, bool dynamic, MPI_Comm comm = MPI_COMM_SELF);

/// The partition of "Partition" (validated): METIS, PT-Scotch (in parallel
/// over `comm`), By Body, Box Grid or an element map file (resolved against
/// `baseDirectory`), with the automatic subdomain count for `strategy` on
/// the ranks of `comm`. On parts of a mesh in ranges of element ids
/// (buildMeshInRanges(), buildMeshOnRankZero()), PT-Scotch gives each rank its elements'
/// subdomains (partitionRangePtScotch()). Collective.
/// \throws InputError for a count that contradicts the method or is below
///         the number of ranks, and the partitioners' errors
Partition partitionModel(const Mesh& mesh, const Teuchos::ParameterList& partition, const std::string& strategy,
                         MPI_Comm comm, const std::string& baseDirectory);

/// One progress line on a graph partition: its subdomain count, edge cut and
/// largest subdomain, "partition: 255 subdomains by METIS, edge cut 10921
/// facets, largest subdomain 530 elements (mean 514.0)".
/// On a part of a mesh (Mesh::isPart(): `partition` holds its elements'
/// subdomains) the counts are summed over `comm` (collective).
std::string partitionSummary(const Mesh& mesh, const Partition& partition, const std::string& method,
                             MPI_Comm comm = MPI_COMM_SELF);

/// What partitionModel() will give with METIS or PT-Scotch, before they run: its
/// subdomain count with the elements spread evenly (for a memory estimate
/// that refuses a run too large before the partitioning, which takes
/// seconds on large meshes). Another method: a partition of 0 subdomains.
/// On a part of a mesh: the subdomains of its elements in that spread.
Partition balancedPartition(const Mesh& mesh, const Teuchos::ParameterList& partition, const std::string& strategy,
                            int ranks);

}  // namespace ddc
