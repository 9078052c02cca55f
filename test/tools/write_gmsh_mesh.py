#!/usr/bin/python3
"""write_gmsh_mesh.py SOURCE.e OUT.msh: write the mesh of the Exodus II file
SOURCE.e (for example the results.e of a run on a generated mesh) as a Gmsh
MSH 4.1 ASCII file, read with netCDF4 (Debian python3-netcdf4):

  - each element block a physical volume (3-D) or surface (2-D) named after
    the block, its elements of the same Gmsh type (Hex8, Tet4, Quad4 only:
    Exodus II and Gmsh order their corners alike);
  - each side set a physical surface (3-D) or curve (2-D) of its element
    sides (Exodus II side numbering), named without the "<block>/" prefix
    DDContact's results give it (the reader qualifies it by the body);
  - each node set a physical point group of one point entity whose point
    elements are the set's nodes, named likewise.

What the Gmsh reader reads (packages/io/src/DDC_Gmsh.hpp); Gmsh itself
writes one point per point entity. Exit status 0, or 2 on bad usage or an
element type it does not write.
"""
import sys

import netCDF4
import numpy as np

# Exodus II element type -> (Gmsh type, dimension, Gmsh type of its sides,
# the 0-based corners of each side in Exodus II's side numbering)
TYPES = {
    "HEX8": (5, 3, 3, [[0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [0, 4, 7, 3], [0, 3, 2, 1], [4, 5, 6, 7]]),
    "TETRA4": (4, 3, 2, [[0, 1, 3], [1, 2, 3], [0, 3, 2], [0, 2, 1]]),
    "QUAD4": (3, 2, 1, [[0, 1], [1, 2], [2, 3], [3, 0]]),
}


def text(row):
    return b"".join(c for c in row if c not in (b"", b"\x00")).decode()


def main():
    if len(sys.argv) != 3:
        print("usage: write_gmsh_mesh.py SOURCE.e OUT.msh", file=sys.stderr)
        sys.exit(2)
    src, out = sys.argv[1:]
    s = netCDF4.Dataset(src)
    s.set_auto_mask(False)
    dim = len(s.dimensions["num_dim"])
    xyz = np.zeros((len(s.dimensions["num_nodes"]), 3))
    for a, v in enumerate(("coordx", "coordy", "coordz")[:dim]):
        xyz[:, a] = s.variables[v][:]
    blocks = []
    for b in range(len(s.dimensions["num_el_blk"])):
        v = s.variables[f"connect{b + 1}"]
        t = v.getncattr("elem_type").upper()
        t = {"HEX": "HEX8", "TETRA": "TETRA4", "TET4": "TETRA4", "QUAD": "QUAD4"}.get(t, t)
        if t not in TYPES:
            print(f"write_gmsh_mesh.py: block {b + 1} has elements of type {t}; writes HEX8, TETRA4, QUAD4",
                  file=sys.stderr)
            sys.exit(2)
        blocks.append((text(s.variables["eb_names"][b]), t, np.array(v[:])))
    def sets(count, names, entries):
        n = len(s.dimensions[count]) if count in s.dimensions else 0
        return [(text(s.variables[names][k]).split("/", 1)[-1], [np.array(s.variables[f"{e}{k + 1}"][:]) for e in entries])
                for k in range(n)]
    side_sets = sets("num_side_sets", "ss_names", ["elem_ss", "side_ss"])
    node_sets = sets("num_node_sets", "ns_names", ["node_ns"])
    s.close()

    # The element block holding each (1-based) element, and its row.
    starts = np.cumsum([0] + [len(c) for _, _, c in blocks])
    body_dim = TYPES[blocks[0][1]][1]
    physical = []  # (dim, tag, name)
    for name, _, _ in blocks:
        physical.append((body_dim, len(physical) + 1, name))
    for name, _ in side_sets:
        physical.append((body_dim - 1, len(physical) + 1, name))
    for name, _ in node_sets:
        physical.append((0, len(physical) + 1, name))
    lines = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", str(len(physical))]
    lines += [f'{d} {t} "{n}"' for d, t, n in physical]
    lines += ["$EndPhysicalNames", "$Entities"]
    # Entities: a point per node set, a curve or surface per side set, a
    # surface or volume per block; tag k + 1 within its dimension.
    count = [0, 0, 0, 0]
    count[0] = len(node_sets)
    count[body_dim - 1] += len(side_sets)
    count[body_dim] += len(blocks)
    lines.append(" ".join(map(str, count)))
    lo, hi = xyz.min(axis=0), xyz.max(axis=0)
    box = " ".join(repr(float(x)) for x in (*lo, *hi))
    entities = {0: [], 1: [], 2: [], 3: []}
    for d, t, _ in physical:
        entities[d].append(t)
    for d in range(4):
        for k, t in enumerate(entities[d]):
            lines.append(f"{k + 1} 0 0 0 1 {t}" if d == 0 else f"{k + 1} {box} 1 {t} 0")
    lines += ["$EndEntities", "$Nodes", f"1 {len(xyz)} 1 {len(xyz)}", f"{body_dim} 1 0 {len(xyz)}"]
    lines += [str(i + 1) for i in range(len(xyz))]
    lines += [f"{x!r} {y!r} {z!r}" for x, y, z in xyz.tolist()]
    lines.append("$EndNodes")
    element_blocks = []  # (dim, entity, gmsh type, rows of node tags)
    for k, (_, t, conn) in enumerate(blocks):
        element_blocks.append((body_dim, k + 1, TYPES[t][0], conn))
    for k, (_, (elems, sides)) in enumerate(side_sets):
        rows = []
        for e, side in zip(elems.tolist(), sides.tolist()):
            b = int(np.searchsorted(starts, e - 1, side="right")) - 1
            _, t, conn = blocks[b]
            rows.append(conn[e - 1 - starts[b]][TYPES[t][3][side - 1]])
        element_blocks.append((body_dim - 1, k + 1, TYPES[blocks[0][1]][2], np.array(rows).reshape(len(rows), -1)))
    for k, (_, (nodes,)) in enumerate(node_sets):
        element_blocks.append((0, k + 1, 15, nodes.reshape(-1, 1)))
    total = sum(len(r) for *_, r in element_blocks)
    lines += ["$Elements", f"{len(element_blocks)} {total} 1 {total}"]
    tag = 1
    for d, entity, gtype, rows in element_blocks:
        lines.append(f"{d} {entity} {gtype} {len(rows)}")
        for r in rows.tolist():
            lines.append(" ".join(map(str, [tag] + r)))
            tag += 1
    lines.append("$EndElements")
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
