#!/usr/bin/python3
"""write_mesh_input_cases.py OUTDIR: the Exodus II and Gmsh meshes of the mesh
input negative cases (test/negative_cases.txt, "Mesh input and contact
set-up"), written with netCDF4 (Debian python3-netcdf4), not the Exodus II
library DDContact reads them with:

  two_blocks.e     a conforming Quad4 mesh of the square [0, 2] x [0, 1], 2 x 1
                   elements, in two element blocks 'Left' and 'Right' that
                   share the nodes on x = 1; node sets 'left' (x = 0) and
                   'right' (x = 2)
  huge_header.e    two_blocks.e with a header that declares 300 million nodes
                   (its coordinates declared, never written: a few kB)
  huge_header_nc4.e  the same in netCDF-4 (HDF5), whose unwritten chunks
                   take no room
  truncated.e      two_blocks.e without its last 20 bytes (in the coordinates)
  truncated_header.e  two_blocks.e cut short after its first half (in the
                   header)
  coordinate_huge.e, coordinate_nan.e   two_blocks.e with x = 1e300 or NaN
                   at node 1
  coordinate_huge.msh, coordinate_nan.msh   a Gmsh 4.1 square of one Quad4
                   with x = 1e300 or nan at node 1
Exit status 0, or 2 on bad usage.
"""
import os
import sys

import netCDF4
import numpy as np


def chars(strings, width):
    a = np.zeros((len(strings), width), dtype="S1")
    for i, s in enumerate(strings):
        b = s.encode()[: width - 1]
        a[i, : len(b)] = [bytes([c]) for c in b]
    return a


def write_exodus(path, num_nodes=6, x0=0.0, fmt="NETCDF3_64BIT_OFFSET"):
    """Nodes 1..6: (0,0) (1,0) (2,0) (0,1) (1,1) (2,1); block Left = element
    1-2-5-4, block Right = 2-3-6-5 (counter-clockwise). With num_nodes > 6
    the coordinates are declared that long and only the first 6 written."""
    d = netCDF4.Dataset(path, "w", format=fmt)
    d.api_version = np.float32(6.02)
    d.version = np.float32(6.02)
    d.floating_point_word_size = np.int32(8)
    d.file_size = np.int32(1)
    d.maximum_name_length = np.int32(32)
    d.int64_status = np.int32(0)
    d.title = "write_mesh_input_cases.py"
    for name, n in (("len_string", 33), ("len_line", 81), ("four", 4), ("len_name", 33), ("num_dim", 2),
                    ("num_nodes", num_nodes), ("num_elem", 2), ("num_el_blk", 2), ("num_node_sets", 2)):
        d.createDimension(name, n)
    d.createDimension("time_step", None)
    d.createVariable("time_whole", "f8", ("time_step",))
    d.createVariable("coor_names", "S1", ("num_dim", "len_name"))[:] = chars(["x", "y"], 33)
    d.createVariable("eb_status", "i4", ("num_el_blk",))[:] = [1, 1]
    p = d.createVariable("eb_prop1", "i4", ("num_el_blk",))
    p.setncattr("name", "ID")
    p[:] = [1, 2]
    d.createVariable("eb_names", "S1", ("num_el_blk", "len_name"))[:] = chars(["Left", "Right"], 33)
    for b, conn in enumerate(([1, 2, 5, 4], [2, 3, 6, 5])):
        d.createDimension(f"num_el_in_blk{b + 1}", 1)
        d.createDimension(f"num_nod_per_el{b + 1}", 4)
        v = d.createVariable(f"connect{b + 1}", "i4", (f"num_el_in_blk{b + 1}", f"num_nod_per_el{b + 1}"))
        v.setncattr("elem_type", "QUAD4")
        v[:] = np.array([conn], dtype=np.int32)
    d.createVariable("ns_status", "i4", ("num_node_sets",))[:] = [1, 1]
    p = d.createVariable("ns_prop1", "i4", ("num_node_sets",))
    p.setncattr("name", "ID")
    p[:] = [1, 2]
    d.createVariable("ns_names", "S1", ("num_node_sets", "len_name"))[:] = chars(["left", "right"], 33)
    for k, nodes in enumerate(([1, 4], [3, 6])):
        d.createDimension(f"num_nod_ns{k + 1}", 2)
        d.createVariable(f"node_ns{k + 1}", "i4", (f"num_nod_ns{k + 1}",))[:] = np.array(nodes, dtype=np.int32)
    # The coordinates last: a declared length beyond what is written costs
    # nothing in a netCDF-4 file.
    x = [x0, 1.0, 2.0, 0.0, 1.0, 2.0]
    y = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]
    for axis, values in (("x", x), ("y", y)):
        chunks = {"chunksizes": [6], "fill_value": False} if fmt == "NETCDF4" else {}
        v = d.createVariable("coord" + axis, "f8", ("num_nodes",), **chunks)
        v[:6] = np.array(values)
    d.close()


def write_msh(path, x0):
    with open(path, "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
        f.write("$Entities\n0 0 1 0\n1 0 0 0 1 1 0 1 1 0\n$EndEntities\n")
        f.write("$PhysicalNames\n1\n2 1 \"Block\"\n$EndPhysicalNames\n")
        f.write(f"$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n{x0} 0 0\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n")
        f.write("$Elements\n1 1 1 1\n2 1 3 1\n1 1 2 3 4\n$EndElements\n")


def main():
    if len(sys.argv) != 2:
        print("usage: write_mesh_input_cases.py OUTDIR", file=sys.stderr)
        sys.exit(2)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    write_exodus(os.path.join(out, "two_blocks.e"))
    write_exodus(os.path.join(out, "coordinate_huge.e"), x0=1e300)
    write_exodus(os.path.join(out, "coordinate_nan.e"), x0=float("nan"))
    write_exodus(os.path.join(out, "huge_header_nc4.e"), num_nodes=300000000, fmt="NETCDF4")
    with open(os.path.join(out, "two_blocks.e"), "rb") as f:
        whole = f.read()
    # The classic header: dimension num_nodes (name, then its length as 4
    # big-endian bytes) declared 300 million long.
    name = b"num_nodes\x00\x00\x00"
    at = whole.index(name) + len(name)
    with open(os.path.join(out, "huge_header.e"), "wb") as f:
        f.write(whole[:at] + (300000000).to_bytes(4, "big") + whole[at + 4:])
    with open(os.path.join(out, "truncated.e"), "wb") as f:
        f.write(whole[:-20])
    with open(os.path.join(out, "truncated_header.e"), "wb") as f:
        f.write(whole[: len(whole) // 2])
    write_msh(os.path.join(out, "coordinate_huge.msh"), "1e300")
    write_msh(os.path.join(out, "coordinate_nan.msh"), "nan")


if __name__ == "__main__":
    main()
