// Contact surfaces of every facet type read from mesh side sets: the facets,
// the element behind each and that element's depth (doc/contact.md, "Curved
// facets and 3-D" and "Which slave nodes pair").
//
//   facet type    from the side set's Segment::numNodes and the mesh
//                 dimension (contactFacetType()): 2-D Line2 (Quad4 sides),
//                 Line3 (Quad9 sides); 3-D Tri3, Tri6, Quad4, Quad8, Quad9
//                 (faces of Tet4, Tet10, Hex8, Hex20, Hex27). The facet nodes
//                 are the Segment's, which DDC_Mesh.hpp lists in the facet
//                 type's node order of DDC_ReferenceCell.hpp (a Quad9 side:
//                 start, end, middle = Line3 ξ = −1, 1, 0) with outward
//                 orientation.
//   depth         how far the element's nodes reach behind the facet along
//                 its inward normal, in the reference configuration:
//                   Line2   max_a −n·(X_a − X_1), n = (t_y, −t_x)/|t|,
//                           t = X_2 − X_1: bit-identical to the closed-form
//                           2-D straight-segment search (a test reference);
//                   others  max_a −n·(X_a − X_c), X_c = x(ξ_c) the facet's
//                           centre point (ξ_c the mean of the reference
//                           facet's corners: 0 on a line, (0, 0) on a
//                           quadrilateral, (⅓, ⅓) on a triangle) and n the
//                           unit outward normal there, a_1 × a_2/|a_1 × a_2|
//                           in 3-D and (a_y, −a_x)/|a| in 2-D (Line3), with
//                           x(ξ) = Σ N_i(ξ) X_i and a_α = ∂x/∂ξ_α
//                           (DDC_ShapeFunctions.hpp, DDC_NodeToSurface.hpp).
//                 For a rectangular or box-shaped element: its size normal
//                 to the facet. The facing rule lets a slave lie at most
//                 kFacingDepthFraction of it behind the facet.
#pragma once

#include <string>
#include <vector>

#include "DDC_ReferenceCell.hpp"

namespace ddc {

class Mesh;

/// A contact surface read from a side set: its facets, oriented outward (DDC_Mesh.hpp Segment).
struct ContactSurfaceFacets {
  CellType type = CellType::Line2;      ///< facet cell type, one per side set
  std::vector<std::vector<int>> nodes;  ///< per facet: mesh node ids in the facet type's node order
  std::vector<int> elements;            ///< per facet: the element it is a facet of
  std::vector<int> sides;               ///< per facet: its local side (facet) number in that element
  std::vector<double> depths;           ///< per facet: extent of that element behind the facet (> 0)
};

/// The facet cell type of a side set's facets with `numNodes` nodes in a mesh
/// of dimension `dim`: 2-D 2 → Line2, 3 → Line3; 3-D 3 → Tri3, 6 → Tri6,
/// 4 → Quad4, 8 → Quad8, 9 → Quad9.
/// \throws InputError naming `sideSet` for any other combination.
CellType contactFacetType(int dim, int numNodes, const std::string& sideSet);

/// The facets of side set `sideSet` in the side set's order, with their
/// elements and depths (see the top of this file). An empty side set gives no
/// facets.
/// \throws InputError if the side set does not exist (listing the known ones,
///         as Mesh::sideSet()), its facets are not all of one
///         facet type of the mesh's dimension, or an element has no extent
///         behind its facet (degenerate element).
ContactSurfaceFacets contactSurfaceFromSideSet(const Mesh& mesh, const std::string& sideSet);

}  // namespace ddc
