#!/usr/bin/python3
"""check_exodus_pieces.py WHOLE_FILE PIECES_BASE [TOLERANCE]: the Exodus II
results a ddcontact run writes as one file per MPI rank ("spread" files,
the pieces SEACAS epu joins) compared with the single results file of the
same model written by a run that holds the whole mesh.

WHOLE_FILE is one Exodus II file (e.g. runs/x/results.e); node i+1 and
element e+1 of it are mesh node i and element e unless it stores
node_num_map / elem_num_map (then those are its global ids). The pieces are
PIECES_BASE.P.r for r = 0 .. P-1, r zero-padded to the digits of P
(results.e.4.0 .. results.e.4.3, results.e.12.00 .. results.e.12.11); P is
found from the directory listing, which must hold every piece of one P and
no piece of another. When PIECES_BASE is itself a file (a run with the
whole mesh, e.g. one continued from pieces by a restart) it is the one
piece. Each piece maps its local nodes and elements to global
ids with node_num_map / elem_num_map. The files are read with netCDF4
(Debian python3-netcdf4) through the Exodus II netCDF layout, independently
of the Exodus II library that wrote them.

Checked, the first mismatch named with its file, entity, ids and values:
- Nemesis information, where a piece has it (ex_put_init_info and
  ex_put_init_global): the processor count (dimension num_processors, or
  processor_info[0]) is P, the processors per file (num_procs_file, or
  processor_info[1]) is 1, the file type nem_ftype is "parallel" (0 or 'p');
  num_nodes_global, num_elems_global, num_el_blk_global, num_ns_global and
  num_ss_global equal the whole file's counts, and the global block ids and
  element counts, node set ids and node counts, side set ids and side counts
  (el_blk_ids_global, el_blk_cnt_global, ns_ids_global, ns_node_cnt_global,
  ss_ids_global, ss_side_cnt_global) equal the whole file's where written.
  Which of them were found is printed; none is required;
- every piece has the whole file's element blocks: the same ids in the same
  order, the same names, element types and nodes per element (a block may
  be empty in a piece);
- every element is in exactly one piece and the pieces' elements are all
  the whole file's; every node is in at least one piece (nodes on the
  partition boundaries are in several);
- each piece node's coordinates equal those of its global node exactly
  (the same doubles are written);
- each piece element is in the block of the same id in the whole file, and
  its nodes, mapped to global ids, are the whole file's element's nodes in
  the same order;
- node sets and side sets, matched by name: the union over the pieces of
  their global node ids, and of their (global element id, side) pairs,
  equals the whole file's set;
- the nodal, element and global variable names are the same, in the same
  order; the time steps are as many and the times equal exactly;
- at every step every piece's nodal and element values equal the whole
  file's at the same global node or element, a node in several pieces
  carries the same value in each, and each piece's global variables equal
  the whole file's, all to TOLERANCE (default 1e-12) relative to the
  largest absolute value in the whole file at that step of the variable's
  field (all components of a vector or tensor: displ_x, displ_y and
  displ_z share one scale; a global variable is its own).

Exit status 0 when everything agrees; 1 with the first mismatch named.
"""
import os
import re
import sys

import netCDF4
import numpy as np

# Variables: the same partition computes the same numbers, up to round-off
# in the order of sums; a difference counts relative to the variable's
# largest absolute value over the whole file at that step.
SAME_VALUES = 1e-12
# At most this many ids are listed in a message about missing or extra ids.
LIST_IDS = 8


def fail(msg):
    print("check_exodus_pieces: " + msg, file=sys.stderr)
    sys.exit(1)


def listed(ids):
    ids = [int(i) for i in ids]
    more = f" and {len(ids) - LIST_IDS} more" if len(ids) > LIST_IDS else ""
    return ", ".join(map(str, ids[:LIST_IDS])) + more


class IdIndex:
    """The position of each global id in a file's id map."""

    def __init__(self, ids, what, path):
        self.order = np.argsort(ids, kind="stable")
        self.sorted = ids[self.order]
        twice = np.nonzero(self.sorted[1:] == self.sorted[:-1])[0]
        if len(twice):
            fail(f"{path}: {what} id {int(self.sorted[twice[0]])} appears twice in its id map")

    def find(self, ids):
        """(positions, found): positions are valid where found."""
        pos = np.searchsorted(self.sorted, ids)
        pos = np.minimum(pos, max(len(self.sorted) - 1, 0))
        found = (self.sorted[pos] == ids) if len(self.sorted) else np.zeros(len(ids), dtype=bool)
        return self.order[pos] if len(self.sorted) else pos, found


class Block:
    def __init__(self, index, block_id, name, count, elem_type, nodes_per_elem, connect, start):
        self.index = index  # k of connect{k}, vals_elem_var{j}eb{k}: 1-based position
        self.id = block_id
        self.name = name
        self.count = count
        self.elem_type = elem_type  # None when the block has no connectivity (empty)
        self.nodes_per_elem = nodes_per_elem
        self.connect = connect  # 0-based local node indices, (count, nodes_per_elem)
        self.start = start  # the block's first element among the file's elements


class Exodus:
    """One Exodus II file read through its netCDF layout."""

    def __init__(self, path):
        self.path = path
        try:
            self.ds = netCDF4.Dataset(path)
        except OSError as e:
            fail(f"{path}: cannot be read as netCDF ({e})")
        self.ds.set_auto_mask(False)
        self.num_dim = self.dim("num_dim")
        self.num_nodes = self.dim("num_nodes")
        self.num_elem = self.dim("num_elem")
        self.node_ids = self.id_map("node_num_map", self.num_nodes, "node")
        self.elem_ids = self.id_map("elem_num_map", self.num_elem, "element")
        self.coords = self.read_coords()
        self.blocks = self.read_blocks()
        self.node_sets = self.read_sets("node")
        self.side_sets = self.read_sets("side")
        self.nodal_names = self.names("name_nod_var")
        self.elem_names = self.names("name_elem_var")
        self.glob_names = self.names("name_glo_var")
        self.times = np.asarray(self.ds.variables["time_whole"][:], dtype=float) \
            if "time_whole" in self.ds.variables else np.zeros(0)

    def dim(self, name):
        """A dimension's length; 0 when absent (netCDF has no empty fixed dimension)."""
        d = self.ds.dimensions.get(name)
        return len(d) if d is not None else 0

    def var(self, name):
        v = self.ds.variables.get(name)
        return None if v is None else v[:]

    def names(self, name):
        v = self.ds.variables.get(name)
        if v is None:
            return []
        return [str(s).strip() for s in np.atleast_1d(netCDF4.chartostring(v[:]))]

    def id_map(self, name, n, what):
        m = self.var(name)
        if m is None:
            return np.arange(1, n + 1, dtype=np.int64)
        m = np.asarray(m, dtype=np.int64).ravel()
        if len(m) != n:
            fail(f"{self.path}: {name} has {len(m)} entries for {n} {what}s")
        return m

    def read_coords(self):
        v = self.ds.variables
        if "coordx" in v:
            axes = [np.asarray(v[a][:], dtype=float) for a in ("coordx", "coordy", "coordz")[: self.num_dim]
                    if a in v]
            if len(axes) != self.num_dim:
                fail(f"{self.path}: {len(axes)} coordinate arrays for num_dim {self.num_dim}")
            c = np.stack(axes, axis=1) if axes else np.zeros((self.num_nodes, 0))
        elif "coord" in v:
            c = np.asarray(v["coord"][:], dtype=float).T
        elif self.num_nodes == 0:
            c = np.zeros((0, self.num_dim))
        else:
            fail(f"{self.path}: no coordinates (coordx/coordy/coordz or coord)")
        if c.shape != (self.num_nodes, self.num_dim):
            fail(f"{self.path}: coordinates of shape {c.shape} for {self.num_nodes} nodes in {self.num_dim} dimensions")
        return c

    def read_blocks(self):
        n = self.dim("num_el_blk")
        ids = self.var("eb_prop1")
        ids = np.arange(1, n + 1) if ids is None else np.asarray(ids, dtype=np.int64)
        names = self.names("eb_names") or [""] * n
        status = self.var("eb_status")
        blocks, start = [], 0
        for k in range(1, n + 1):
            count = self.dim(f"num_el_in_blk{k}")
            if status is not None and int(status[k - 1]) == 0:
                count = 0
            c = self.ds.variables.get(f"connect{k}") if count else None
            npe = self.dim(f"num_nod_per_el{k}") or None
            elem_type, connect = None, None
            if c is not None:
                elem_type = c.getncattr("elem_type").strip() if "elem_type" in c.ncattrs() else ""
                connect = np.asarray(c[:], dtype=np.int64)
                if connect.shape != (count, npe or connect.shape[1]):
                    fail(f"{self.path}: block {int(ids[k - 1])}: connect{k} of shape {connect.shape} "
                         f"for {count} elements of {npe} nodes")
                npe = connect.shape[1]
                bad = np.nonzero((connect < 1) | (connect > self.num_nodes))
                if len(bad[0]):
                    fail(f"{self.path}: block {int(ids[k - 1])}: element {int(bad[0][0]) + 1} of the block names "
                         f"node {int(connect[bad][0])}, outside 1..{self.num_nodes}")
                connect -= 1
            elif count:
                fail(f"{self.path}: block {int(ids[k - 1])} has {count} elements and no connect{k}")
            blocks.append(Block(k, int(ids[k - 1]), names[k - 1], count, elem_type, npe, connect, start))
            start += count
        if start != self.num_elem:
            fail(f"{self.path}: the blocks hold {start} elements, num_elem is {self.num_elem}")
        return blocks

    def read_sets(self, kind):
        """{key: (set id, name, local node indices) or (id, name, local element indices, sides)}."""
        s = "ns" if kind == "node" else "ss"
        n = self.dim(f"num_{kind}_sets")
        ids = self.var(f"{s}_prop1")
        ids = np.arange(1, n + 1) if ids is None else np.asarray(ids, dtype=np.int64)
        names = self.names(f"{s}_names") or [""] * n
        status = self.var(f"{s}_status")
        out = {}
        for k in range(1, n + 1):
            key = names[k - 1] or f"id {int(ids[k - 1])}"
            if key in out:
                fail(f"{self.path}: two {kind} sets called '{key}'")
            count = self.dim(f"num_nod_ns{k}" if kind == "node" else f"num_side_ss{k}")
            if status is not None and int(status[k - 1]) == 0:
                count = 0
            if kind == "node":
                nodes = self.var(f"node_ns{k}") if count else None
                nodes = np.zeros(0, dtype=np.int64) if nodes is None else np.asarray(nodes, dtype=np.int64) - 1
                if len(nodes) and (nodes.min() < 0 or nodes.max() >= self.num_nodes):
                    fail(f"{self.path}: node set '{key}' names a node outside 1..{self.num_nodes}")
                out[key] = (int(ids[k - 1]), names[k - 1], nodes)
            else:
                elems = self.var(f"elem_ss{k}") if count else None
                sides = self.var(f"side_ss{k}") if count else None
                elems = np.zeros(0, dtype=np.int64) if elems is None else np.asarray(elems, dtype=np.int64) - 1
                sides = np.zeros(0, dtype=np.int64) if sides is None else np.asarray(sides, dtype=np.int64)
                if len(elems) != len(sides):
                    fail(f"{self.path}: side set '{key}': {len(elems)} elements, {len(sides)} sides")
                if len(elems) and (elems.min() < 0 or elems.max() >= self.num_elem):
                    fail(f"{self.path}: side set '{key}' names an element outside 1..{self.num_elem}")
                out[key] = (int(ids[k - 1]), names[k - 1], elems, sides)
        return out

    def nodal(self, step, j):
        v = self.ds.variables
        if f"vals_nod_var{j + 1}" in v:
            return np.asarray(v[f"vals_nod_var{j + 1}"][step, :], dtype=float)
        if "vals_nod_var" in v:
            return np.asarray(v["vals_nod_var"][step, j, :], dtype=float)
        if self.num_nodes == 0:
            return np.zeros(0)
        fail(f"{self.path}: no values of nodal variable {j + 1} ({self.nodal_names[j]})")

    def element(self, step, j, block):
        """The block's values of element variable j, or None where the file has none."""
        v = self.ds.variables.get(f"vals_elem_var{j + 1}eb{block.index}")
        return None if v is None else np.asarray(v[step, :], dtype=float)

    def globals(self, step):
        v = self.ds.variables.get("vals_glo_var")
        if v is None:
            return np.zeros(0)
        return np.asarray(v[step, :], dtype=float).ravel()


def find_pieces(base):
    """P and the paths of BASE.P.r, r = 0 .. P-1 padded to the digits of P;
    BASE itself (P = 1) when it is a file: the results of a run with the
    whole mesh, compared the same way."""
    if os.path.isfile(base):
        return 1, [base]
    d = os.path.dirname(base) or "."
    name = os.path.basename(base)
    try:
        entries = os.listdir(d)
    except OSError as e:
        fail(f"cannot list {d} ({e.strerror})")
    pattern = re.compile(re.escape(name) + r"\.(\d+)\.(\d+)$")
    found = {}
    for f in entries:
        m = pattern.match(f)
        if m:
            found.setdefault(m.group(1), set()).add(m.group(2))
    if not found:
        fail(f"no pieces {base}.P.r in {d}")
    if len(found) > 1:
        fail(f"pieces of {len(found)} different processor counts in {d}: "
             + ", ".join(f"{name}.{p}.*" for p in sorted(found, key=int)))
    p_text, ranks = found.popitem()
    P = int(p_text)
    if P < 1 or p_text != str(P):
        fail(f"{base}.{p_text}.*: '{p_text}' is not a processor count")
    want = [f"{r:0{len(p_text)}d}" for r in range(P)]
    missing = [r for r in want if r not in ranks]
    if missing:
        fail(f"{base}.{P}.*: {len(missing)} of the {P} pieces missing: "
             + ", ".join(f"{name}.{P}.{r}" for r in missing[:LIST_IDS]))
    extra = sorted(ranks - set(want))
    if extra:
        fail(f"{base}.{P}.*: pieces {', '.join(f'{name}.{P}.{r}' for r in extra[:LIST_IDS])} are not "
             f"ranks 0..{P - 1} padded to the {len(p_text)} digit(s) of {P}")
    return P, [os.path.join(d, f"{name}.{P}.{r}") for r in want]


def nemesis_info(ds):
    """The Nemesis items of a piece, those that exist: {item: value}."""
    info = {}
    dims, v, attrs = ds.dimensions, ds.variables, ds.ncattrs()
    if "num_processors" in dims:
        info["num_processors"] = len(dims["num_processors"])
    if "num_procs_file" in dims:
        info["num_procs_file"] = len(dims["num_procs_file"])
    proc = ds.getncattr("processor_info") if "processor_info" in attrs else \
        (v["processor_info"][:] if "processor_info" in v else None)
    if proc is not None:
        proc = np.atleast_1d(np.asarray(proc)).ravel()
        info.setdefault("num_processors", int(proc[0]))
        if len(proc) > 1:
            info.setdefault("num_procs_file", int(proc[1]))
    ftype = ds.getncattr("nem_ftype") if "nem_ftype" in attrs else \
        (v["nem_ftype"][:] if "nem_ftype" in v else None)
    if ftype is not None:
        if isinstance(ftype, bytes):
            ftype = ftype.decode()
        elif not isinstance(ftype, str):
            a = np.asarray(ftype).ravel()
            if a.dtype.kind in "SU":
                ftype = a[0].decode() if isinstance(a[0], bytes) else str(a[0])
            else:
                ftype = int(a[0])
        info["nem_ftype"] = ftype
    for d in ("num_nodes_global", "num_elems_global", "num_el_blk_global", "num_ns_global", "num_ss_global"):
        if d in dims:
            info[d] = len(dims[d])
    for name in ("el_blk_ids_global", "el_blk_cnt_global", "ns_ids_global", "ns_node_cnt_global",
                 "ss_ids_global", "ss_side_cnt_global"):
        if name in v:
            var = v[name]
            a = np.asarray(var[:]).ravel()
            fill = var.getncattr("_FillValue") if "_FillValue" in var.ncattrs() else \
                netCDF4.default_fillvals.get(var.dtype.str[1:])
            if len(a) and (fill is None or not np.any(a == fill)):  # written, not left at the fill value
                info[name] = a.astype(np.int64)
    return info


def check_nemesis(piece, P, whole, seen):
    info = nemesis_info(piece.ds)
    seen.update(info)
    whole_has = "the whole file's"
    expect = {
        "num_processors": (P, f"there are {P} pieces"),
        "num_procs_file": (1, "a spread file holds one processor"),
        "num_nodes_global": (whole.num_nodes, whole_has),
        "num_elems_global": (whole.num_elem, whole_has),
        "num_el_blk_global": (len(whole.blocks), whole_has),
        "num_ns_global": (len(whole.node_sets), whole_has),
        "num_ss_global": (len(whole.side_sets), whole_has),
        "el_blk_ids_global": ([b.id for b in whole.blocks], whole_has),
        "el_blk_cnt_global": ([b.count for b in whole.blocks], whole_has),
        "ns_ids_global": ([s[0] for s in whole.node_sets.values()], whole_has),
        "ns_node_cnt_global": ([len(s[2]) for s in whole.node_sets.values()], whole_has),
        "ss_ids_global": ([s[0] for s in whole.side_sets.values()], whole_has),
        "ss_side_cnt_global": ([len(s[2]) for s in whole.side_sets.values()], whole_has),
    }
    for item, (want, why) in expect.items():
        if item in info and not np.array_equal(np.asarray(info[item]), np.asarray(want)):
            got = info[item].tolist() if isinstance(info[item], np.ndarray) else info[item]
            fail(f"{piece.path}: Nemesis {item} is {got}, expected {want} ({why})")
    if "nem_ftype" in info and info["nem_ftype"] not in (0, "p", "P"):
        fail(f"{piece.path}: Nemesis nem_ftype is {info['nem_ftype']!r}, not a parallel (spread) file (0 or 'p')")


def check_blocks(piece, whole):
    wb, pb = whole.blocks, piece.blocks
    if [b.id for b in pb] != [b.id for b in wb]:
        fail(f"{piece.path}: element block ids {[b.id for b in pb]}, the whole file has {[b.id for b in wb]}")
    for p, w in zip(pb, wb):
        if p.name != w.name:
            fail(f"{piece.path}: block {p.id} is called '{p.name}', in the whole file '{w.name}'")
        if p.count and w.elem_type is not None and p.elem_type.upper() != w.elem_type.upper():
            fail(f"{piece.path}: block {p.id} ('{p.name}') has element type {p.elem_type}, "
                 f"the whole file {w.elem_type}")
        if p.count and w.nodes_per_elem is not None and p.nodes_per_elem != w.nodes_per_elem:
            fail(f"{piece.path}: block {p.id} ('{p.name}') has {p.nodes_per_elem} nodes per element, "
                 f"the whole file {w.nodes_per_elem}")
        if p.count and not w.count:
            fail(f"{piece.path}: block {p.id} ('{p.name}') has {p.count} elements, in the whole file none")


def check_union(pieces, whole, index, what):
    """Element or node ids of the pieces against the whole file's; returns each piece's positions in it."""
    n = whole.num_elem if what == "element" else whole.num_nodes
    whole_ids = whole.elem_ids if what == "element" else whole.node_ids
    positions, count = [], np.zeros(n, dtype=np.int64)
    for p in pieces:
        ids = p.elem_ids if what == "element" else p.node_ids
        u, c = np.unique(ids, return_counts=True)
        if np.any(c > 1):
            fail(f"{p.path}: {what} id {int(u[np.argmax(c > 1)])} appears {int(c.max())} times in its id map")
        pos, found = index.find(ids)
        if not np.all(found):
            fail(f"{p.path}: {what} ids not in the whole file: {listed(ids[~found])}")
        positions.append(pos)
        count += np.bincount(pos, minlength=n)
    missing = np.nonzero(count == 0)[0]
    if len(missing):
        fail(f"{len(missing)} of the whole file's {n} {what}s in no piece: ids {listed(whole_ids[missing])}")
    if what == "element" and np.any(count > 1):
        i = int(np.argmax(count > 1))
        holders = [p.path for p, pos in zip(pieces, positions) if np.any(pos == i)]
        fail(f"element {int(whole_ids[i])} is in {int(count[i])} pieces: {', '.join(holders)}")
    return positions


def check_coordinates(piece, whole, npos):
    if piece.num_dim != whole.num_dim:
        fail(f"{piece.path}: num_dim {piece.num_dim}, the whole file's {whole.num_dim}")
    w = whole.coords[npos]
    bad = np.nonzero(np.any(piece.coords != w, axis=1))[0]
    if len(bad):
        i = int(bad[0])
        fail(f"{piece.path}: node {int(piece.node_ids[i])} (local {i + 1}): coordinates "
             f"{piece.coords[i].tolist()}, in the whole file {w[i].tolist()} ({len(bad)} of its nodes differ)")


def check_connectivity(piece, whole, npos, epos):
    starts = np.array([b.start for b in whole.blocks])
    for k, (p, w) in enumerate(zip(piece.blocks, whole.blocks)):
        if not p.count:
            continue
        wpos = epos[p.start: p.start + p.count]
        wblock = np.searchsorted(starts, wpos, side="right") - 1
        # Empty blocks share their start with the next block: the block of a
        # whole-file element is the last one starting at or before it.
        elsewhere = np.nonzero(wblock != k)[0]
        if len(elsewhere):
            i = int(elsewhere[0])
            fail(f"{piece.path}: element {int(piece.elem_ids[p.start + i])} is in block {p.id} ('{p.name}'), "
                 f"in the whole file in block {whole.blocks[wblock[i]].id} ('{whole.blocks[wblock[i]].name}')")
        mine = piece.node_ids[p.connect]
        theirs = whole.node_ids[w.connect[wpos - w.start]]
        bad = np.nonzero(np.any(mine != theirs, axis=1))[0]
        if len(bad):
            i = int(bad[0])
            fail(f"{piece.path}: block {p.id} ('{p.name}'): element {int(piece.elem_ids[p.start + i])} has nodes "
                 f"{mine[i].tolist()}, in the whole file {theirs[i].tolist()} "
                 f"({len(bad)} elements of the block differ)")


def difference(a, b, ids, scale, tol, what, other="the whole file"):
    """Largest relative difference of a against b (other's values); fails beyond tol * scale."""
    diff = np.abs(a - b)
    limit = tol * scale
    bad = ~(diff <= limit) & ~(np.isnan(a) & np.isnan(b))
    if np.any(bad):
        i = int(np.argmax(bad))
        fail(f"{what} {int(ids[i])}: {a[i]!r} where {other} has {b[i]!r} "
             f"(difference {diff[i]:.3e}, allowed {limit:.3e} = {tol:g} x largest {scale:.3e}; "
             f"{int(np.count_nonzero(bad))} values differ)")
    finite = diff[np.isfinite(diff)]
    return float(finite.max()) / scale if len(finite) and scale > 0 else 0.0


# Suffixes of the components of one vector or tensor field (displ_x, ...,
# stress_xz): they share the field's scale, so that a component that is
# round-off noise beside the others (a bar stretched along x) is compared
# with the field's magnitude, not with its own.
COMPONENTS = {"x", "y", "z", "xx", "yy", "zz", "xy", "yz", "xz"}


def field(name):
    """The field a variable is a component of (displ_x -> displ), or the name."""
    head, _, tail = name.rpartition("_")
    return head if head and tail in COMPONENTS else name


def largest(values):
    finite = np.abs(values[np.isfinite(values)])
    return float(finite.max()) if len(finite) else 0.0


def main():
    if len(sys.argv) not in (3, 4):
        fail("usage: check_exodus_pieces.py WHOLE_FILE PIECES_BASE [TOLERANCE]")
    tol = SAME_VALUES
    if len(sys.argv) == 4:
        try:
            tol = float(sys.argv[3])
        except ValueError:
            fail(f"TOLERANCE '{sys.argv[3]}' is not a number")
        if not tol >= 0:
            fail(f"TOLERANCE {sys.argv[3]} is negative")
    whole = Exodus(sys.argv[1])
    P, paths = find_pieces(sys.argv[2])
    pieces = [Exodus(p) for p in paths]
    node_index = IdIndex(whole.node_ids, "node", whole.path)
    elem_index = IdIndex(whole.elem_ids, "element", whole.path)

    # Structure: blocks, Nemesis information.
    nemesis = {}
    for p in pieces:
        check_blocks(p, whole)
        check_nemesis(p, P, whole, nemesis)
    print("check_exodus_pieces: Nemesis information checked: "
          + (", ".join(sorted(nemesis)) if nemesis else "none found"))

    # Elements in exactly one piece, nodes in at least one; coordinates and connectivity.
    epos = check_union(pieces, whole, elem_index, "element")
    npos = check_union(pieces, whole, node_index, "node")
    for p, n in zip(pieces, npos):
        check_coordinates(p, whole, n)
    for p, n, e in zip(pieces, npos, epos):
        check_connectivity(p, whole, n, e)

    # Node sets and side sets by name.
    for kind in ("node", "side"):
        wsets = whole.node_sets if kind == "node" else whole.side_sets
        union = {key: [] for key in wsets}
        for p in pieces:
            for key, s in (p.node_sets if kind == "node" else p.side_sets).items():
                if key not in wsets:
                    fail(f"{p.path}: {kind} set '{key}' is not in the whole file (it has {sorted(wsets)})")
                if kind == "node":
                    union[key].append(p.node_ids[s[2]][:, None])
                else:
                    union[key].append(np.stack([p.elem_ids[s[2]], s[3]], axis=1))
        for key, s in wsets.items():
            want = whole.node_ids[s[2]][:, None] if kind == "node" else np.stack([whole.elem_ids[s[2]], s[3]], axis=1)
            want = np.unique(want.reshape(-1, want.shape[1]), axis=0)
            got = np.unique(np.concatenate(union[key]).reshape(-1, want.shape[1]), axis=0) if union[key] \
                else np.zeros((0, want.shape[1]), dtype=np.int64)
            if not np.array_equal(got, want):
                w_rows, g_rows = set(map(tuple, want.tolist())), set(map(tuple, got.tolist()))
                show = (lambda rows: listed(sorted(r[0] for r in rows))) if kind == "node" else \
                    (lambda rows: ", ".join(f"(element {r[0]}, side {r[1]})" for r in sorted(rows)[:LIST_IDS]))
                msg = []
                if w_rows - g_rows:
                    msg.append(f"missing from the pieces: {show(w_rows - g_rows)}")
                if g_rows - w_rows:
                    msg.append(f"in the pieces, not in the whole file: {show(g_rows - w_rows)}")
                fail(f"{kind} set '{key}': " + "; ".join(msg))

    # Variables and time steps.
    for p in pieces:
        for what, mine, theirs in (("nodal", p.nodal_names, whole.nodal_names),
                                   ("element", p.elem_names, whole.elem_names),
                                   ("global", p.glob_names, whole.glob_names)):
            if mine != theirs:
                fail(f"{p.path}: {what} variables {mine}, the whole file has {theirs}")
        if len(p.times) != len(whole.times):
            fail(f"{p.path}: {len(p.times)} time steps, the whole file has {len(whole.times)}")
        bad = np.nonzero(p.times != whole.times)[0]
        if len(bad):
            i = int(bad[0])
            fail(f"{p.path}: step {i + 1} at time {p.times[i]!r}, in the whole file {whole.times[i]!r}")

    worst = 0.0
    for step in range(len(whole.times)):
        at = f"step {step + 1}"
        nodal_scale = {}
        for j, name in enumerate(whole.nodal_names):
            key = field(name)
            nodal_scale[key] = max(nodal_scale.get(key, 0.0), largest(whole.nodal(step, j)))
        for j, name in enumerate(whole.nodal_names):
            w = whole.nodal(step, j)
            scale = nodal_scale[field(name)]
            value, written = np.zeros(whole.num_nodes), np.zeros(whole.num_nodes, dtype=bool)
            for p, n in zip(pieces, npos):
                v = p.nodal(step, j)
                where = f"{p.path}: {at}: nodal {name} at node"
                worst = max(worst, difference(v, w[n], p.node_ids, scale, tol, where))
                # A node shared by pieces: the same value in each.
                both = written[n]
                difference(v[both], value[n][both], p.node_ids[both], scale, tol,
                           f"{p.path}: {at}: nodal {name} at shared node", "an earlier piece")
                value[n], written[n] = v, True
        element_values, element_scale = [], {}
        for j, name in enumerate(whole.elem_names):
            w = np.full(whole.num_elem, np.nan)
            has = np.zeros(whole.num_elem, dtype=bool)
            for b in whole.blocks:
                v = whole.element(step, j, b) if b.count else None
                if v is not None:
                    w[b.start: b.start + b.count], has[b.start: b.start + b.count] = v, True
            element_values.append((w, has))
            key = field(name)
            element_scale[key] = max(element_scale.get(key, 0.0), largest(w[has]))
        for j, name in enumerate(whole.elem_names):
            w, has = element_values[j]
            scale = element_scale[field(name)]
            for p, e in zip(pieces, epos):
                for b in p.blocks:
                    if not b.count:
                        continue
                    v = p.element(step, j, b)
                    pos = e[b.start: b.start + b.count]
                    ids = p.elem_ids[b.start: b.start + b.count]
                    if (v is None) != (not np.all(has[pos])):
                        fail(f"{p.path}: {at}: element variable {name} in block {b.id} ('{b.name}'): "
                             f"{'absent' if v is None else 'present'} in the piece, "
                             f"{'present' if v is None else 'absent'} in the whole file")
                    if v is not None:
                        where = f"{p.path}: {at}: element {name} in block {b.id} at element"
                        worst = max(worst, difference(v, w[pos], ids, scale, tol, where))
        if whole.glob_names:
            w = whole.globals(step)
            for p in pieces:
                v = p.globals(step)
                if len(v) != len(w):
                    fail(f"{p.path}: {at}: {len(v)} global values, the whole file has {len(w)}")
                for i, name in enumerate(whole.glob_names):
                    worst = max(worst, difference(v[i: i + 1], w[i: i + 1], [i + 1], abs(w[i]), tol,
                                                  f"{p.path}: {at}: global {name}, variable"))

    nvars = len(whole.nodal_names) + len(whole.elem_names) + len(whole.glob_names)
    print(f"check_exodus_pieces: {P} pieces, {whole.num_nodes} nodes, {whole.num_elem} elements, "
          f"{len(whole.times)} steps, {nvars} variables agree (largest relative difference {worst:.3e})")


if __name__ == "__main__":
    main()
