// Contact search and tracking over a master surface of facets of any type
// (3-D faces Tri3/Tri6/Quad4/Quad8/Quad9, or 2-D segments Line2/Line3): which
// facet each slave node pairs with, the closest point, the normal and the gap
// (doc/contact.md, "Curved facets and 3-D"). The contact component pairs
// every facet type with it (its closed-form special case, the 2-D
// straight-segment search, is a test reference in packages/contact/test).
//
// Nearest point of one facet (`nearestPoint()`), the rule at facet edges and
// corners:
//  - Interior: projectOntoFacet() converges inside the reference facet (within
//    kEndTolerance): the closest point, the facet's normal there, the signed
//    gap g = n·(x_s − x(ξ̄)).
//  - Otherwise the nearest point of the facet's boundary, taken as the
//    polyline through its boundary nodes (corner, mid-edge, corner: exact for
//    linear facets, the chords of a quadratic edge otherwise): kind Edge (inside
//    a chord) or Vertex (at a node), with the normal the unit direction from
//    that point to the slave and the gap the distance (≥ 0). At a convex edge
//    or corner, where a slave sees no facet from inside, this gives the
//    nearest-point projection with the direction as normal and the contact is
//    never lost; at a concave one the slave's interior projections onto the
//    two facets exist and the nearer one wins.
// The pairing is the candidate with the smallest key (distance, not interior,
// facet index): nearest first; on an exact tie an interior projection, then
// the lowest facet index (a total order: every rank and both search paths
// agree).
//
// Global search: a uniform 3-D grid of cubic bins over the facets' bounding
// boxes inflated by the search radius; each facet sits in every bin its
// inflated box overlaps, so a slave query looks at one bin. Tracking: from the
// previous facet, walk to the neighbour (facets sharing a boundary node) with
// the smallest key while it improves; fall back to the global search if the
// walk exceeds its step limit or ends farther than the radius.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "DDC_NodeToSurface.hpp"
#include "DDC_ReferenceCell.hpp"

namespace ddc {

/// Which part of a facet the nearest point lies on.
enum class FacetPointKind { Interior, Edge, Vertex };

/// The nearest point of one facet to a slave node.
struct FacetCandidate {
  int facet = -1;           ///< index in the surface, −1: none within the radius
  /// Interior: ξ̄; Edge/Vertex: the reference coordinates of `point` along
  /// its chord (exact on straight edges; on a curved edge x(ξ) is the point
  /// of the edge the chord point maps to, not `point` itself).
  std::array<double, 2> xi{{0.0, 0.0}};
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double gap = 0.0;         ///< Interior: n·(x_s − x̄) (signed); Edge/Vertex: the distance
  double distance = 0.0;    ///< |x_s − point|
  FacetPointKind kind = FacetPointKind::Interior;
};

/// Which part of the facing rule rejected the nearest master facet.
enum class ContactRejection {
  None,       ///< accepted (or no facet within the radius)
  NotFacing,  ///< n_s·n_m >= 0: the slave surface does not face the facet
  TooDeep     ///< behind the facet by kFacingDepthFraction of its element's depth or more
};

/// Fraction of the master element's depth a slave may lie behind the master
/// facet and still be paired with it (doc/contact.md "Which slave nodes
/// pair"): deeper, it is nearer the far side of that element than the
/// facet, which a contact increment cannot produce on a mesh that resolves
/// the motion, but a node of the other side of a thin body (or a node that
/// started inside the master body) always is.
constexpr double kFacingDepthFraction = 0.5;

/// The facing rule (doc/contact.md "Which slave nodes pair") for a slave
/// node with outward normal `slaveNormal` (the normalised sum of the unit
/// outward normals of its slave facets) at gap `gap` from a master facet
/// with outward normal `masterNormal`: the facet is accepted only if (a)
/// n_s·n_m < 0 and (b) a slave behind it (g < 0) lies less than
/// `penetrationLimit` (kFacingDepthFraction × the depth of the facet's
/// element) behind it. One function for every consumer that pairs or keeps
/// a pairing (z = 0 in 2-D).
ContactRejection facingVerdict(const Eigen::Vector3d& slaveNormal, const Eigen::Vector3d& masterNormal, double gap,
                               double penetrationLimit);

/// The nearest point of facet `nodes` (positions numCellNodes x dim) to xs.
FacetCandidate nearestPoint(CellType facet, const Eigen::MatrixXd& nodes, const Eigen::VectorXd& xs);

/// A master surface of facets of one type (node ids in the facet type's node
/// order, outward orientation) and their adjacency (shared nodes).
class FacetSearch {
 public:
  /// \param facets node ids per facet
  /// \param radius pairs farther apart are not candidates (> 0)
  /// \param maxTrackingSteps step limit of the tracking walk
  /// \throws std::invalid_argument for a non-facet type, a facet with the
  ///         wrong number of nodes, no facets, or a non-positive radius.
  FacetSearch(CellType facet, std::vector<std::vector<int>> facets, double radius, int maxTrackingSteps = 8);
  /// Pair each slave node (ids) at the current node positions.
  /// \param position current coordinates of a node id (dim entries)
  void update(const std::vector<int>& slaves, const std::function<Eigen::VectorXd(int)>& position, bool forceGlobal);
  /// One candidate per slave of the last update(), in its order.
  const std::vector<FacetCandidate>& candidates() const { return candidates_; }
  const std::vector<int>& neighbours(int facet) const { return neighbours_[facet]; }
  long globalQueries() const { return globalQueries_; }
  long trackingQueries() const { return trackingQueries_; }
  long trackingFallbacks() const { return trackingFallbacks_; }

 private:
  FacetCandidate evaluate(int f, const Eigen::VectorXd& xs) const;
  FacetCandidate globalQuery(const Eigen::VectorXd& xs);
  void buildGrid();
  long long key(long long i, long long j, long long k) const;

  CellType type_;
  int dim_;
  std::vector<std::vector<int>> facets_;
  std::vector<std::vector<int>> neighbours_;
  double radius_;
  int maxSteps_;
  std::vector<FacetCandidate> candidates_;
  std::vector<int> previous_;  ///< per slave: facet of the last update
  std::function<Eigen::VectorXd(int)> position_;
  // grid
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double h_ = 1.0;
  long long n_[3] = {1, 1, 1};
  std::vector<std::pair<long long, int>> bins_;
  long globalQueries_ = 0, trackingQueries_ = 0, trackingFallbacks_ = 0;
};

}  // namespace ddc
