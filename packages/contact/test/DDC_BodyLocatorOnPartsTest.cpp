// BodyLocator on parts of a mesh (Mesh::part()): each rank locates points in
// the elements it holds, and a face that two ranks' elements share is no
// boundary of the body, so the ranks together find what the locator on the
// whole mesh finds: a point on such a face (or edge, or node) is inside, in
// the lowest element id containing it, and points on the body's own
// boundary and outside are in none. 2 x 1 x 1 boxes of 4 x 2 x 2 cells of
// Hex8 and Tet4, cut into slabs along x, one per rank (1-3 ranks).
#include <gtest/gtest.h>

#include <Teuchos_ParameterList.hpp>
#include <mpi.h>

#include <algorithm>
#include <limits>
#include <vector>

#include "DDC_BodyLocator.hpp"
#include "DDC_Mesh.hpp"
#include "DDC_MeshGenerators.hpp"

namespace {

using Vec3 = Eigen::Vector3d;

/// Points this far from the boundary are clearly on one side of it (100
/// times BodyLocator::kInsideMargin).
constexpr double kClearlyOff = 1e-6;

ddc::Mesh box(ddc::CellType type) {
  ddc::Mesh m;
  Teuchos::ParameterList p("Box");
  p.set("Length X", 2.0);
  p.set("Elements X", 4);
  p.set("Elements Y", 2);
  p.set("Elements Z", 2);
  ddc::generateBox(m, "B", type, p, "Box");
  return m;
}

/// This rank's slab: the elements whose corners' mean x lies in its share
/// of [0, 2].
ddc::Mesh slab(const ddc::Mesh& whole, int rank, int ranks) {
  std::vector<int> mine;
  for (int e = 0; e < whole.numElements(); ++e) {
    double x = 0.0;
    const int corners = ddc::referenceCell(whole.elementType(e)).numCorners;
    for (int i = 0; i < corners; ++i) x += whole.coord(whole.elementNodes(e)[i])[0] / corners;
    if (std::min(int(x / 2.0 * ranks), ranks - 1) == rank) mine.push_back(e);
  }
  return whole.part(mine);
}

TEST(BodyLocatorOnParts, TheRanksTogetherFindWhatTheWholeMeshFinds) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  // On the cut planes x = 2/3, 1 and 4/3 (faces, edges and nodes between
  // slabs for 2 and 3 ranks, between cells or inside cells), inside cells,
  // on the body's faces, and outside.
  std::vector<Vec3> points;
  for (double x : {2.0 / 3.0, 1.0, 4.0 / 3.0, 0.3, 1.7})
    for (double y : {0.2, 0.5, 0.7})
      for (double z : {0.25, 0.5, 0.9}) points.emplace_back(x, y, z);
  for (const Vec3& x : {Vec3(0.0, 0.5, 0.5), Vec3(2.0, 0.3, 0.3), Vec3(1.0, 0.0, 0.5), Vec3(1.0, 0.5, 1.0),
                        Vec3(1.0, 1.0, 1.0), Vec3(2.0 + kClearlyOff, 0.5, 0.5), Vec3(1.0, -kClearlyOff, 0.5)})
    points.push_back(x);
  for (ddc::CellType type : {ddc::CellType::Hex8, ddc::CellType::Tet4}) {
    const ddc::Mesh whole = box(type);
    const ddc::Mesh part = slab(whole, rank, ranks);
    const ddc::BodyLocator onWhole(whole, 0), onPart(part, 0, MPI_COMM_WORLD);
    int inside = 0;
    for (const Vec3& x : points) {
      const int expected = onWhole.elementContaining(x);
      inside += expected >= 0;
      const int e = onPart.elementContaining(x);
      long long found = e >= 0 ? part.elementId(e) : std::numeric_limits<long long>::max();
      MPI_Allreduce(MPI_IN_PLACE, &found, 1, MPI_LONG_LONG, MPI_MIN, MPI_COMM_WORLD);
      EXPECT_EQ(found == std::numeric_limits<long long>::max() ? -1 : found, expected)
          << ddc::cellTypeName(type) << " (" << x.transpose() << ") on " << ranks << " ranks";
    }
    EXPECT_EQ(inside, 45) << ddc::cellTypeName(type);  // the 5 x 3 x 3 points off the body's faces
  }
}

}  // namespace
