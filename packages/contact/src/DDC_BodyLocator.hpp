// Which element of a body contains a point, in the reference configuration:
// the test behind the check that no slave node starts inside a master body
// where contact cannot reach it (doc/contact.md "Which slave nodes pair").
#pragma once

#include <Eigen/Dense>

#include <array>
#include <utility>
#include <vector>

namespace ddc {

class Mesh;

/// Point location in the elements of one body of a replicated mesh, by a
/// uniform grid of bins over the elements' bounding boxes (a query tests the
/// elements of one bin, never all of them).
///
/// An element is taken as the polygon of its corner nodes (nodes 0..3, counter-
/// clockwise; exact for Quad4, the straight-sided approximation for Quad9).
/// A point is *inside the body* if it lies in the closure of one of its
/// elements (to the left of every edge or on it, within kInsideMargin times
/// the edge's length) and not on the body's boundary (within that margin of
/// an edge that only one element has). So a point on a mesh line between two
/// elements is inside, while the nodes of the body's own surfaces and the
/// nodes of a body that merely touches it are not.
class BodyLocator {
 public:
  /// Relative margin of "inside" (see the class documentation): far above the
  /// round-off of coordinates (~1e-16 relative), far below any overlap a
  /// mesh resolves.
  static constexpr double kInsideMargin = 1e-8;

  /// \param mesh the mesh (must outlive the locator)
  /// \param body body index
  BodyLocator(const Mesh& mesh, int body);

  /// If x is inside the body: an element whose closure contains x (the
  /// lowest index if several do); otherwise −1.
  int elementContaining(const Eigen::Vector2d& x) const;

 private:
  bool inClosure(int e, const Eigen::Vector2d& x) const;
  bool onBoundaryEdge(int e, int edge, const Eigen::Vector2d& x) const;
  long long cell(double v, double origin, long long n) const;

  const Mesh& mesh_;
  int firstElement_ = 0, numElements_ = 0;
  double x0_ = 0, y0_ = 0, h_ = 1;
  long long nx_ = 1, ny_ = 1;
  std::vector<std::pair<long long, int>> bins_;  ///< (cell key, element), sorted
  std::vector<std::array<char, 4>> boundaryEdge_;  ///< per element: edge a → a+1 is on the body's boundary
};

}  // namespace ddc
