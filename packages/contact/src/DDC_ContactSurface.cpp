// Contact surfaces from side sets (see DDC_ContactSurface.hpp for the facet
// types and the depth rule).
#include "DDC_ContactSurface.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <sstream>

#include "DDC_Error.hpp"
#include "DDC_Mesh.hpp"
#include "DDC_ShapeFunctions.hpp"

namespace ddc {

namespace {

Eigen::Vector3d position(const Mesh& mesh, int node) {
  const auto& x = mesh.coord(node);
  return Eigen::Vector3d(x[0], x[1], x[2]);
}

/// max_a −n·(X_a − X_c) over the nodes of element `e`, with X_c the centre
/// point of the facet `nodes` of type `type` and n its unit outward normal
/// there (header); 0 if the facet has no normal there (zero tangent or area).
double depthBehindCentre(const Mesh& mesh, CellType type, const std::vector<int>& nodes, int e) {
  const ReferenceCell& facet = referenceCell(type);
  std::array<double, 3> xi{{0.0, 0.0, 0.0}};
  for (int c = 0; c < facet.numCorners; ++c)
    for (int k = 0; k < 3; ++k) xi[k] += facet.nodes[c][k] / facet.numCorners;
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  shapeFunctions(type, xi, &N, &dN);
  Eigen::Vector3d xc = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, 2> a = Eigen::Matrix<double, 3, 2>::Zero();
  for (int i = 0; i < facet.numNodes; ++i) {
    const Eigen::Vector3d x = position(mesh, nodes[i]);
    xc += N[i] * x;
    for (int al = 0; al < facet.dim; ++al) a.col(al) += dN(i, al) * x;
  }
  const Eigen::Vector3d normal =
      facet.dim == 1 ? Eigen::Vector3d(a(1, 0), -a(0, 0), 0.0) : Eigen::Vector3d(a.col(0).cross(a.col(1)));
  const double length = normal.norm();
  if (!(length > 0.0)) return 0.0;
  const Eigen::Vector3d n = normal / length;
  double depth = 0.0;
  for (int i = 0; i < mesh.elementNumNodes(e); ++i)
    depth = std::max(depth, -n.dot(position(mesh, mesh.elementNodes(e)[i]) - xc));
  return depth;
}

/// Line2 facets: max_a −n·(X_a − X_1) with n = (t_y, −t_x)/|t|, t = X_2 −
/// X_1 (header), in the arithmetic of the closed-form straight-segment search
/// (packages/contact/test), whose depths these equal bit for bit.
std::vector<double> line2Depths(const Mesh& mesh, const std::vector<Segment>& sides, const std::string& sideSet) {
  std::vector<double> depth(sides.size(), 0.0);
  for (std::size_t k = 0; k < sides.size(); ++k) {
    const auto& a = mesh.coord(sides[k].nodes[0]);
    const auto& b = mesh.coord(sides[k].nodes[1]);
    const Eigen::Vector2d t(b[0] - a[0], b[1] - a[1]);
    const Eigen::Vector2d n = Eigen::Vector2d(t.y(), -t.x()).normalized();
    const int e = sides[k].element;
    for (int i = 0; i < mesh.elementNumNodes(e); ++i) {
      const auto& x = mesh.coord(mesh.elementNodes(e)[i]);
      depth[k] = std::max(depth[k], -n.dot(Eigen::Vector2d(x[0] - a[0], x[1] - a[1])));
    }
    DDC_INPUT_REQUIRE(depth[k] > 0.0, "side set '" << sideSet << "': element " << e
                                                   << " has no extent behind its side " << sides[k].localSide
                                                   << " (degenerate element)");
  }
  return depth;
}

}  // namespace

CellType contactFacetType(int dim, int numNodes, const std::string& sideSet) {
  if (dim == 2 && numNodes == 2) return CellType::Line2;
  if (dim == 2 && numNodes == 3) return CellType::Line3;
  if (dim == 3) {
    switch (numNodes) {
      case 3:
        return CellType::Tri3;
      case 6:
        return CellType::Tri6;
      case 4:
        return CellType::Quad4;
      case 8:
        return CellType::Quad8;
      case 9:
        return CellType::Quad9;
      default:
        break;
    }
  }
  DDC_THROW(InputError, "side set '" << sideSet << "': a facet with " << numNodes << " nodes is no facet of a " << dim
                                     << "-D element (2-D: 2 or 3 nodes; 3-D: 3, 4, 6, 8 or 9)");
}

ContactSurfaceFacets contactSurfaceFromSideSet(const Mesh& mesh, const std::string& sideSet) {
  const std::vector<Segment>& sides = mesh.sideSet(sideSet);  // checks that it exists
  ContactSurfaceFacets out;
  if (sides.empty()) return out;
  out.type = contactFacetType(mesh.dim(), sides[0].numNodes, sideSet);
  const char* facetWord = mesh.dim() == 2 ? "side" : "face";
  for (const Segment& s : sides) {
    const CellType type = contactFacetType(mesh.dim(), s.numNodes, sideSet);
    DDC_INPUT_REQUIRE(type == out.type, "side set '" << sideSet << "': " << facetWord << " " << s.localSide
                                                     << " of element " << s.element << " is a " << cellTypeName(type)
                                                     << " facet, the first one a " << cellTypeName(out.type)
                                                     << "; a contact surface has facets of one type");
    out.nodes.emplace_back(s.nodes.begin(), s.nodes.begin() + s.numNodes);
    out.elements.push_back(s.element);
    out.sides.push_back(s.localSide);
  }
  if (out.type == CellType::Line2) {
    out.depths = line2Depths(mesh, sides, sideSet);
    return out;
  }
  for (std::size_t k = 0; k < sides.size(); ++k) {
    out.depths.push_back(depthBehindCentre(mesh, out.type, out.nodes[k], out.elements[k]));
    DDC_INPUT_REQUIRE(out.depths[k] > 0.0, "side set '" << sideSet << "': element " << out.elements[k]
                                                        << " has no extent behind its " << facetWord << " "
                                                        << sides[k].localSide << " (degenerate element)");
  }
  return out;
}

}  // namespace ddc
