// Contact search and tracking for node-to-segment contact in 2-D: which
// master segment each slave node is paired with, its closest-point projection
// ξ, outward normal n and normal gap g_N (doc/contact.md). Straight 2-node
// master segments (sides of Quad4 bodies) only. A test reference, not part
// of the library: the contact component pairs every facet type, Line2
// included, with the facet search of DDC_FacetSearch.hpp; this closed-form
// search is its 2-D special case, and both apply the facing rule of
// DDC_FacetSearch.hpp (facingVerdict()).
//
// Geometry rules (one place, used by the global search and the tracking alike,
// so both give bitwise the same numbers for the same pairing):
//
//  - Segment k with nodes x1, x2 (in MasterSurface order), t = x2 − x1.
//    Closest projection ξ = (x_s − x1)·t / |t|²; the slave projects *inside*
//    if −ε ≤ ξ ≤ 1 + ε, ε = kEndTolerance = 1e-10: a slave node on the end
//    node of a master surface (a patch whose slave and master surfaces end
//    together) stays inside whatever the round-off of its position. Clamped point x̄ = x1 if ξ ≤ 0, x2 if ξ ≥ 1 (the node
//    coordinates themselves, so the two segments at a node tie exactly),
//    x1 + ξ t otherwise. Distance d_k = |x_s − x̄|.
//  - Unit outward normal n = (t_y, −t_x)/|t| (the body is on the left of
//    the direction of travel, DDC_Mesh.hpp Segment). Gap g = n·(x_s − x1):
//    positive = separated, negative = penetration (Wriggers ch. 4 / paper
//    eq. 1 with ξ, n frozen).
//  - Candidates are the segments with d_k ≤ search radius. The pairing is the
//    candidate with the smallest key (d_k, projects-outside, k): nearest
//    clamped point first; on an exact distance tie a segment the slave
//    projects inside is preferred, then the lowest segment index. The key is
//    a total order evaluated with the same arithmetic everywhere, so every
//    rank (replicated data) and both search paths agree.
//  - If the slave projects outside the chosen segment, the nearest point of
//    the whole surface is a node: a convex corner's blind spot (the slave
//    projects outside both segments at the corner) or beyond a free end.
//    The pairing is then reported with viaCorner = true, ξ clamped to 0 or 1,
//    point = that node, and the gap/normal of the chosen segment (of the two
//    segments at a corner: the lower index, they tie). Beyond a free end the
//    consumer decides whether such a pair may be active (the end segment's
//    normal says nothing about the space past the end): test
//    `cand.viaCorner && master.neighbour(cand.segment, cand.xi < 0.5 ? 0 : 1) < 0`.
//  - No candidate (farther than the radius from every segment): segment = −1;
//    the slave has left the master surface.
//  - Facing rule (doc/contact.md "Which slave nodes pair"; only with a
//    FacingRule): the nearest segment k found above is accepted only if
//      (a) n_s·n_k < 0, n_s the slave node's outward normal (the normalised
//          sum of the unit outward normals of the slave segments at the node,
//          current configuration), n_k segment k's outward normal; and
//      (b) a slave behind the segment (g < 0) is less deep than
//          kFacingDepthFraction times the depth of the element that owns
//          segment k (its extent normal to the segment, reference
//          configuration): −g < ½ depth_k.
//    Otherwise the slave is not paired (segment = −1) and the candidate says
//    why (rejection, rejectedSegment; its ξ, gap, normal, ... are those of
//    the rejected segment). The rule acts on the result of the key above, so
//    tracking and the global search still agree bitwise, and a pairing the
//    rule accepts is exactly the pairing without the rule.
#pragma once

#include <Eigen/Dense>

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "DDC_FacetSearch.hpp"  // the facing rule; kEndTolerance (DDC_NodeToSurface.hpp)

namespace ddc {

class Mesh;

/// The master surface: oriented straight 2-node segments (mesh node ids) and
/// their adjacency, built from shared nodes. The surface may be one or several
/// open chains (free ends) and/or closed loops.
class MasterSurface {
 public:
  /// \param segments node pairs (x1, x2) oriented with the body on the left
  ///        of x1 → x2, e.g. from masterSegmentsFromSideSet().
  /// \throws InputError if there are no segments, a segment repeats a node or
  ///         has a negative id, or the segments do not form simple
  ///         consistently oriented chains (a node is the start node of two
  ///         segments or the end node of two segments: a branch, a pinch, or
  ///         a segment listed twice / reversed).
  explicit MasterSurface(std::vector<std::array<int, 2>> segments);

  int numSegments() const { return static_cast<int>(segments_.size()); }
  /// Mesh node ids (x1, x2) of segment k.
  const std::array<int, 2>& segment(int k) const { return segments_[k]; }
  /// The segment sharing node `end` (0: x1, 1: x2) of segment k; −1 at a
  /// free end.
  int neighbour(int k, int end) const { return neighbours_[k][end]; }
  /// The distinct mesh node ids of the surface, ascending.
  const std::vector<int>& nodes() const { return nodes_; }
  /// Position of mesh node `node` in nodes() (−1 if not a surface node).
  int localNode(int node) const;

 private:
  std::vector<std::array<int, 2>> segments_;
  std::vector<std::array<int, 2>> neighbours_;
  std::vector<int> nodes_;
};

/// The facing rule's verdict (facingVerdict() of DDC_FacetSearch.hpp, z = 0)
/// for a slave node with outward normal `slaveNormal` at gap `gap` from a
/// master segment with outward normal `masterNormal`, allowed to lie
/// `penetrationLimit` behind it (the rule at the top of this file).
ContactRejection facingVerdict(const Eigen::Vector2d& slaveNormal, const Eigen::Vector2d& masterNormal, double gap,
                               double penetrationLimit);
/// What the facing rule needs besides the master surface: the slave surface
/// (for nodal normals) and the depth of each master segment's element.
struct FacingRule {
  /// Segments of the slave surface (mesh node ids), oriented with the slave
  /// body on the left (e.g. from masterSegmentsFromSideSet() on the slave side
  /// set). Every slave node must be on one; the positions of the other nodes
  /// of the segments at a slave node are read in update().
  std::vector<std::array<int, 2>> slaveSegments;
  /// Per master segment (MasterSurface order): the depth of the element that
  /// owns it (masterElementDepths()), > 0.
  std::vector<double> masterDepths;
};

/// The pairing of one slave node (see the geometry rules at the top).
struct ContactCandidate {
  /// Master segment index in MasterSurface, −1 if none within the radius.
  int segment = -1;
  /// Projection parameter ξ ∈ [0, 1] from x1 to x2 (clamped if viaCorner).
  double xi = 0.0;
  /// Normal gap g = n·(x_s − x1): > 0 separated, < 0 penetration.
  double gap = 0.0;
  /// |x_s − point|.
  double distance = 0.0;
  /// Unit outward normal of the segment.
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();
  /// Closest point x̄ = x1 + ξ t (the corner / end node if viaCorner).
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  /// The slave projects outside the chosen segment: a convex corner's blind
  /// spot or beyond a free end.
  bool viaCorner = false;
  /// The slave node's outward normal n_s (zero without a FacingRule, or if
  /// the normals of its slave segments cancel).
  Eigen::Vector2d slaveNormal = Eigen::Vector2d::Zero();
  /// Not None: the nearest segment within the radius, `rejectedSegment`, failed
  /// the facing rule; segment is then −1 and xi, gap, distance, normal, point
  /// and viaCorner describe the rejected segment.
  ContactRejection rejection = ContactRejection::None;
  int rejectedSegment = -1;
};

/// Work counters, cumulative over all update() calls. "Query" = one slave
/// node in one update().
struct ContactSearchCounters {
  long trackingCalls = 0;      ///< queries started by tracking (slave had a segment, not forced global)
  long trackingFallbacks = 0;  ///< of those, queries where tracking failed and the global search answered
  long globalSearches = 0;     ///< queries answered by the global search (forced, no previous segment, or fallback)
  long gridBuilds = 0;         ///< bin grids built (at most one per update, only if a global query occurs)
  long projections = 0;        ///< slave–segment projections evaluated (the work measure)
};

/// Node-to-segment contact search with tracking.
///
/// Global search: a uniform grid of square bins over the bounding box of the
/// master segments inflated by the search radius; each segment is registered
/// in every bin its inflated bounding box overlaps, so a slave query looks at
/// one bin only (never all pairs). Cell size max(mean segment length, radius);
/// only occupied bins are stored. The grid is rebuilt from the current
/// master positions lazily, once per update() that needs a global query.
///
/// Tracking: from the slave's previous segment, walk along the surface to the
/// adjacent segment with the smaller key (d_k, outside, k) until no neighbour
/// is smaller (a local minimum of the distance along the surface). It falls
/// back to the global search if the walk would leave the surface (the local
/// minimum is past a free end), exceeds the step limit, or ends farther than
/// the radius. Tracking equals the global search whenever the global pairing
/// is the local minimum reached from the previous segment — always for
/// motions small against the surface's features (curvature radius, distance
/// to other parts of the surface). It cannot see a *different* part of the
/// surface becoming nearer (a fold, a second chain): call update() with
/// forceGlobal when that can happen, e.g. at the start of each load step.
///
/// All data are replicated; every rank computes the same pairing.
class ContactSearch {
 public:
  /// \param master the master surface
  /// \param slaveNodes mesh node ids of the slave nodes (distinct, not nodes
  ///        of the master surface)
  /// \param searchRadius pairs farther apart are not candidates (> 0)
  /// \param maxTrackingSteps step limit of the tracking walk: moves from a
  ///        segment to a neighbour (≥ 0; 0 still lets tracking confirm the
  ///        previous segment)
  /// \throws InputError for a non-positive or non-finite radius, a negative
  ///         step limit, a repeated or negative slave node, or a slave node
  ///         on the master surface.
  ContactSearch(MasterSurface master, std::vector<int> slaveNodes, double searchRadius,
                int maxTrackingSteps = 8);
  /// The same with the facing rule (see the top of this file).
  /// \throws InputError as above, and if a slave node is on no slave segment,
  ///         a slave segment repeats a node or has a negative id, or the
  ///         depths are not one positive finite value per master segment.
  ContactSearch(MasterSurface master, std::vector<int> slaveNodes, double searchRadius, FacingRule rule,
                int maxTrackingSteps = 8);

  /// Pair every slave node with a master segment in the current configuration.
  /// \param currentPosition current coordinates x = X + u of a mesh node id
  ///        (called for every master and slave node and, with a FacingRule,
  ///        for the nodes of the slave segments at the slave nodes)
  /// \param forceGlobal ignore previous pairings (global search for all)
  /// \throws SolverError if a master segment has zero length or a position
  ///         is not finite.
  void update(const std::function<Eigen::Vector2d(int node)>& currentPosition, bool forceGlobal);

  /// One candidate per slave node, in the order of slaveNodes(); all
  /// segment = −1 before the first update().
  const std::vector<ContactCandidate>& candidates() const { return candidates_; }
  const std::vector<int>& slaveNodes() const { return slaves_; }
  const MasterSurface& master() const { return master_; }
  double searchRadius() const { return radius_; }
  bool hasFacingRule() const { return hasRule_; }
  /// How deep a slave may lie behind master segment k and be paired with it:
  /// kFacingDepthFraction × its element's depth (infinite without a FacingRule).
  double penetrationLimit(int k) const;

  const ContactSearchCounters& counters() const { return counters_; }
  /// Shortcuts for counters().globalSearches / .trackingCalls (per query).
  long globalSearches() const { return counters_.globalSearches; }
  long trackingCalls() const { return counters_.trackingCalls; }

 private:
  struct Eval;
  Eval evaluate(int k, const Eigen::Vector2d& xs);
  void buildGrid();
  Eval globalQuery(const Eigen::Vector2d& xs);
  Eval trackingQuery(int start, const Eigen::Vector2d& xs);
  long long cellKey(long long ix, long long iy) const;
  long long cellIndex(double v, double origin) const;

  MasterSurface master_;
  std::vector<int> slaves_;
  double radius_;
  int maxSteps_;
  std::vector<ContactCandidate> candidates_;
  ContactSearchCounters counters_;

  // Segments as positions in master_.nodes(); per update: master node
  // positions in that order.
  std::vector<std::array<int, 2>> local_;
  std::vector<Eigen::Vector2d> x_;
  // Facing rule: the rule, and per slave the slave segments at it.
  bool hasRule_ = false;
  FacingRule rule_;
  std::vector<std::vector<int>> slaveSegmentsAt_;
  Eigen::Vector2d slaveNormal(std::size_t i, const std::function<Eigen::Vector2d(int node)>& currentPosition) const;
  // Bin grid (valid when gridValid_): sorted (cell key, segment) pairs.
  bool gridValid_ = false;
  double x0_ = 0, y0_ = 0, xHi_ = 0, yHi_ = 0, h_ = 1;
  long long nx_ = 1, ny_ = 1;
  std::vector<std::pair<long long, int>> bins_;
};

/// The segments of side set `sideSet` as node pairs for MasterSurface.
/// \throws InputError if the side set does not exist (listing the known ones)
///         or has 3-node (Quad9) sides: "contact surfaces must be Quad4 sides
///         for now".
std::vector<std::array<int, 2>> masterSegmentsFromSideSet(const Mesh& mesh, const std::string& sideSet);

/// For each segment of side set `sideSet` (the order of
/// masterSegmentsFromSideSet()): the depth of the element it is a side of,
/// i.e. how far the element's nodes reach behind the segment along its inward
/// normal, max_a −n·(X_a − X_1), in the reference configuration. For a
/// rectangular element: its height over that side.
/// \throws InputError as masterSegmentsFromSideSet(), or if an element has no
///         depth (degenerate).
std::vector<double> masterElementDepths(const Mesh& mesh, const std::string& sideSet);

}  // namespace ddc
