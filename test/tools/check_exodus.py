#!/usr/bin/python3
"""check_exodus.py RESULT_DIR: the Exodus II results of a ddcontact run
(RESULT_DIR/results.e, Output/Exodus = true) read back by independent
readers and compared with the run's other outputs.

- VTK's vtkExodusIIReader (Debian python3-vtk9): one element block per body
  with the body's name, the node sets and side sets, the variables, one time
  step per history.csv row at its load factor (or time); at every step the
  displacements (and velocities/accelerations) and the element stresses,
  von Mises and strain-energy density equal those of the VTK output
  (RESULT_DIR/vtk, written with Output/VTK Interval = 1) at the same
  reference points and cell centres, and the global strain_energy equals
  history.csv's, to 1e-12 relative to each field's largest value (both
  outputs hold the same doubles; the tolerance is the ASCII round trip);
- meshio (Debian python3-meshio): the points, the cells per block, the point
  sets and the variable names.

Exit status 0 when everything agrees; 1 with the first mismatch named.
"""
import csv
import math
import os
import sys

import meshio
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

# Equal doubles written by two writers: relative to the field's largest value.
SAME_VALUES = 1e-12
# vtkExodusIIReader returns the coordinates in single precision: points and
# cell centres match to this fraction of the mesh's extent.
SAME_POINT = 1e-6


def fail(msg):
    print("check_exodus: " + msg, file=sys.stderr)
    sys.exit(1)


def nearest(points, queries, what):
    """Index of the point nearest to each query; fails beyond SAME_POINT."""
    points = np.asarray(points, dtype=float)
    extent = float(np.max(np.ptp(points, axis=0))) if len(points) else 1.0
    out = np.empty(len(queries), dtype=int)
    for i, q in enumerate(np.asarray(queries, dtype=float)):
        d = np.max(np.abs(points - q), axis=1)
        j = int(np.argmin(d))
        if d[j] > SAME_POINT * extent:
            fail(f"{what} {q} has no counterpart in the Exodus file (nearest {d[j]:.3e} away)")
        out[i] = j
    return out


def close(a, b, scale, what):
    err = float(np.max(np.abs(np.asarray(a) - np.asarray(b)))) if len(a) else 0.0
    if err > SAME_VALUES * max(scale, 1e-300):
        fail(f"{what}: differs by {err:.3e} (largest value {scale:.3e})")
    return err


def array_name(names, want):
    """VTK's reader joins displ_x, displ_y, ... into one vector named 'displ_'."""
    for n in names:
        if n.rstrip("_") == want:
            return n
    return None


def blocks(multiblock):
    """The unstructured grids of the element blocks, in order, with names."""
    out = []
    eb = multiblock.GetBlock(0)  # vtkExodusIIReader: block 0 = element blocks
    for i in range(eb.GetNumberOfBlocks()):
        out.append((eb.GetMetaData(i).Get(vtk.vtkCompositeDataSet.NAME()), eb.GetBlock(i)))
    return out


def cell_point_ids(grid):
    """Every cell's point indices in the cell's (VTK) order."""
    ids = vtk.vtkIdList()
    out = []
    for c in range(grid.GetNumberOfCells()):
        grid.GetCellPoints(c, ids)
        out.append(np.array([ids.GetId(i) for i in range(ids.GetNumberOfIds())], dtype=int))
    return out


def cell_centres(grid):
    f = vtk.vtkCellCenters()
    f.SetInputData(grid)
    f.Update()
    return vtk_to_numpy(f.GetOutput().GetPoints().GetData())


def main():
    if len(sys.argv) != 2:
        fail("usage: check_exodus.py RESULT_DIR")
    d = sys.argv[1]
    path = os.path.join(d, "results.e")
    rows = list(csv.DictReader(open(os.path.join(d, "history.csv"))))
    if not rows:
        fail("history.csv has no rows")
    dynamic = "time" in rows[0]

    r = vtk.vtkExodusIIReader()
    r.SetFileName(path)
    r.UpdateInformation()
    r.ApplyDisplacementsOff()  # reference coordinates, like the VTK output
    for t in (r.ELEM_BLOCK, r.NODE_SET, r.SIDE_SET):
        for i in range(r.GetNumberOfObjects(t)):
            r.SetObjectStatus(t, i, 1)
    for t in (r.NODAL, r.ELEM_BLOCK, r.GLOBAL):
        for i in range(r.GetNumberOfObjectArrays(t)):
            r.SetObjectArrayStatus(t, r.GetObjectArrayName(t, i), 1)
    times = r.GetOutputInformation(0).Get(vtk.vtkStreamingDemandDrivenPipeline.TIME_STEPS())
    if times is None or len(times) != len(rows):
        fail(f"{path}: {0 if times is None else len(times)} time steps, history.csv has {len(rows)} rows")
    for t, row in zip(times, rows):
        if not math.isclose(t, float(row["load_factor"]), rel_tol=1e-15, abs_tol=0):
            fail(f"{path}: time {t} where history.csv has load_factor {row['load_factor']}")
    nodal = [r.GetObjectArrayName(r.NODAL, i) for i in range(r.GetNumberOfObjectArrays(r.NODAL))]
    elem = [r.GetObjectArrayName(r.ELEM_BLOCK, i) for i in range(r.GetNumberOfObjectArrays(r.ELEM_BLOCK))]
    glob = [r.GetObjectArrayName(r.GLOBAL, i) for i in range(r.GetNumberOfObjectArrays(r.GLOBAL))]
    vectors = {}
    for want in ["displ"] + (["vel", "acc"] if dynamic else []):
        vectors[want] = array_name(nodal, want)
        if vectors[want] is None:
            fail(f"{path}: no nodal vector '{want}' (has {nodal})")
    # Contact: gap and pressure at the slave nodes, like the VTK output's.
    for want in ["contact_gap", "contact_pressure"]:
        if want in nodal:
            vectors[want] = want
    stress_name = array_name(elem, "stress")
    for want in ["von_mises", "strain_energy_density"]:
        if want not in elem:
            fail(f"{path}: no element variable '{want}' (has {elem})")
    for want in ["strain_energy", "external_work", "active_contacts"]:
        if want not in glob:
            fail(f"{path}: no global variable {want} (has {glob})")
    if array_name(glob, "contact_force") is None:
        fail(f"{path}: no global vector contact_force (has {glob})")
    names = [r.GetObjectName(r.ELEM_BLOCK, i) for i in range(r.GetNumberOfObjects(r.ELEM_BLOCK))]
    print(f"{path}: {len(times)} steps; blocks {names}; {r.GetNumberOfObjects(r.NODE_SET)} node sets, "
          f"{r.GetNumberOfObjects(r.SIDE_SET)} side sets; nodal {nodal}; element {elem}; global {glob}")

    worst = 0.0
    compared = []  # steps with VTK output
    for k, t in enumerate(times):
        if k == 0:
            r.SetTimeStep(0)
            r.Update()
            # The global variables (every step's, in the field data) against history.csv.
            fd = r.GetOutput().GetBlock(0).GetBlock(0).GetFieldData()
            for name in ["strain_energy", "external_work", "active_contacts"] + (["kinetic_energy"] if dynamic else []):
                a = fd.GetArray(name)
                if a is None or a.GetNumberOfTuples() != len(rows):
                    fail(f"{path}: global {name}: not one value per step")
                h = [float(row[name]) for row in rows]
                worst = max(worst, close([a.GetValue(i) for i in range(len(rows))], h, max(map(abs, h)),
                                         f"global {name} against history.csv"))
            f = fd.GetArray(array_name(glob, "contact_force"))
            for c, axis in enumerate("xyz"[: f.GetNumberOfComponents()]):
                h = [float(row["contact_force_" + axis]) for row in rows]
                worst = max(worst, close([f.GetComponent(i, c) for i in range(len(rows))], h, max(map(abs, h)) or 1.0,
                                         f"global contact_force_{axis} against history.csv"))
        # The VTK output of the same step (Output/VTK Interval may skip some).
        pvtu = os.path.join(d, "vtk", f"step_{k + 1:05d}.pvtu")
        if not os.path.exists(pvtu):
            continue
        compared.append(k + 1)
        r.SetTimeStep(k)
        r.Update()
        # The Exodus blocks, concatenated: points, nodal vectors, cells (as
        # lists of point indices), element values.
        pts, vecs, cells, centres, stress, vm, w = [], {n: [] for n in vectors}, [], [], [], [], []
        for name, g in blocks(r.GetOutput()):
            offset = sum(len(p) for p in pts)
            pts.append(vtk_to_numpy(g.GetPoints().GetData()))
            for n, a in vectors.items():
                vecs[n].append(vtk_to_numpy(g.GetPointData().GetArray(a)))
            cells += [c + offset for c in cell_point_ids(g)]
            centres.append(cell_centres(g))
            cd = g.GetCellData()
            if stress_name:
                stress.append(vtk_to_numpy(cd.GetArray(stress_name)))
            vm.append(vtk_to_numpy(cd.GetArray("von_mises")))
            w.append(vtk_to_numpy(cd.GetArray("strain_energy_density")))
        pts, centres, vm, w = np.concatenate(pts), np.concatenate(centres), np.concatenate(vm), np.concatenate(w)
        vecs = {n: np.concatenate(v) for n, v in vecs.items()}
        stress = np.concatenate(stress) if stress else None

        pv = vtk.vtkXMLPUnstructuredGridReader()
        pv.SetFileName(pvtu)
        pv.Update()
        g = pv.GetOutput()
        g_pts = vtk_to_numpy(g.GetPoints().GetData())
        g_cells = cell_point_ids(g)
        # Cells match by their centres (two bodies' cells never share one,
        # where their nodes may); points match through the cells, so the
        # coincident nodes of two bodies in contact keep apart.
        idx = nearest(centres, cell_centres(g), f"step {k + 1}: VTK cell centre")
        extent = float(np.max(np.ptp(pts, axis=0)))
        ours, theirs = [], []
        for c, mine in enumerate(g_cells):
            other = cells[idx[c]]
            # The element node order: after the reader's conversion to VTK's
            # order, the cell lists the VTK output's points in the same order.
            if len(other) != len(mine) or np.max(np.abs(pts[other] - g_pts[mine])) > SAME_POINT * extent:
                fail(f"step {k + 1}: cell {c}: its points are not in the VTK output's order: element node order")
            ours.append(mine)
            theirs.append(other)
        ours, theirs = np.concatenate(ours), np.concatenate(theirs)
        fields = {"displ": "displacement", "vel": "velocity", "acc": "acceleration", "contact_gap": "contact_gap",
                  "contact_pressure": "contact_pressure"}
        for ex_name, vtk_name in fields.items():
            if ex_name not in vectors:
                continue
            arr = g.GetPointData().GetArray(vtk_name)
            if arr is None:
                fail(f"step {k + 1}: the VTK output has no {vtk_name}")
            v = vtk_to_numpy(arr).reshape(arr.GetNumberOfTuples(), -1)
            a = vecs[ex_name][theirs].reshape(len(theirs), -1)
            b = v[ours][:, : a.shape[1]]
            worst = max(worst, close(a.ravel(), b.ravel(), float(np.max(np.abs(v))) if v.size else 0,
                                     f"step {k + 1}: nodal {ex_name}"))
        cs = vtk_to_numpy(g.GetCellData().GetArray("cauchy_stress"))
        g_vm = vtk_to_numpy(g.GetCellData().GetArray("von_mises_stress"))
        g_w = vtk_to_numpy(g.GetCellData().GetArray("strain_energy_density"))
        if stress is not None:
            a = stress[idx]
            worst = max(worst, close(a.ravel(), cs[:, : a.shape[1]].ravel(), float(np.max(np.abs(cs))),
                                     f"step {k + 1}: element stress"))
        worst = max(worst, close(vm[idx], g_vm, float(np.max(np.abs(g_vm))), f"step {k + 1}: von Mises"))
        worst = max(worst, close(w[idx], g_w, float(np.max(np.abs(g_w))), f"step {k + 1}: strain-energy density"))

    # Side numbering: each side set's faces lie on the node set of the same
    # name (the mesh defines one per side set), so a wrong side number (a
    # face across the element) shows.
    r.SetTimeStep(0)
    r.Update()
    out = r.GetOutput()
    groups = {out.GetMetaData(i).Get(vtk.vtkCompositeDataSet.NAME()): out.GetBlock(i) for i in range(out.GetNumberOfBlocks())}
    node_sets = {groups["Node Sets"].GetMetaData(j).Get(vtk.vtkCompositeDataSet.NAME()): groups["Node Sets"].GetBlock(j)
                 for j in range(groups["Node Sets"].GetNumberOfBlocks())}
    side_sets = groups["Side Sets"]
    if side_sets.GetNumberOfBlocks() != r.GetNumberOfObjects(r.SIDE_SET) or not side_sets.GetNumberOfBlocks():
        fail(f"{path}: {side_sets.GetNumberOfBlocks()} side sets read")
    for j in range(side_sets.GetNumberOfBlocks()):
        name = side_sets.GetMetaData(j).Get(vtk.vtkCompositeDataSet.NAME())
        faces = side_sets.GetBlock(j)
        ns = node_sets.get(name)
        if ns is None:
            fail(f"{path}: side set '{name}' has no node set of the same name")
        nearest(vtk_to_numpy(ns.GetPoints().GetData()), vtk_to_numpy(faces.GetPoints().GetData()),
                f"side set '{name}': a face point off the node set (side numbering?):")
    if not compared:
        fail(f"{d}/vtk has none of the steps (Output/VTK must be true)")
    print(f"vtkExodusIIReader: {len(times)} steps equal to history.csv, {len(compared)} of them to the VTK output "
          f"(largest difference {worst:.3e})")

    m = meshio.read(path)
    ncells = sum(len(c.data) for c in m.cells)
    pts_vtk = vtk.vtkXMLPUnstructuredGridReader()
    pts_vtk.SetFileName(os.path.join(d, "vtk", f"step_{compared[0]:05d}.pvtu"))
    pts_vtk.Update()
    if ncells != pts_vtk.GetOutput().GetNumberOfCells():
        fail(f"meshio: {ncells} cells, the VTK output has {pts_vtk.GetOutput().GetNumberOfCells()}")
    if len(m.cells) != len(names):
        fail(f"meshio: {len(m.cells)} cell blocks for {len(names)} bodies")
    if "displ_x" not in m.point_data:
        fail(f"meshio: no point data displ_x (has {list(m.point_data)})")
    print(f"meshio: {len(m.points)} points, {ncells} cells in {len(m.cells)} blocks, point sets "
          f"{sorted(m.point_sets)}")


if __name__ == "__main__":
    main()
