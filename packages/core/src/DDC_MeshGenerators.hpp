// Built-in structured mesh generators: each adds one body to a ddc::Mesh.
// Rectangle and Annular Sector make 2-D bodies; Box and Cylindrical Shell
// Sector are their 3-D extrusions along z and keep their side names.
//
// Every generator validates its parameter sublist against a static,
// documented getValidParameters() (misspelt names are errors, defaults are
// filled in, each number's range is in its validator) and then checks the
// relations between values, naming the parameter path. A cell type of the
// wrong dimension (Hex8 for a Rectangle, Quad4 for a Box) is an InputError.
//
// Conventions shared by all generators:
//  - elements are positively oriented (counter-clockwise in 2-D, positive
//    Jacobian in 3-D), nodes in Gmsh order (ddc::CellType);
//  - nodes are numbered on a structured grid of points, index 0 fastest
//    (x, or the radius), then 1, then 2; quadratic cell types use the grid
//    with 2 points per element and direction, and Hex20 leaves out the face
//    and cell centres, which are no nodes of it. Nodes on element edges and
//    faces are shared by the neighbours (no duplicates);
//  - 2-D side sets list their segments in the order met when walking the
//    body's boundary counter-clockwise, 3-D side sets their faces in element
//    order; every segment is oriented by Mesh::makeSegment (outward normal);
//  - each side set also defines the node set of the same name
//    (Mesh::addSideSet); node set "all" holds every node of the body;
//  - in 3-D, "back" is the face at the smallest z and "front" the one at the
//    largest (x right, y up, z towards the viewer);
//  - "Refinement" multiplies every element count, so a benchmark deck can be
//    refined from the command line: --set ".../Refinement=2".
//
// Tetrahedra (Tet4, Tet10) split every grid cell into the six tetrahedra of
// the Kuhn (Freudenthal) triangulation along the cell's diagonal from its
// lowest to its highest corner (Bey, BIT 40 (2000) 642-656): every face of
// the grid is cut along the same diagonal from both sides, so the mesh is
// conforming, and every tetrahedron has the volume of its cell over 6.
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

/// Box [Origin X, Origin X + Length X] x [.. Y ..] x [.. Z ..] meshed with
/// (Elements X * Refinement) x (Elements Y * Refinement) x (Elements Z *
/// Refinement) hexahedra (Hex8, Hex20, Hex27) or six times as many
/// tetrahedra (Tet4, Tet10; see the file comment). The 3-D Rectangle: same
/// parameter names plus the Z ones.
///
/// Node counts: Hex8 and Tet4 (nx+1)(ny+1)(nz+1); Hex27 and Tet10
/// (2nx+1)(2ny+1)(2nz+1); Hex20 the vertices plus the edge midpoints,
/// (nx+1)(ny+1)(nz+1) + nx(ny+1)(nz+1) + (nx+1)ny(nz+1) + (nx+1)(ny+1)nz.
///
/// Sets (qualified "<body>/<name>"):
///  - side sets "left" (x = Origin X), "right" (x max), "bottom" (y min),
///    "top" (y max) -- the Rectangle's names -- and "back" (z min), "front"
///    (z max); also node sets;
///  - node sets "all" and the eight corners "bottom left back", "bottom right
///    back", "top left back", ..., "top right front" (one node each).
///
/// "Distortion" d in [0, 0.25] moves every interior vertex of the element
/// grid by a random vector, uniform in the ball of radius d * min(hx, hy, hz),
/// from the same fixed-seed generator as the Rectangle.
/// Why 0.25: at any point of a trilinear cell, column k of the Jacobian is a
/// convex combination of the cell's four edges along direction k, each the
/// undistorted edge h_k e_k plus the difference of two vertex moves, at most
/// 2 d min(h) <= 2 d h_k long. So J = (I + M) diag(h) with every column of M
/// at most 2d long, |M| <= 2 sqrt(3) d < 1 for d < 1/(2 sqrt 3) = 0.289, and
/// det J >= (1 - 2 sqrt(3) d)^3 hx hy hz (0.0024 hx hy hz at d = 0.25): every
/// hexahedron stays valid everywhere, not only at its corners. A Kuhn
/// tetrahedron's determinant det[w1-w0, w2-w1, w3-w2] has columns h_k e_k
/// plus two vertex moves in the same way, so the same bound holds for it.
/// Quadratic nodes are placed on the straight geometry: Hex20/Hex27 nodes on
/// the trilinear map of the distorted corners (the average of the 2, 4 or 8
/// surrounding vertices), Tet10 nodes at the midpoints of straight edges;
/// the isoparametric map then equals the trilinear / affine map of the
/// corners, and the bound above applies to it.
class BoxGenerator {
 public:
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

/// Cylindrical shell sector: the Annular Sector (same parameters) extruded
/// along z from Origin Z over Axial Length, meshed with (Radial Elements *
/// Refinement) x (Circumferential Elements * Refinement) x (Axial Elements *
/// Refinement) hexahedra (Hex8, Hex20, Hex27) or six times as many
/// tetrahedra (Tet4, Tet10). The 3-D half-ring is the default.
///
/// Every node lies on its circle, at the position the Annular Sector gives
/// the same grid point (the two generators share the code): with one axial
/// element (Hex8) or two node layers (Hex27) each layer of the 3-D mesh
/// repeats the 2-D mesh's nodes in the same order. Hex8 cells have straight
/// chords, so their volume is (Circumferential Elements)(1/2) sin(dtheta)
/// (Ro^2 - Ri^2) Axial Length with dtheta the angle per element; Hex27 cells
/// carry the Quad9 arcs and their volume is the Quad9 area times the length.
/// Tetrahedra of a sector with dtheta < 180 degrees are valid: each is
/// spanned by an axial step and two consecutive in-plane steps of a convex
/// quadrilateral.
///
/// Nodes are numbered radial index fastest, then angle (Start -> End), then
/// axial (Origin Z upwards); elements likewise.
///
/// Sets: side sets "inner", "outer", "start", "end" (as the Annular
/// Sector), "back" (z = Origin Z) and "front" (z = Origin Z + Axial Length);
/// also node sets; node set "all".
class CylindricalShellSectorGenerator {
 public:
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
};

/// One eighth of a ball: the part of the ball of radius Radius about (Center
/// X, Center Y, Center Z) with x >= Center X, y >= Center Y and z <= Center Z,
/// i.e. a quarter of a hemisphere with its pole (Center X, Center Y, Center Z
/// - Radius) at the bottom. With the symmetry planes held it models a whole
/// sphere or hemisphere pressed at its pole (Hertz contact,
/// examples/hertz_sphere.xml) at a quarter of the cost.
///
/// The grid is the cube [0,1] x [0,1] x [-1,0] with (Elements * Refinement)
/// cells per direction, graded towards the pole corner (0, 0, -1) by
/// "Progression" (geometric cell sizes), mapped to the ball by
/// p -> p (1 - m + m^2/|p|) with m = |p|_inf: each cube shell m = const
/// onto a surface between that cube (centre) and the sphere of radius m
/// (outside), so the outer cube faces (m = 1) go onto the sphere by radial
/// projection and the planes a = 0, b = 0, w = 0 stay in place. Along a ray
/// p = t q (|q|_inf = 1) the radius grows as t (1 - t + t/|q|), with
/// derivative 2/|q| - 1 >= 2/sqrt 3 - 1 > 0 at the surface: unlike the
/// spherified-cube map x = a sqrt(1 - b^2/2 - w^2/2 + b^2 w^2/3), whose
/// Jacobian is singular at the cube's corners (inverted Hex8 cells there on
/// graded meshes), no cell degenerates. The map is the identity along the
/// axis through the pole, where the cells are near cubes.
/// Every node (quadratic ones too) is mapped, so the surface nodes lie on the
/// sphere. Hexahedra (Hex8, Hex20, Hex27) or Kuhn tetrahedra (Tet4, Tet10).
///
/// Nodes are numbered in grid order (x-like index fastest, from the pole
/// upwards in the last index).
///
/// Sets: side sets "sphere" (the curved surface: the three outer cube faces),
/// "symmetry x" (on the plane x = Center X), "symmetry y" (y = Center Y) and
/// "top" (the flat face on z = Center Z), also node sets; node sets "pole"
/// (one node) and "all".
class SphereOctantGenerator {
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

/// A half-open range [first, last) of element ids of a whole mesh.
struct ElementRange {
  long long first = 0, last = 0;
};

/// generateRectangle() making only the body's elements whose ids in the
/// whole mesh lie in `range` (the body's ids follow those of the bodies
/// before it, part.numGlobalElements() of them) and their nodes, into the
/// part `part` (Mesh::startPart()): the mesh Mesh::part() would cut out of
/// the whole mesh, without the whole mesh, its grid points or the
/// displacements of other vertices (doc/architecture.md, "What a
/// distributed mesh has to change"). The body is added even if the range
/// holds none of its elements.
int generateRectangle(Mesh& part, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                      const std::string& path, const ElementRange& range);

/// Whether `generator` (a body's Generator) can make a body by element
/// range: Rectangle, Box, Annular Sector, Cylindrical Shell Sector, Sphere
/// Octant.
bool generatesByRange(const std::string& generator);

/// The number of elements the generator `generator` (generatesByRange())
/// makes of a body, from its parameters (validated and checked as the
/// generator checks them), without making any: what an even range of
/// element ids over several bodies needs first.
long long structuredElementCount(const std::string& generator, CellType type, Teuchos::ParameterList& params,
                                 const std::string& path);

/// Add an annular-sector body named `bodyName` to `mesh`.
/// \param params validated against AnnularSectorGenerator::getValidParameters().
/// \return the index of the new body.
/// \throws InputError naming the path for unknown parameters, radii not
///         satisfying 0 < Inner < Outer, |End - Start| not in (0, 360),
///         non-positive element counts or refinement.
int generateAnnularSector(Mesh& mesh, const std::string& bodyName, CellType type,
                          Teuchos::ParameterList& params, const std::string& path);

/// generateAnnularSector() by element range, as generateRectangle() by range.
int generateAnnularSector(Mesh& part, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                          const std::string& path, const ElementRange& range);

/// Add a box body named `bodyName` to `mesh`.
/// \param type Hex8, Hex20, Hex27, Tet4 or Tet10.
/// \param params validated against BoxGenerator::getValidParameters().
/// \return the index of the new body.
/// \throws InputError naming the path for unknown parameters, values out of
///         range (Distortion outside [0, 0.25]), a 2-D cell type, or a
///         duplicate body name.
int generateBox(Mesh& mesh, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                const std::string& path);

/// generateBox() by element range, as generateRectangle() by range.
int generateBox(Mesh& part, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                const std::string& path, const ElementRange& range);

/// Add a cylindrical-shell-sector body named `bodyName` to `mesh`.
/// \param type Hex8, Hex20, Hex27, Tet4 or Tet10.
/// \param params validated against
///        CylindricalShellSectorGenerator::getValidParameters().
/// \return the index of the new body.
/// \throws InputError as generateAnnularSector(), and for a non-positive
///         Axial Length / Axial Elements or a 2-D cell type.
int generateCylindricalShellSector(Mesh& mesh, const std::string& bodyName, CellType type,
                                   Teuchos::ParameterList& params, const std::string& path);

/// generateCylindricalShellSector() by element range, as generateRectangle()
/// by range.
int generateCylindricalShellSector(Mesh& part, const std::string& bodyName, CellType type,
                                   Teuchos::ParameterList& params, const std::string& path,
                                   const ElementRange& range);

/// Add a sphere-octant body named `bodyName` to `mesh`.
/// \param type Hex8, Hex20, Hex27, Tet4 or Tet10.
/// \param params validated against SphereOctantGenerator::getValidParameters().
/// \return the index of the new body.
/// \throws InputError naming the path for unknown parameters, values out of
///         range (Progression outside [1, 2]) or a 2-D cell type.
int generateSphereOctant(Mesh& mesh, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                         const std::string& path);

/// generateSphereOctant() by element range, as generateRectangle() by range.
int generateSphereOctant(Mesh& part, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                         const std::string& path, const ElementRange& range);

}  // namespace ddc
