// A mesh no rank holds whole (doc/architecture.md, "What a distributed mesh
// has to change"): each rank generates or reads the bodies' elements of an
// even range of element ids, PT-Scotch partitions the ranges' dual graph in
// parallel, and each element moves to the rank of its subdomain
// (migratedRankPart()). The analysis takes this path when 'Partition/Mesh On
// Every Rank' is false and the partitioner is PT-Scotch: every body comes
// from a built-in generator (generatesByRange()), an Exodus II file
// (readExodusBodyInRange(): slabs of the file) or a Gmsh file
// (readGmshBodyInRange(): each rank keeps its range as the file streams
// by); the model it gives is the one cut from the whole mesh. A mesh only
// one rank can build is dealt in the same ranges by buildMeshOnRankZero().
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <mpi.h>

#include <memory>
#include <string>

#include "DDC_ElementFactory.hpp"
#include "DDC_Memory.hpp"
#include "DDC_Mesh.hpp"

namespace ddc {

/// Where a run's mesh comes from, by meshOrigin().
enum class MeshOrigin {
  EveryRank,  ///< every rank builds the whole mesh (and keeps its part without 'Mesh On Every Rank')
  Ranges,     ///< each rank generates or reads an even range of the elements (buildMeshInRanges())
};

/// Whether a body of this Generator can be made in ranges of elements: the
/// built-in generators (generatesByRange()), Exodus II and Gmsh files.
bool readsByRange(const std::string& generator);

/// Ranges where meshBuiltInRanges(params), else EveryRank.
MeshOrigin meshOrigin(const Teuchos::ParameterList& params);

/// Whether the validated parameters `params` (the whole deck; Mesh/Bodies
/// not yet validated) ask for a mesh built in ranges: 'Partition/Mesh On
/// Every Rank' = false, 'Partition/Method' = PT-Scotch, and every body's
/// Generator one that readsByRange().
bool meshBuiltInRanges(const Teuchos::ParameterList& params);

/// The bodies of "Mesh" (validated in place) generated or read (Exodus II
/// and Gmsh files, readExodusBodyInRange(), readGmshBodyInRange()) in this rank's even share of the element
/// ids (rank r of P: ids [N r / P, N (r + 1) / P) of the N elements of all
/// bodies): the part Mesh::part() would cut from the
/// whole mesh (generateBox() by ElementRange). The checks of buildMesh()
/// run on the parts and agree on every rank: body extents taken over the
/// ranks, element shapes each on its own rank, the error of the lowest
/// element id thrown on every rank. Collective.
/// \param budget if given, what a rank may use: each generator refuses its
///        share of a body that does not fit (Mesh::requireRoom())
/// \param baseDirectory what a relative file name is resolved against
/// \throws InputError on every rank, as buildMesh()
std::shared_ptr<Mesh> buildMeshInRanges(Teuchos::ParameterList& meshParams, const ElementFactory& factory,
                                        const MemoryLimit* budget, const std::string& budgetHint, MPI_Comm comm,
                                        const std::string& baseDirectory = ".");

/// The whole mesh of "Mesh" built or read by buildMesh() on rank 0 alone
/// (its checks and messages those of the whole mesh), then dealt to the
/// ranks in even ranges of element ids (Mesh::scatteredInRanges()): the
/// parts buildMeshInRanges() would make, for any body: for a host code whose
/// mesh only one rank can build, and the readers' reference in the tests.
/// Every rank validates the bodies' parameters in place. Collective.
/// \throws InputError on every rank, as buildMesh()
std::shared_ptr<Mesh> buildMeshOnRankZero(Teuchos::ParameterList& meshParams, const ElementFactory& factory,
                                          const std::string& baseDirectory, const MemoryLimit* budget,
                                          const std::string& budgetHint, MPI_Comm comm);

}  // namespace ddc
