#!/usr/bin/env python3
"""cattaneo_2d_mesh.py [OUT.msh]: the Gmsh mesh of examples/cattaneo_2d.xml.

A plane-strain cylinder of radius R = 1 (centre (0, R)) touching a block at
the origin (doc/contact.md, "Cattaneo"). Both bodies are structured Quad4
meshes graded towards the contact point, so the contact zone (half-width
a of 0.05-0.1 R) is resolved by uniform elements of size H0 and the rest
of each body is coarse:

  - x: uniform spacing H0 for |x| <= X_UNIFORM, then growing by RATIO per
    element out to |x| = W_CYLINDER (the cylinder, a node at x = 0) and
    W_BLOCK (the block, its nodes half an element beside the cylinder's);
  - the cylinder is its cap below y = CAP (the flat top, loaded), between
    the arc y = R - sqrt(R^2 - x^2) and y = CAP, each column split like the
    centre one: layers of H0 down to depth D_UNIFORM from the arc, then
    growing by RATIO;
  - the block is [-W_BLOCK, W_BLOCK] x [-DEPTH, 0], layers of H0 below its
    top down to D_UNIFORM, then growing by RATIO.

Physical groups: surfaces "cylinder", "block"; curves "surface" (the
cylinder's arc, the slave side), "load" (the cylinder's top), "top" (the
block's top, the master side), "bottom" (the block's base). Written as MSH
4.1 ASCII (packages/io/src/DDC_Gmsh.hpp). Plain Python, no Gmsh needed:
    python3 examples/cattaneo_2d_mesh.py examples/cattaneo_2d.msh
"""
import math
import sys

R = 1.0
H0 = 0.004          # element size in the contact zone (2a ~ 0.14 R: ~35 slave nodes across)
X_UNIFORM = 0.1     # half-width of the uniform zone (> a)
D_UNIFORM = 0.05    # depth of the uniform layers
RATIO = 1.15        # growth of the element size outside
W_CYLINDER = 0.5    # half-width of the cylinder's cap
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


def structured(xs, ys_of_column):
    """Nodes (x, y) of a structured grid, column i along ys_of_column(i);
    quads counter-clockwise; index(i, j)."""
    nodes, ny = [], None
    for i, x in enumerate(xs):
        ys = ys_of_column(i)
        ny = len(ys)
        nodes += [(x, y) for y in ys]
    quads = []
    for i in range(len(xs) - 1):
        for j in range(ny - 1):
            a = i * ny + j
            quads.append((a, a + ny, a + ny + 1, a + 1))
    return nodes, quads, ny


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "cattaneo_2d.msh"
    # Cylinder cap.
    xc = symmetric(graded(W_CYLINDER, X_UNIFORM))
    fractions = [d / CAP for d in graded(CAP, D_UNIFORM)]

    def cylinder_column(i):
        yb = R - math.sqrt(R * R - xc[i] ** 2)
        return [yb + f * (CAP - yb) for f in fractions]

    cn, cq, cny = structured(xc, cylinder_column)
    arc = [(i * cny, (i + 1) * cny) for i in range(len(xc) - 1)]
    load = [(i * cny + cny - 1, (i + 1) * cny + cny - 1) for i in range(len(xc) - 1)]
    # Block.
    # The block's nodes lie half an element beside the cylinder's, so no
    # slave node starts on a master node (where its projection would jump
    # between the two facets).
    xb = symmetric(graded(W_BLOCK, X_UNIFORM, start=0.5 * H0))
    layers = [-d for d in reversed(graded(DEPTH, D_UNIFORM))]
    bn, bq, bny = structured(xb, lambda i: layers)
    top = [(i * bny + bny - 1, (i + 1) * bny + bny - 1) for i in range(len(xb) - 1)]
    bottom = [(i * bny, (i + 1) * bny) for i in range(len(xb) - 1)]

    off = len(cn)  # block node indices follow the cylinder's
    tag = lambda k: k + 1  # node tags from 1
    with open(out, "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
        f.write('$PhysicalNames\n6\n1 1 "surface"\n1 2 "load"\n1 3 "top"\n1 4 "bottom"\n'
                '2 5 "cylinder"\n2 6 "block"\n$EndPhysicalNames\n')
        f.write("$Entities\n0 4 2 0\n")
        for c in range(1, 5):
            f.write(f"{c} {-W_BLOCK} {-DEPTH} 0 {W_BLOCK} {CAP} 0 1 {c} 0\n")
        f.write(f"1 {-W_CYLINDER} 0 0 {W_CYLINDER} {CAP} 0 1 5 2 1 2\n")
        f.write(f"2 {-W_BLOCK} {-DEPTH} 0 {W_BLOCK} 0 0 1 6 2 3 4\n")
        f.write("$EndEntities\n")
        n = len(cn) + len(bn)
        f.write(f"$Nodes\n2 {n} 1 {n}\n")
        for surface, nodes, first in ((1, cn, 0), (2, bn, off)):
            f.write(f"2 {surface} 0 {len(nodes)}\n")
            f.write("".join(f"{tag(first + k)}\n" for k in range(len(nodes))))
            f.write("".join(f"{x:.12g} {y:.12g} 0\n" for x, y in nodes))
        f.write("$EndNodes\n")
        blocks = [(1, 1, 1, arc, 0), (1, 2, 1, load, 0), (1, 3, 1, top, off), (1, 4, 1, bottom, off),
                  (2, 1, 3, cq, 0), (2, 2, 3, bq, off)]
        m = sum(len(b[3]) for b in blocks)
        f.write(f"$Elements\n{len(blocks)} {m} 1 {m}\n")
        e = 1
        for dim, entity, kind, cells, first in blocks:
            f.write(f"{dim} {entity} {kind} {len(cells)}\n")
            for cell in cells:
                f.write(f"{e} " + " ".join(str(tag(first + k)) for k in cell) + "\n")
                e += 1
        f.write("$EndElements\n")
    print(f"{out}: cylinder {len(xc) - 1} x {cny - 1} Quad4, block {len(xb) - 1} x {bny - 1} Quad4, "
          f"{len(cn) + len(bn)} nodes, {len(arc) + 1} slave nodes")


if __name__ == "__main__":
    main()
