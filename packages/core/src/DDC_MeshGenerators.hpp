// Built-in structured mesh generators: each adds one body to a ddc::Mesh.
//
// Both generators validate their parameter sublist against a static,
// documented getValidParameters() (misspelt names are errors, defaults are
// filled in) and then check value ranges, naming the parameter path.
//
// Conventions shared by both generators:
//  - elements are counter-clockwise (positive Jacobian), nodes in Gmsh order
//    (ddc::CellType);
//  - each side set lists its segments in the order met when walking the
//    body's boundary counter-clockwise, and every segment is oriented by
//    Mesh::makeSegment (body on the left, outward normal (dy, -dx)/|.|);
//  - each side set also defines the node set of the same name
//    (Mesh::addSideSet); node set "all" holds every node of the body;
//  - "Refinement" multiplies both element counts, so a benchmark deck can be
//    refined from the command line: --set ".../Refinement=2".
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>
#include <string>

#include "DDC_Mesh.hpp"

namespace ddc {

/// Rectangle [Origin X, Origin X + Length X] x [Origin Y, Origin Y + Length Y]
/// meshed with (Elements X * Refinement) x (Elements Y * Refinement) quads.
///
/// Node numbering is row-major on the node grid (x fastest), elements
/// row-major. Quad4: (nx+1)(ny+1) nodes; Quad9: (2nx+1)(2ny+1) nodes.
///
/// Sets (qualified "<body>/<name>"):
///  - side sets "bottom", "right", "top", "left" (also node sets);
///  - node sets "all", "bottom left", "bottom right", "top left", "top right"
///    (one node each).
///
/// "Distortion" d in [0, 0.3] moves every interior vertex of the element grid
/// (corner nodes not on the boundary) by a random vector of length
/// <= d * min(hx, hy) (hx, hy element sizes), drawn from a fixed-seed
/// Mersenne twister, so the mesh is the same on every rank and every run.
/// Why 0.3: a corner of an hx x hy cell is at least min(hx, hy)/sqrt(2) from
/// the diagonal through its two neighbours; moving the neighbours by
/// d*min(hx, hy) tilts that line by at most asin(d sqrt 2) (25 degrees) and
/// shifts it by d*min(hx, hy), so the corner keeps a distance of at least
/// (0.707 cos 25deg - 2 d) min(hx, hy) > 0.04 min(hx, hy): every element
/// stays strictly convex.
/// Quad9 mid-side nodes are placed at the midpoints of the (straight) edges
/// and the centre node at the average of the four corners, i.e. the Quad9
/// geometry equals the bilinear map of the distorted Quad4: a patch test on
/// the distorted mesh is then exact for both cell types.
class RectangleGenerator {
 public:
  /// Every parameter with its default and a doc string.
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
};

/// Annular sector (a ring segment; a half-ring is Start Angle 0, End Angle
/// 180) centred at (Center X, Center Y) between radii Inner Radius < Outer
/// Radius, meshed with (Radial Elements * Refinement) x (Circumferential
/// Elements * Refinement) quads.
///
/// Angles are in degrees, measured counter-clockwise from the +x axis. End
/// Angle may be smaller than Start Angle (the sector is then swept clockwise
/// from Start to End); |End - Start| must lie in (0, 360) -- a closed ring
/// would need its seam nodes merged and is not supported. Elements are
/// counter-clockwise in either case.
///
/// Every node lies exactly on its circle r = const (Quad9 mid-side and centre
/// nodes too: they sit at the mid angle and, on radial edges, at the mid
/// radius), so a Quad9 mesh represents the arcs to O(h^3) and its area
/// converges quickly to (pi |End-Start|/360)(Ro^2 - Ri^2).
///
/// Nodes are numbered with the radial index fastest, then the angle index
/// from Start to End; elements likewise.
///
/// Sets: side sets "inner", "outer", "start" (the radial edge at Start
/// Angle), "end" (at End Angle), also node sets; node set "all".
class AnnularSectorGenerator {
 public:
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
};

/// Add a rectangle body named `bodyName` to `mesh`.
/// \param params the generator's sublist; validated (this level) against
///        RectangleGenerator::getValidParameters(), defaults filled in.
/// \param path parameter path of `params` for messages, e.g.
///        "Mesh/Bodies/Block/Rectangle".
/// \return the index of the new body.
/// \throws InputError naming the path for unknown parameters, non-positive
///         lengths / element counts / refinement, Distortion outside [0, 0.3],
///         or a duplicate body name.
int generateRectangle(Mesh& mesh, const std::string& bodyName, CellType type,
                      Teuchos::ParameterList& params, const std::string& path);

/// Add an annular-sector body named `bodyName` to `mesh`.
/// \param params validated against AnnularSectorGenerator::getValidParameters().
/// \return the index of the new body.
/// \throws InputError naming the path for unknown parameters, radii not
///         satisfying 0 < Inner < Outer, |End - Start| not in (0, 360),
///         non-positive element counts or refinement.
int generateAnnularSector(Mesh& mesh, const std::string& bodyName, CellType type,
                          Teuchos::ParameterList& params, const std::string& path);

}  // namespace ddc
