#!/usr/bin/python3
"""incline_check.py RESULT_DIR stick|slide [--slip-tolerance R] [--tolerance R]:
checks a run of examples/incline_block.xml (doc/contact.md, "Incline"), a
block on a held plane y = 0 under gravity g = (g_x, g_y), g_y < 0, with one
frictional contact pair of coefficient mu. Read from the run's own
outputs: parameters.xml (the deck as run: the gravity of body 'Block', the
pair's Friction Coefficient, no initial velocity), results.e (Output/Exodus:
the displacements of every step) and history.csv.

- stick: every slave node of 'Block/bottom' keeps its x displacement
  relative to the plane's top (the mean over 'Plane/top') below
  R (default 1e-8) times the block's length, at every step;
- slide: the block's centre of mass (its Quad4 cells' centroids, area
  weighted) follows x(t) = a t^2 / 2: a, fitted by least squares over every
  step, is within R (default 1 %) of Coulomb's g_x + mu g_y
  (= g (sin theta - mu cos theta)), and at the last step total_energy +
  frictional_dissipation equals the initial energy (0: at rest, unstrained)
  plus external_work within R of external_work.

Prints the measured values; exit status 0 when the checks pass, 1 when one
fails, 2 on bad usage or unreadable results.
"""
import argparse
import csv
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
from netCDF4 import Dataset, chartostring


def bad(msg):
    print("incline_check: " + msg, file=sys.stderr)
    sys.exit(2)


def sublist(node, name):
    for s in node.findall("ParameterList"):
        if s.get("name") == name:
            return s
    return None


def value(node, name, default=None):
    for p in node.findall("Parameter"):
        if p.get("name") == name:
            return p.get("value")
    return default


def deck(path):
    """(g_x, g_y, mu) of the deck as run."""
    root = ET.parse(path).getroot()
    dyn = sublist(root, "Dynamics")
    if dyn is None:
        bad(f"{path} has no Dynamics")
    if sublist(dyn, "Initial Velocity") is not None and len(sublist(dyn, "Initial Velocity")):
        bad(f"{path} has an initial velocity; the energy check assumes the block starts at rest")
    g = np.zeros(2)
    grav = sublist(dyn, "Gravity")
    for field in [] if grav is None else grav.findall("ParameterList"):
        if value(field, "Set") == "Block":
            g += [float(value(field, "Acceleration X", 0)), float(value(field, "Acceleration Y", 0))]
    if not g[1] < 0:
        bad(f"{path}: no gravity on body 'Block' pressing it onto the plane (Acceleration Y < 0)")
    pairs = sublist(sublist(root, "Contact"), "Pairs")
    mus = [float(value(p, "Friction Coefficient", 0)) for p in pairs.findall("ParameterList")]
    if len(mus) != 1:
        bad(f"{path}: expected one contact pair, found {len(mus)}")
    return g[0], g[1], mus[0]


def names(ds, var):
    return [str(s) for s in chartostring(ds.variables[var][:])]


def exodus(path):
    """times, displacements (steps x nodes x 2), block cells, slave nodes, plane-top nodes."""
    ds = Dataset(path)
    t = np.array(ds.variables["time_whole"][:])
    nod = names(ds, "name_nod_var")
    try:
        ux = np.array(ds.variables[f"vals_nod_var{nod.index('displ_x') + 1}"][:])
        uy = np.array(ds.variables[f"vals_nod_var{nod.index('displ_y') + 1}"][:])
    except ValueError:
        bad(f"{path} has no displ_x / displ_y (nodal variables: {nod})")
    eb = names(ds, "eb_names")
    if "Block" not in eb:
        bad(f"{path} has no element block 'Block' ({eb})")
    cells = np.array(ds.variables[f"connect{eb.index('Block') + 1}"][:]) - 1
    ns = names(ds, "ns_names")
    sets = {}
    for want in ("Block/bottom", "Plane/top"):
        if want not in ns:
            bad(f"{path} has no node set '{want}' ({ns})")
        sets[want] = np.array(ds.variables[f"node_ns{ns.index(want) + 1}"][:]) - 1
    x = np.array(ds.variables["coordx"][:])
    y = np.array(ds.variables["coordy"][:])
    return t, np.stack([ux, uy], axis=-1), cells, sets["Block/bottom"], sets["Plane/top"], np.stack([x, y], -1)


def history(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for col in ("time", "total_energy", "external_work", "frictional_dissipation"):
        if not rows or col not in rows[0]:
            bad(f"{path} has no column '{col}'")
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("mode", choices=["stick", "slide"])
    ap.add_argument("--slip-tolerance", type=float, default=1e-8)
    ap.add_argument("--tolerance", type=float, default=0.01)
    a = ap.parse_args()
    for f in ("parameters.xml", "results.e", "history.csv"):
        if not os.path.exists(os.path.join(a.dir, f)):
            bad(f"{a.dir} has no {f}")
    gx, gy, mu = deck(os.path.join(a.dir, "parameters.xml"))
    t, u, cells, slaves, plane, X = exodus(os.path.join(a.dir, "results.e"))
    length = np.ptp(X[np.unique(cells), 0])
    ok = True
    if a.mode == "stick":
        rel = u[:, slaves, 0] - u[:, plane, 0].mean(axis=1)[:, None]
        slip = np.abs(rel).max() / length
        ok = slip < a.slip_tolerance
        # For the report only: the slip over the second half of the run
        # (after the normal contact settled).
        half = t >= 0.5 * t[-1]
        late = np.abs(rel[half] - rel[half][0]).max() / length
        print(f"incline stick: g = ({gx}, {gy}), mu = {mu}, tan theta / mu = {-gx / gy / mu:.4f}; "
              f"max |slip| / length over {len(t)} steps = {slip:.3e} "
              f"(<= {a.slip_tolerance}: {'passed' if ok else 'FAILED'}); over t >= {t[half][0]:g}: {late:.3e}")
        return 0 if ok else 1
    # Centre of mass: Quad4 cell centroids weighted by the cells' areas.
    def area(c):
        p = X[c]
        return 0.5 * abs(np.dot(p[:, 0], np.roll(p[:, 1], -1)) - np.dot(p[:, 1], np.roll(p[:, 0], -1)))
    w = np.array([area(c) for c in cells])
    xcm = (u[:, cells, 0].mean(axis=2) * w).sum(axis=1) / w.sum()
    fit = np.dot(xcm, t**2) / (0.5 * np.dot(t**2, t**2))
    exact = gx + mu * gy
    err = fit / exact - 1.0
    ok_a = abs(err) <= a.tolerance
    rows = history(os.path.join(a.dir, "history.csv"))
    last = rows[-1]
    total, work, diss = (float(last[c]) for c in ("total_energy", "external_work", "frictional_dissipation"))
    balance = (total + diss - work) / work
    ok_e = abs(balance) <= a.tolerance
    print(f"incline slide: g = ({gx}, {gy}), mu = {mu}, tan theta / mu = {-gx / gy / mu:.4f}; "
          f"fitted a = {fit:.6g} over {len(t)} steps, Coulomb's {exact:.6g}: error {100 * err:+.4f} % "
          f"(<= {100 * a.tolerance:g} %: {'passed' if ok_a else 'FAILED'})")
    print(f"incline energy at t = {float(last['time']):g}: total {total:.6g} + frictional dissipation {diss:.6g} "
          f"- external work {work:.6g} = {100 * balance:+.4f} % of the work "
          f"(<= {100 * a.tolerance:g} %: {'passed' if ok_e else 'FAILED'})")
    return 0 if ok_a and ok_e else 1


if __name__ == "__main__":
    sys.exit(main())
