// Mesh-free choice of the FETI-DP primal vertices (doc/feti-dp.md, "Primal
// nodes"), for a host that has its subdomains' DOFs, coordinates and
// stiffness matrices but no mesh to hand to the analysis' corner rule.
//
// The rule is PETSc PCBDDC's graph rule: interface DOFs are grouped into
// nodes (the DOFs of a subdomain at the same coordinates), each node has its
// interface set (the subdomains sharing it, dofSharingSets()), and two nodes
// are neighbours if the stiffness matrix of a subdomain couples them. The
// nodes of one interface set that are connected through neighbours of the
// same set form an edge or a face; a node with no neighbour of its own set
// is a vertex: the cross points of a 2-D partition, the corners where
// subdomain edges meet in 3-D, a point where two subdomains only touch.
// Unlike the analysis' rule (selectPrimalNodes()), the ends of an interface
// at the mesh boundary are not vertices (they belong to their edge), so the
// edge / face averages ("Primal Constraints": the default, Automatic, is
// "Vertices and Edges") are what fixes a subdomain with no cross point; with "Vertices"
// alone such a subdomain stays floating and FetiDpSolver::numeric() reports
// it by id.
#pragma once

#include <mpi.h>

#include <vector>

#include "DDC_FetiDpSolver.hpp"

namespace ddc {

/// Per subdomain of `subs` (in order), per local DOF: 1 if it is a DOF of a
/// vertex (see the top of this file). Uses the fields id, dofs, K and
/// coordinates (dim values per DOF) of each FetiSubdomain; `primal` is
/// ignored. Collective over `comm`.
/// \throws std::invalid_argument (on every rank) for a dimension other than
///         2 or 3, missing coordinates, K not n x n, or a DOF not in
///         `ownedMap`.
std::vector<std::vector<char>> findPrimalVertices(MPI_Comm comm, const Map& ownedMap,
                                                  const std::vector<FetiSubdomain>& subs, int dim);

}  // namespace ddc
