// Reference cells: for every cell type its nodes (Gmsh order), edges and
// facets with outward orientation. Everything that walks the sides of an
// element (side sets, partition boundaries, contact surfaces, output) reads
// them here instead of enumerating corners by hand (as deal.II's
// ReferenceCell and MFEM's Geometry do).
//
// Node order is Gmsh's (gmsh.info, "Node ordering"): corners first, then one
// node per edge in the order of edges() below, then (Quad9, Hex27) face and
// cell centres.
//   Quad4/Quad9   [-1,1]^2, corners counter-clockwise; Quad9 mid-sides
//                 4:(0-1) 5:(1-2) 6:(2-3) 7:(3-0), centre 8.
//   Hex8/20/27    [-1,1]^3, corners 0..3 on z = -1 counter-clockwise seen
//                 from +z, 4..7 above them; Hex20 edges 8:(0-1) 9:(0-3)
//                 10:(0-4) 11:(1-2) 12:(1-5) 13:(2-3) 14:(2-6) 15:(3-7)
//                 16:(4-5) 17:(4-7) 18:(5-6) 19:(6-7); Hex27 face centres
//                 20:(z=-1) 21:(y=-1) 22:(x=-1) 23:(x=+1) 24:(y=+1)
//                 25:(z=+1), cell centre 26.
//   Tet4/Tet10    corners (0,0,0) (1,0,0) (0,1,0) (0,0,1); Tet10 edges
//                 4:(0-1) 5:(1-2) 6:(2-0) 7:(3-0) 8:(3-2) 9:(3-1).
//   Facet cells   Line2/Line3 (ends, then middle), Tri3/Tri6 (corners, then
//                 3:(0-1) 4:(1-2) 5:(2-0)), Quad8 (Quad9 without its centre).
//
// Facet orientation: a facet lists its nodes in the facet cell's own order
// such that its parametrisation has an outward normal. In 2-D a side runs
// with the body on its left, outward normal (dy, -dx)/|.|; in 3-D the facet
// corners run counter-clockwise seen from outside, outward normal
// (x_1 - x_0) x (x_{last} - x_0) direction.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace ddc {

/// Cell types. Quad4..Tet10 are element (volume) cells; Line2..Quad8 are
/// the facets of element cells.
enum class CellType { Quad4, Quad9, Hex8, Hex20, Hex27, Tet4, Tet10, Line2, Line3, Tri3, Tri6, Quad8 };

/// One facet of a cell: its cell type and its nodes, as local node numbers
/// of the cell, in the facet type's node order with outward orientation.
struct ReferenceFacet {
  CellType type;
  std::vector<int> nodes;
};

/// One edge of a cell: its two end corners and, for quadratic cells, the
/// local node in its middle (-1 for linear cells).
struct ReferenceEdge {
  int start, end, middle;
};

/// The description of one cell type; obtain it with referenceCell().
struct ReferenceCell {
  CellType type;
  const char* name;           ///< "Quad4", "Hex20", ...
  int dim;                    ///< 1, 2 or 3
  int numNodes;
  int numCorners;             ///< vertices (the linear sub-cell)
  bool simplex;               ///< triangle/tetrahedron rather than quad/hex
  /// Reference coordinates of the nodes (unused components are 0).
  std::vector<std::array<double, 3>> nodes;
  std::vector<ReferenceEdge> edges;
  /// Facets (sides of 2-D cells, faces of 3-D cells); empty for Line cells.
  std::vector<ReferenceFacet> facets;
  /// VTK cell type id and the permutation vtk[i] = gmsh[vtkOrder[i]].
  int vtkType;
  std::vector<int> vtkOrder;
};

/// The reference cell of a type (a static table; never fails).
const ReferenceCell& referenceCell(CellType t);

/// Number of nodes of a cell type.
int numCellNodes(CellType t);
/// Human-readable name ("Quad4", "Hex20", ...).
const char* cellTypeName(CellType t);
/// Dimension of the cell (1 for lines, 2 for triangles/quadrilaterals, 3).
int cellDimension(CellType t);
/// The element cell types (those a body can be made of), in enum order.
const std::vector<CellType>& elementCellTypes();

/// Verdict of cornerJacobian() on one cell.
struct CornerJacobian {
  enum class Verdict { Valid, Inverted, Degenerate };
  Verdict verdict = Verdict::Valid;
  /// The smallest determinant found (the most negative one if inverted).
  double det = 0.0;
  /// Where it was found: a corner (local node number), or -1 for the centre
  /// (and for simplices, whose corner map has one constant Jacobian).
  int where = -1;
  /// The threshold below which |det| counts as zero: 1e-12 h^dim, h the
  /// largest distance between two corners.
  double tolerance = 0.0;
};

/// \brief Is the cell's corner geometry valid, inverted or degenerate?
///
/// Evaluates the Jacobian determinant of the map from the reference cell
/// spanned by the corners alone -- affine for triangles and tetrahedra,
/// bilinear / trilinear for quadrilaterals and hexahedra -- at every corner
/// and at the centre. For a multilinear cell each column of J at a corner is
/// a pair of that corner's edges, so a negative value there means the corner
/// is folded over, and the centre catches a cell turned inside out as a
/// whole. The verdict is Inverted if some det < -tolerance, else Degenerate
/// if some det <= tolerance (coincident corners, a flat cell, an edge angle
/// of 180 degrees), else Valid.
///
/// Mid-edge, face and centre nodes of quadratic cells are not looked at: a
/// cell whose corners pass can still be inverted by a misplaced middle node,
/// which the elements' own isoparametric Jacobian check has to catch.
/// \param t an element or facet cell type of dimension dim = cellDimension(t)
///        equal to the number of coordinates used (2: x, y; 3: x, y, z).
/// \param corners numCorners coordinates in the cell's node order.
CornerJacobian cornerJacobian(CellType t, const std::array<double, 3>* corners);

/// What is wrong with a cell that cornerJacobian() did not find Valid, for
/// messages: "inverted (det J = -0.125 at corner 3 of the corner map; ...)"
/// followed by the expected corner order of type `t`.
std::string describeCornerJacobian(CellType t, const CornerJacobian& j);

}  // namespace ddc
