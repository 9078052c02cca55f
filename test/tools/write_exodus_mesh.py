#!/usr/bin/python3
"""write_exodus_mesh.py SOURCE.e OUT.e [options]: write an Exodus II mesh
with netCDF4 (Debian python3-netcdf4) - an Exodus II writer independent of
the Exodus II library DDContact reads with - from the mesh of SOURCE.e (for
example the results.e of a run on a generated mesh: coordinates, element
blocks, node sets and side sets; no results are copied).

Set names lose the "<block>/" prefix DDContact's results give them (the
reader qualifies them by the body again). Options make malformed files for
the reader's negative tests:
  --element-type T        call every block's elements T (e.g. WEDGE6)
  --invert-element N      reverse element N's corners (1-based, file numbering)
  --side-set-element N    make the first side of the first side set name element N
  --side-number S         make the first side of the first side set side S
Exit status 0, or 2 on bad usage.
"""
import sys

import netCDF4
import numpy as np


def usage(msg):
    print("write_exodus_mesh.py: " + msg, file=sys.stderr)
    sys.exit(2)


def chars(strings, width):
    a = np.zeros((len(strings), width), dtype="S1")
    for i, s in enumerate(strings):
        b = s.encode()[: width - 1]
        a[i, : len(b)] = [bytes([c]) for c in b]
    return a


def text(row):
    return b"".join(c for c in row if c not in (b"", b"\x00")).decode()


def main():
    args = sys.argv[1:]
    if len(args) < 2:
        usage("usage: write_exodus_mesh.py SOURCE.e OUT.e [options]")
    src, out = args[0], args[1]
    opts = {}
    i = 2
    while i < len(args):
        if args[i] in ("--element-type", "--invert-element", "--side-set-element", "--side-number") and i + 1 < len(args):
            opts[args[i]] = args[i + 1]
            i += 2
        else:
            usage(f"unknown option {args[i]}")

    s = netCDF4.Dataset(src)
    s.set_auto_mask(False)
    dim = len(s.dimensions["num_dim"])
    coords = [np.array(s.variables[v][:]) for v in ("coordx", "coordy", "coordz")[:dim]]
    nblk = len(s.dimensions["num_el_blk"])
    block_names = [text(r) for r in s.variables["eb_names"][:]]
    block_ids = list(s.variables["eb_prop1"][:])
    conns, types = [], []
    for b in range(nblk):
        v = s.variables[f"connect{b + 1}"]
        conns.append(np.array(v[:]))
        types.append(v.getncattr("elem_type"))
    sets = {}
    for kind, count, names, entries in (("ns", "num_node_sets", "ns_names", ["node_ns"]),
                                        ("ss", "num_side_sets", "ss_names", ["elem_ss", "side_ss"])):
        n = len(s.dimensions[count]) if count in s.dimensions else 0
        nm = [text(r) for r in s.variables[names][:]] if n else []
        sets[kind] = [(nm[k].split("/", 1)[-1], [np.array(s.variables[f"{e}{k + 1}"][:]) for e in entries])
                      for k in range(n)]
    s.close()

    if "--element-type" in opts:
        types = [opts["--element-type"]] * nblk
    if "--invert-element" in opts:
        n = int(opts["--invert-element"]) - 1
        for b in range(nblk):
            if n < len(conns[b]):
                c = conns[b][n]
                t = types[b].upper()
                if t.startswith("TET"):
                    c[[1, 2]] = c[[2, 1]]  # turned inside out
                elif t.startswith("HEX"):
                    c[:4], c[4:8] = c[4:8].copy(), c[:4].copy()  # top and bottom swapped
                else:
                    c[:4] = c[[0, 3, 2, 1]]  # clockwise
                break
            n -= len(conns[b])
    if "--side-set-element" in opts:
        sets["ss"][0][1][0][0] = int(opts["--side-set-element"])
    if "--side-number" in opts:
        sets["ss"][0][1][1][0] = int(opts["--side-number"])

    d = netCDF4.Dataset(out, "w", format="NETCDF3_64BIT_OFFSET")
    d.api_version = np.float32(6.02)
    d.version = np.float32(6.02)
    d.floating_point_word_size = np.int32(8)
    d.file_size = np.int32(1)
    d.maximum_name_length = np.int32(80)
    d.int64_status = np.int32(0)
    d.title = "written by write_exodus_mesh.py (netCDF4)"
    d.createDimension("len_string", 33)
    d.createDimension("len_line", 81)
    d.createDimension("four", 4)
    d.createDimension("len_name", 81)
    d.createDimension("time_step", None)
    d.createDimension("num_dim", dim)
    d.createDimension("num_nodes", len(coords[0]))
    d.createDimension("num_elem", sum(len(c) for c in conns))
    d.createDimension("num_el_blk", nblk)
    d.createVariable("time_whole", "f8", ("time_step",))
    for axis, x in zip("xyz", coords):
        d.createVariable("coord" + axis, "f8", ("num_nodes",))[:] = x
    d.createVariable("coor_names", "S1", ("num_dim", "len_name"))[:] = chars(list("xyz"[:dim]), 81)
    d.createVariable("eb_status", "i4", ("num_el_blk",))[:] = np.ones(nblk, dtype=np.int32)
    p = d.createVariable("eb_prop1", "i4", ("num_el_blk",))
    p.setncattr("name", "ID")
    p[:] = np.array(block_ids, dtype=np.int32)
    d.createVariable("eb_names", "S1", ("num_el_blk", "len_name"))[:] = chars(block_names, 81)
    for b in range(nblk):
        d.createDimension(f"num_el_in_blk{b + 1}", len(conns[b]))
        d.createDimension(f"num_nod_per_el{b + 1}", conns[b].shape[1])
        v = d.createVariable(f"connect{b + 1}", "i4", (f"num_el_in_blk{b + 1}", f"num_nod_per_el{b + 1}"))
        v.setncattr("elem_type", types[b])
        v[:] = conns[b].astype(np.int32)
    for kind, entries, count in (("ns", ["node_ns"], "num_nod_ns"), ("ss", ["elem_ss", "side_ss"], "num_side_ss")):
        n = len(sets[kind])
        if not n:
            continue
        d.createDimension("num_node_sets" if kind == "ns" else "num_side_sets", n)
        dimname = "num_node_sets" if kind == "ns" else "num_side_sets"
        d.createVariable(f"{kind}_status", "i4", (dimname,))[:] = np.ones(n, dtype=np.int32)
        p = d.createVariable(f"{kind}_prop1", "i4", (dimname,))
        p.setncattr("name", "ID")
        p[:] = np.arange(1, n + 1, dtype=np.int32)
        d.createVariable(f"{kind}_names", "S1", (dimname, "len_name"))[:] = chars([nm for nm, _ in sets[kind]], 81)
        for k, (_, arrays) in enumerate(sets[kind]):
            d.createDimension(f"{count}{k + 1}", len(arrays[0]))
            for e, a in zip(entries, arrays):
                d.createVariable(f"{e}{k + 1}", "i4", (f"{count}{k + 1}",))[:] = a.astype(np.int32)
    d.close()


if __name__ == "__main__":
    main()
