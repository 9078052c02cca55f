#!/usr/bin/env python3
"""mindlin_sphere_mesh.py [OUT.msh]: the Gmsh mesh of examples/mindlin_sphere.xml.

Half of a sphere of radius R = 1 (centre (0, 0, R)) touching a block at the
origin, the symmetry plane y = 0 (doc/contact.md, "Mindlin"). Both bodies
are structured Hex8 meshes, a tensor grid in x and y graded towards the
contact point, so the contact zone (radius a ~ 0.1 R) is resolved by
uniform elements of size H0 and the rest of each body is coarse:

  - x: uniform spacing H0 for |x| <= X_UNIFORM, then growing by RATIO per
    element out to |x| = W_SPHERE (the sphere, a node at x = 0) and W_BLOCK
    (the block); y the same on 0 <= y;
  - the sphere is the part below z = CAP of the column |x|, y <= W_SPHERE
    under the sphere (its lower face on the sphere z = R - sqrt(R^2 - x^2 -
    y^2), its flat top loaded), each column split like the centre one:
    layers of H0 up to height D_UNIFORM above the sphere, then growing by
    RATIO;
  - the block is [-W_BLOCK, W_BLOCK] x [0, W_BLOCK] x [-DEPTH, 0], layers of
    H0 below its top down to D_UNIFORM, then growing by RATIO. Its nodes lie
    half an element beside the sphere's in x and y (its first row in y is
    half an element wide), so no slave node starts on a master edge (where
    its projection would jump between two facets).

Physical groups: volumes "sphere", "block"; surfaces "surface" (the
sphere's lower face, the slave side), "load" (its top), "symmetry" (the
faces on y = 0 of either body), "top" (the block's top, the master side),
"bottom" (its base). Written as MSH 4.1 ASCII (packages/io/src/DDC_Gmsh.hpp).
Plain Python, no Gmsh needed:
    python3 examples/mindlin_sphere_mesh.py examples/mindlin_sphere.msh
"""
import math
import sys

R = 1.0
H0 = 0.0125         # element size in the contact zone (a ~ 0.1 R: 8 elements across the radius)
X_UNIFORM = 0.125   # extent of the uniform zone (> a)
D_UNIFORM = 0.025   # height / depth of the uniform layers
RATIO = 1.5         # growth of the element size outside
W_SPHERE = 0.5      # half-width of the sphere's column
CAP = 0.5           # height of its flat top
W_BLOCK = 1.0       # half-width of the block
DEPTH = 1.0         # depth of the block


def graded(length, uniform, start=0.0):
    """Points start = t_0 < t_1 < ... < t_n = length: intervals of H0 up to
    `uniform`, then each RATIO times the one before; the last interval
    takes the remainder (merged into the one before if under half of it)."""
    t, h = [start], H0
    while t[-1] + h < length - 1e-12:
        t.append(t[-1] + h)
        if t[-1] >= uniform - 1e-12:
            h *= RATIO
    if len(t) > 1 and length - t[-1] < 0.5 * (t[-1] - t[-2]):
        t.pop()
    t.append(length)
    return t


def symmetric(half):
    """-half .. half mirrored about 0 (half[0] = 0: one point at 0)."""
    return [-x for x in reversed(half[1:] if half[0] == 0.0 else half)] + half


class Grid:
    """A structured grid of nodes (x_i, y_j, z_ijk), k the layer index;
    hexahedra positively oriented, faces by their four corners."""

    def __init__(self, xs, ys, zs_of_column):
        self.nx, self.ny = len(xs), len(ys)
        self.nodes = []
        for i, x in enumerate(xs):
            for j, y in enumerate(ys):
                zs = zs_of_column(x, y)
                self.nz = len(zs)
                self.nodes += [(x, y, z) for z in zs]

    def index(self, i, j, k):
        return (i * self.ny + j) * self.nz + k

    def hexes(self):
        n = self.index
        return [(n(i, j, k), n(i + 1, j, k), n(i + 1, j + 1, k), n(i, j + 1, k),
                 n(i, j, k + 1), n(i + 1, j, k + 1), n(i + 1, j + 1, k + 1), n(i, j + 1, k + 1))
                for i in range(self.nx - 1) for j in range(self.ny - 1) for k in range(self.nz - 1)]

    def layer(self, k):
        """The faces of layer k (bottom 0, top nz - 1)."""
        n = self.index
        return [(n(i, j, k), n(i + 1, j, k), n(i + 1, j + 1, k), n(i, j + 1, k))
                for i in range(self.nx - 1) for j in range(self.ny - 1)]

    def front(self):
        """The faces on y = ys[0]."""
        n = self.index
        return [(n(i, 0, k), n(i + 1, 0, k), n(i + 1, 0, k + 1), n(i, 0, k + 1))
                for i in range(self.nx - 1) for k in range(self.nz - 1)]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "mindlin_sphere.msh"
    # Sphere's column.
    ws = graded(W_SPHERE, X_UNIFORM)
    fractions = [d / CAP for d in graded(CAP, D_UNIFORM)]

    def sphere_column(x, y):
        zb = R - math.sqrt(R * R - x * x - y * y)
        return [zb + f * (CAP - zb) for f in fractions]

    sphere = Grid(symmetric(ws), ws, sphere_column)
    # Block: nodes half an element beside the sphere's (module comment).
    wb = graded(W_BLOCK, X_UNIFORM, start=0.5 * H0)
    layers = [-d for d in reversed(graded(DEPTH, D_UNIFORM))]
    block = Grid(symmetric(wb), [0.0] + wb, lambda x, y: layers)

    off = len(sphere.nodes)  # block node indices follow the sphere's
    tag = lambda k: k + 1  # node tags from 1
    names = ["surface", "load", "symmetry", "top", "bottom", "sphere", "block"]
    # Surface entities: (entity, physical, faces, node offset); volumes likewise.
    surfaces = [(1, 1, sphere.layer(0), 0), (2, 2, sphere.layer(sphere.nz - 1), 0), (3, 3, sphere.front(), 0),
                (4, 4, block.layer(block.nz - 1), off), (5, 5, block.layer(0), off), (6, 3, block.front(), off)]
    volumes = [(1, 6, sphere.hexes(), 0), (2, 7, block.hexes(), off)]
    with open(out, "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
        f.write(f"$PhysicalNames\n{len(names)}\n")
        f.write("".join(f'{2 if p <= 5 else 3} {p} "{name}"\n' for p, name in enumerate(names, 1)))
        f.write("$EndPhysicalNames\n")
        f.write(f"$Entities\n0 0 {len(surfaces)} {len(volumes)}\n")
        box = f"{-W_BLOCK} 0 {-DEPTH} {W_BLOCK} {W_BLOCK} {CAP}"
        for entity, physical, _, _ in surfaces:
            f.write(f"{entity} {box} 1 {physical} 0\n")
        f.write(f"1 {box} 1 6 3 1 2 3\n2 {box} 1 7 3 4 5 6\n")
        f.write("$EndEntities\n")
        n = len(sphere.nodes) + len(block.nodes)
        f.write(f"$Nodes\n2 {n} 1 {n}\n")
        for volume, nodes, first in ((1, sphere.nodes, 0), (2, block.nodes, off)):
            f.write(f"3 {volume} 0 {len(nodes)}\n")
            f.write("".join(f"{tag(first + k)}\n" for k in range(len(nodes))))
            f.write("".join(f"{x:.12g} {y:.12g} {z:.12g}\n" for x, y, z in nodes))
        f.write("$EndNodes\n")
        blocks = [(2, e, 3, cells, first) for e, _, cells, first in surfaces] + \
                 [(3, e, 5, cells, first) for e, _, cells, first in volumes]
        m = sum(len(b[3]) for b in blocks)
        f.write(f"$Elements\n{len(blocks)} {m} 1 {m}\n")
        e = 1
        for dim, entity, kind, cells, first in blocks:
            f.write(f"{dim} {entity} {kind} {len(cells)}\n")
            for cell in cells:
                f.write(f"{e} " + " ".join(str(tag(first + k)) for k in cell) + "\n")
                e += 1
        f.write("$EndElements\n")
    print(f"{out}: sphere {sphere.nx - 1} x {sphere.ny - 1} x {sphere.nz - 1} Hex8, block {block.nx - 1} x "
          f"{block.ny - 1} x {block.nz - 1} Hex8, {n} nodes, {sphere.nx * sphere.ny} slave nodes")


if __name__ == "__main__":
    main()
