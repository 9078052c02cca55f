// Which element of a body contains a point, in the reference configuration:
// the test behind the check that no slave node starts inside a master body
// where contact cannot reach it (doc/contact.md "Which slave nodes pair").
#pragma once

#include <Eigen/Dense>

#include <mpi.h>

#include <array>
#include <utility>
#include <vector>

namespace ddc {

class Mesh;

/// Point location in the elements of one body of a mesh (whole, or this
/// rank's part of it: see the constructor), by a uniform grid of bins
/// (squares in 2-D, cubes in 3-D) over the elements' bounding boxes (a query
/// tests the elements of one bin, never all of them).
///
/// Only corner nodes count: an element is taken as its linear sub-cell (exact
/// for Quad4, Tet4 and Hex8 with plane faces, the straight-sided
/// approximation for the quadratic cells).
///
/// 2-D: an element is the polygon of its corner nodes (nodes 0..3, counter-
/// clockwise). A point is *inside the body* if it lies in the closure of one
/// of its elements (to the left of every edge or on it, within kInsideMargin
/// times the edge's length) and not on the body's boundary (within that
/// margin of an edge that only one element has). So a point on a mesh line
/// between two elements is inside, while the nodes of the body's own surfaces
/// and the nodes of a body that merely touches it are not.
///
/// 3-D: the same definition with faces instead of edges. An element is the
/// polyhedron bounded by the triangles of its corner faces: a tetrahedron's
/// faces are triangles; a hexahedron's quadrilateral faces are each split
/// into two triangles along the diagonal through the face corner with the
/// smallest node number. Why this rule: the four corners of a face of a
/// distorted hexahedron need not lie in a plane, and the rule depends only on
/// the face's nodes, so the two elements sharing a face split it the same way
/// and the elements tile the body without gaps or overlaps, exactly as the
/// polygons do in 2-D; the body's boundary is then the triangles of its
/// boundary faces. (Inverting the trilinear map by Newton instead would need
/// iterations that can fail outside the element, and the distance to a
/// curved face for the boundary test.) A point is in the closure of an
/// element if the element's surface winds once around it (the solid angles of
/// its triangles sum to 4π; no convexity needed) or it is within kInsideMargin
/// times the element's size (the largest extent of its corners' bounding box)
/// of that surface; it is on the body's boundary if it is within that
/// distance of a triangle of a face that only one element has.
class BodyLocator {
 public:
  /// Relative margin of "inside" (see the class documentation): far above the
  /// round-off of coordinates (~1e-16 relative), far below any overlap a
  /// mesh resolves.
  static constexpr double kInsideMargin = 1e-8;

  /// \param mesh the mesh (must outlive the locator)
  /// \param body body index
  /// \param comm for a part of a mesh (Mesh::isPart()): the ranks holding
  ///        the other parts, so that a face two ranks' elements share is
  ///        not the body's boundary (collective then); unused for a whole
  ///        mesh
  BodyLocator(const Mesh& mesh, int body, MPI_Comm comm = MPI_COMM_SELF);

  /// For a 2-D body: if x is inside the body, an element whose closure
  /// contains x (the lowest index if several do); otherwise −1.
  /// \throws std::invalid_argument if the body is 3-D.
  int elementContaining(const Eigen::Vector2d& x) const;

  /// For a 3-D body: if x is inside the body, an element whose closure
  /// contains x (the lowest index if several do); otherwise −1.
  /// \throws std::invalid_argument if the body is 2-D.
  int elementContaining(const Eigen::Vector3d& x) const;

 private:
  using Triangle = std::array<Eigen::Vector3d, 3>;

  template <class Point>
  int locate(const Point& x) const;
  bool inClosure(int e, const Eigen::Vector2d& x) const;
  bool onBoundaryFacet(int e, int edge, const Eigen::Vector2d& x) const;
  bool inClosure(int e, const Eigen::Vector3d& x) const;
  bool onBoundaryFacet(int e, int face, const Eigen::Vector3d& x) const;
  /// The triangles of corner face `face` of 3-D element e, outward, by the
  /// split rule above; returns their number (1 or 2).
  int faceTriangles(int e, int face, Triangle* triangles) const;
  /// The distance "within the margin" of 3-D element e: kInsideMargin times
  /// its size.
  double margin(int e) const;
  long long cell(double v, double origin, long long n) const;
  /// boundaryFacet_: the facets only one element has, on this part and, on
  /// a part of a mesh, on the other ranks' parts (a directory of facets by
  /// their corners' ids).
  void findBoundaryFacets(MPI_Comm comm);

  const Mesh& mesh_;
  int body_ = 0, dim_ = 2, numFacets_ = 4;
  int firstElement_ = 0, numElements_ = 0;
  double h_ = 1;
  std::array<double, 3> origin_{};                  ///< lower corner of the bin grid
  std::array<long long, 3> n_{{1, 1, 1}};           ///< bins per axis (1 along z in 2-D)
  std::vector<std::pair<long long, int>> bins_;     ///< (cell key, element), sorted
  std::vector<std::array<char, 6>> boundaryFacet_;  ///< per element: facet f is on the body's boundary
  std::vector<std::array<double, 6>> boxes_;        ///< 3-D: per element its corners' box (lower, upper corner)
};

}  // namespace ddc
