// Mesh-aware set-up of the FETI-DP subdomain problems: which nodes are
// primal (corners), each subdomain's free DOFs and its local stiffness
// pattern. The algebra lives in the feti package (FetiDpSolver), which knows
// nothing of meshes.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "DDC_DirectSolver.hpp"

namespace ddc {

class Model;

/// Which 3-D interface nodes are vertices (doc/feti-dp.md, "In 3-D").
enum class VertexRule {
  /// Every node of a subdomain edge except those next to an edge end (the
  /// strong coarse space for FETI-DP with vertex constraints only).
  EdgeNodes,
  /// The edge ends only: nodes of an edge whose place no node of their
  /// elements shares. For use with edge averages
  /// (FetiDpSolver "Primal Constraints" with Edges), which constrain the
  /// rest of each edge.
  EdgeEnds
};

/// Primal node selection (doc/feti-dp.md, "Primal nodes"). In 2-D:
///  1. interface nodes shared by ≥ 3 subdomains (cross points);
///  2. interface nodes on the mesh boundary (the ends of a subdomain–
///     subdomain interface that reaches the boundary);
/// in 3-D, the vertices. With VertexRule::EdgeNodes: interface nodes whose
/// set of subdomains (the mesh boundary counted as one more) has ≥ 3 members
/// and is not strictly contained in that of a node of one of their elements
/// (in effect every edge node but those next to an edge end). With
/// VertexRule::EdgeEnds: of each class of edge nodes (connected, one set),
/// the node itself if it is alone, else its two ends when no one-node class
/// touches it; on contact surfaces the EdgeNodes rule; and (rule 2b) each
/// face, the nodes two subdomains share when they do not lie on one line,
/// gets primal nodes until the two subdomains' relative rigid modes are
/// fixed (no hinge through two edge ends);
///  3. every subdomain must be fixed against its rigid modes. 2-D: it needs
///     two distinct "anchor" nodes (primal, or carrying a prescribed DOF)
///     and prescribed DOFs in both directions unless it has two primal
///     nodes. 3-D: the six rigid modes restricted to its primal DOFs and
///     prescribed DOFs must be independent (at least three primal nodes not
///     on one line, or prescribed DOFs that do the same). Where the rules
///     above give fewer, interface nodes of the subdomain are made primal
///     (the one farthest from the existing anchors, then the one farthest
///     from those).
/// On a part of a mesh (Mesh::part(), each rank its subdomains' elements)
/// the ranks agree through the holders of each node and decide in turns,
/// and the selection is the one made on the whole mesh. Collective.
/// \returns per mesh node 1 if primal. `report` receives one line per
///          subdomain that needed rule 3 (every subdomain's, on every rank).
/// \param massive the subdomain matrices are K^s + c M^s with c > 0
///        (dynamics): nonsingular, so a subdomain that rule 3 cannot anchor
///        is left floating (reported) instead of refused.
/// \throws InputError for a floating subdomain without interface nodes
///         (e.g. a body that is its own subdomain and has no boundary
///         conditions) unless `massive`: no choice of corners can fix it.
std::vector<char> selectPrimalNodes(const Model& model, std::vector<std::string>* report = nullptr,
                                    VertexRule rule = VertexRule::EdgeNodes, bool massive = false);

/// One subdomain's problem: its free DOFs (global ids, sorted), which are
/// primal, the local stiffness (MPI_COMM_SELF, local numbering) and, for
/// each of its elements, the local index of each element DOF (−1 where the
/// DOF is prescribed).
struct SubdomainSystem {
  int id = -1;
  std::vector<GO> dofs;
  std::vector<char> primal;
  std::vector<int> component;  ///< per DOF: displacement component 0..dim-1
  std::vector<double> coordinates;  ///< per DOF: dim coordinates of its node
  Teuchos::RCP<CrsMatrix> K;
  std::vector<int> elements;
  std::vector<std::vector<int>> elementLocal;
};

/// The subdomain systems of this rank's subdomains, with the stiffness
/// patterns built from their elements (values zero).
std::vector<SubdomainSystem> buildSubdomainSystems(const Model& model, const std::vector<char>& primalNode);

}  // namespace ddc
