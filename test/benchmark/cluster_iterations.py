#!/usr/bin/python3
"""Dual iterations of FETI-DP, clusters of subdomains and total FETI, on a model problem.

A study, not a solver: how many dual iterations subdomains grouped into
clusters cost (hybrid total FETI, HTFETI: the primal nodes inside a cluster
make that cluster's coarse problem; the clusters are glued by Lagrange
multipliers on every DOF they share, their primal nodes included; each
floating cluster's rigid-body modes enter the natural coarse problem G^T G,
G = B R), and total FETI (clusters of one subdomain, no primal DOFs),
against FETI-DP on the same subdomains, measured before any of it is built
into the solver (doc/performance.md, "Clusters and total FETI: the
iterations, measured on a model problem").

The model: the unit cube of (k H)^3 trilinear hexahedra, linear elasticity
(E = 1, nu = 0.3), clamped at x = 0, a unit body force in -z; k^3 cube
subdomains of H^3 elements; primal nodes by the solver's rule or the
subdomain corners alone (--primal); clusters of c^3 subdomains (c = k is
FETI-DP, c = 1 total FETI). All use fully redundant multipliers,
multiplicity scaling and the Dirichlet preconditioner, and count the CG
iterations until the (projected) dual residual has fallen by each
tolerance. Each solution is checked against the assembled problem (the
relative residual of K u = f) and each kernel against its cluster's matrix.

Prints a markdown table; needs python3-scipy (Debian, cmake/setup.sh).

    /usr/bin/python3 test/benchmark/cluster_iterations.py --k 8 --H 4 --c 1 2 4 [--primal corners]
"""
import argparse
import itertools
import sys

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla

E, NU = 1.0, 0.3


def hex8_stiffness():
    """The 24x24 stiffness of a unit cube element; node a = i + 2 j + 4 k."""
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    mu = E / (2 * (1 + NU))
    D = np.zeros((6, 6))
    D[:3, :3] = lam
    D[range(3), range(3)] += 2 * mu
    D[3:, 3:] = mu * np.eye(3)
    s = np.array([[i, j, k] for k in (0, 1) for j in (0, 1) for i in (0, 1)]) * 2 - 1
    g = 1 / np.sqrt(3)
    K = np.zeros((24, 24))
    for p in itertools.product((-g, g), repeat=3):
        dN = np.empty((8, 3))
        for a in range(8):
            f = [(1 + s[a, d] * p[d]) for d in range(3)]
            for d in range(3):
                o = [f[e] for e in range(3) if e != d]
                dN[a, d] = s[a, d] * o[0] * o[1] / 8 * 2  # d/dx = 2 d/dxi (h = 1)
        B = np.zeros((6, 24))
        for a in range(8):
            x, y, z = dN[a]
            B[0, 3 * a], B[1, 3 * a + 1], B[2, 3 * a + 2] = x, y, z
            B[3, 3 * a], B[3, 3 * a + 1] = y, x
            B[4, 3 * a + 1], B[4, 3 * a + 2] = z, y
            B[5, 3 * a], B[5, 3 * a + 2] = z, x
        K += B.T @ D @ B / 8  # det J = (1/2)^3
    return K


class Model:
    def __init__(self, k, H, primal="edges"):
        self.k, self.H, self.n = k, H, k * H
        n1 = self.n + 1
        self.nn = n1**3
        m = H + 1
        # the subdomain matrix (identical for all subdomains)
        Ke = hex8_stiffness()
        loc = lambda i, j, l: i + m * (j + m * l)
        rows, cols, vals = [], [], []
        for ei, ej, el in itertools.product(range(H), repeat=3):
            nodes = [loc(ei + a % 2, ej + (a // 2) % 2, el + a // 4) for a in range(8)]
            dofs = np.array([3 * q + d for q in nodes for d in range(3)])
            rows.append(np.repeat(dofs, 24))
            cols.append(np.tile(dofs, 24))
            vals.append(Ke.ravel())
        self.Ks = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                                shape=(3 * m**3, 3 * m**3))
        # per subdomain: its global node ids, in local order
        li = np.array([(i, j, l) for l in range(m) for j in range(m) for i in range(m)])
        self.subs = []
        for a, b, c in itertools.product(range(k), repeat=3):
            ijk = li + np.array([a * H, b * H, c * H])
            self.subs.append(dict(box=(a, b, c), ijk=ijk, node=ijk[:, 0] + n1 * (ijk[:, 1] + n1 * ijk[:, 2])))
        # a node's multiplicity; fixed: x = 0; primal: the primal nodes (--primal)
        self.mult = np.zeros(self.nn, int)
        for s in self.subs:
            self.mult[s["node"]] += 1
        g = np.arange(self.nn)
        self.xyz = np.stack([g % n1, (g // n1) % n1, g // n1**2], axis=1).astype(float)
        self.fixed = self.xyz[:, 0] == 0
        if primal == "corners":
            self.primal = np.all(self.xyz % H == 0, axis=1) & ~self.fixed
        else:  # the solver's rule: shared by >= 3 subdomains, or by 2 on the mesh boundary
            outer = np.any((self.xyz == 0) | (self.xyz == self.n), axis=1)
            self.primal = ((self.mult >= 3) | ((self.mult == 2) & outer)) & ~self.fixed
        # the load: a unit body force in -z, lumped to the nodes
        self.f = np.zeros(3 * self.nn)
        w = np.zeros(self.nn)
        for s in self.subs:
            ijk = s["ijk"] - np.array(s["box"]) * H
            cnt = np.prod(np.where((ijk == 0) | (ijk == H), 1, 2), axis=1)  # elements of s touching the node
            w[s["node"]] += cnt / 8
        self.f[2::3] = -w

    def assembled(self):
        rows, cols, vals = [], [], []
        Kc = self.Ks.tocoo()
        for s in self.subs:
            d = 3 * s["node"][Kc.row // 3] + Kc.row % 3
            e = 3 * s["node"][Kc.col // 3] + Kc.col % 3
            rows.append(d), cols.append(e), vals.append(Kc.data)
        return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                             shape=(3 * self.nn, 3 * self.nn))


def solve(model, cluster_size, tols, dirichlet=True, maxit=1000):
    """FETI-DP (cluster_size = k: one cluster) or clusters of cluster_size^3 subdomains."""
    M, k = model, model.k
    ncl = k // cluster_size
    cl_of = lambda box: (box[0] // cluster_size) + ncl * ((box[1] // cluster_size) + ncl * (box[2] // cluster_size))
    # the partially assembled space: a subdomain's own copy of each non-primal
    # DOF, a cluster's copy of each primal DOF
    ncols = 0
    primal_col = {}  # (cluster, node) -> first column
    col_of = []      # per subdomain: column of each local DOF (-1: fixed)
    owner = []       # per column: subdomain (>= 0) or -1 - cluster
    col_node = []
    for si, s in enumerate(M.subs):
        c = cl_of(s["box"])
        cols = np.full(3 * len(s["node"]), -1)
        for q, g in enumerate(s["node"]):
            if M.fixed[g]:
                continue
            if M.primal[g]:
                key = (c, g)
                if key not in primal_col:
                    primal_col[key] = ncols
                    ncols += 3
                    owner += [-1 - c] * 3
                    col_node += [g] * 3
                cols[3 * q:3 * q + 3] = primal_col[key] + np.arange(3)
            else:
                cols[3 * q:3 * q + 3] = ncols + np.arange(3)
                ncols += 3
                owner += [si] * 3
                col_node += [g] * 3
        col_of.append(cols)
    owner, col_node = np.array(owner), np.array(col_node)
    col_cluster = np.array([cl_of(M.subs[o]["box"]) if o >= 0 else -1 - o for o in owner])
    # K~ and f~ (f at each copy divided by the copies: the sum is f)
    Kc = M.Ks.tocoo()
    rows, cols_, vals = [], [], []
    for si, s in enumerate(M.subs):
        cm = col_of[si]
        keep = (cm[Kc.row] >= 0) & (cm[Kc.col] >= 0)
        rows.append(cm[Kc.row[keep]]), cols_.append(cm[Kc.col[keep]]), vals.append(Kc.data[keep])
    Kt = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols_))), shape=(ncols, ncols))
    copies = np.zeros(3 * M.nn)
    for d in range(3):
        np.add.at(copies, 3 * col_node[d::3] + d, 1)
    gdof = 3 * col_node + np.tile(np.arange(3), ncols // 3)
    ft = M.f[gdof] / copies[gdof]
    # B: fully redundant, one row per pair of copies of a DOF
    by_dof = {}
    for j in range(ncols):
        by_dof.setdefault(gdof[j], []).append(j)
    br, bc, bv, bd = [], [], [], []
    nl = 0
    for g, cs in by_dof.items():
        m = len(cs)
        for a, b in itertools.combinations(cs, 2):
            br += [nl, nl]
            bc += [a, b]
            bv += [1.0, -1.0]
            bd += [1.0 / m, -1.0 / m]
            nl += 1
    B = sp.csr_matrix((bv, (br, bc)), shape=(nl, ncols))
    BD = sp.csr_matrix((bd, (br, bc)), shape=(nl, ncols))
    # floating clusters: rigid-body modes R, and 6 DOFs fixed for a generalised inverse
    Rcols, fixdofs = [], []
    for c in range(ncl**3):
        js = np.nonzero(col_cluster == c)[0]
        touches = any(M.fixed[s["node"]].any() for s in M.subs if cl_of(s["box"]) == c)
        if touches:
            continue
        X = M.xyz[col_node[js]] - M.xyz[col_node[js]].mean(axis=0)
        d = np.tile(np.arange(3), len(js) // 3)
        Rc = np.zeros((len(js), 6))
        for t in range(3):
            Rc[d == t, t] = 1
        x, y, z = X[:, 0], X[:, 1], X[:, 2]
        Rc[d == 1, 3], Rc[d == 2, 3] = -z[d == 1], y[d == 2]
        Rc[d == 0, 4], Rc[d == 2, 4] = z[d == 0], -x[d == 2]
        Rc[d == 0, 5], Rc[d == 1, 5] = -y[d == 0], x[d == 1]
        Rc, _ = np.linalg.qr(Rc)
        prim = np.nonzero(owner[js] < 0)[0]  # fix 6 of the cluster's primal DOFs
        _, _, piv = la.qr(Rc[prim].T, pivoting=True)
        fixdofs += list(js[prim[piv[:6]]])
        R = sp.csc_matrix((Rc.ravel(), (np.repeat(js, 6), np.tile(np.arange(6), len(js)))), shape=(ncols, 6))
        Rcols.append(R)
    fixdofs = np.array(fixdofs, int)
    R = sp.hstack(Rcols).tocsc() if Rcols else sp.csc_matrix((ncols, 0))
    kernel_residual = spla.norm(Kt @ R) / spla.norm(Kt) if R.shape[1] else 0.0
    # K^+ by condensation on the primal columns, as FETI-DP applies K~^{-1}:
    # per subdomain K_rr (dense; subdomains of one pattern share it), the
    # primal problem sum_s S_PiPi^s, with the fixed DOFs' rows and columns
    # replaced by the identity
    groups = {}
    for si, s in enumerate(M.subs):
        cm = col_of[si]
        loc = np.nonzero(cm >= 0)[0]
        rl, pl = loc[owner[cm[loc]] >= 0], loc[owner[cm[loc]] < 0]
        key = (rl.tobytes(), pl.tobytes())
        groups.setdefault(key, (rl, pl, []))[2].append(cm)
    Kd = M.Ks.toarray()
    parts = []
    srow, scol, sval = [], [], []
    for rl, pl, cms in groups.values():
        cms = np.array(cms).T  # local DOF x subdomain
        Krr = la.cho_factor(Kd[np.ix_(rl, rl)])
        KrP = Kd[np.ix_(rl, pl)]
        S = Kd[np.ix_(pl, pl)] - KrP.T @ la.cho_solve(Krr, KrP)
        Rc_, Pc_ = cms[rl], cms[pl]
        parts.append((Krr, KrP, Rc_, Pc_))
        for b in range(Pc_.shape[1]):
            srow.append(np.repeat(Pc_[:, b], len(pl))), scol.append(np.tile(Pc_[:, b], len(pl)))
            sval.append(S.ravel())
    pcols = np.nonzero(owner < 0)[0]
    pidx = np.full(ncols, -1)
    pidx[pcols] = np.arange(len(pcols))
    Sc = sp.csr_matrix((np.concatenate(sval), (pidx[np.concatenate(srow)], pidx[np.concatenate(scol)])),
                       shape=(len(pcols), len(pcols)))
    keep = np.ones(len(pcols))
    keep[pidx[fixdofs]] = 0
    Dk = sp.diags(keep)
    coarse = spla.splu((Dk @ Sc @ Dk + sp.diags(1 - keep)).tocsc(), permc_spec="MMD_AT_PLUS_A")

    def Kplus(v):
        out = np.zeros(ncols)
        g = v[pcols].copy()
        ys = []
        for Krr, KrP, Rc_, Pc_ in parts:
            y = la.cho_solve(Krr, v[Rc_])
            np.add.at(g, pidx[Pc_], -(KrP.T @ y))
            ys.append(y)
        up = keep * coarse.solve(keep * g)
        out[pcols] = up
        for (Krr, KrP, Rc_, Pc_), y in zip(parts, ys):
            out[Rc_] = y - la.cho_solve(Krr, KrP @ up[pidx[Pc_]])
        return out

    F = lambda lam: B @ Kplus(B.T @ lam)
    d = B @ Kplus(ft)
    # the Dirichlet preconditioner: per subdomain, S on the DOFs with rows
    # (its dual DOFs, and the primal DOFs its cluster shares with another)
    has_rows = np.diff(BD.tocsc().indptr) > 0
    blocks, allcols = [], []
    for si, s in enumerate(M.subs):
        cm = col_of[si]
        loc = np.nonzero(cm >= 0)[0]
        rowed = has_rows[cm[loc]]
        interior = M.mult[s["node"][loc // 3]] == 1
        Dl, Il = loc[rowed], loc[interior & ~rowed]
        K = M.Ks
        KII = K[Il][:, Il].toarray()
        KID = K[Il][:, Dl].toarray()
        S = K[Dl][:, Dl].toarray() - KID.T @ la.solve(KII, KID, assume_a="pos")
        # A cluster's primal column is shared by its subdomains there: each
        # applies the whole jump and the reactions add up, as in the
        # cluster's own (partially assembled) Schur complement. Splitting
        # the entry over them (weights 1/n) took 3 times the iterations.
        blocks.append(S), allcols.append(cm[Dl])
    offsets = np.cumsum([0] + [len(x) for x in allcols])
    Bcat = BD[:, np.concatenate(allcols)].tocsr()
    BcatT = Bcat.T.tocsr()

    def precond(r):
        if not dirichlet:
            return r.copy()
        v = BcatT @ r
        y = np.empty_like(v)
        for b, S in enumerate(blocks):
            y[offsets[b]:offsets[b + 1]] = S @ v[offsets[b]:offsets[b + 1]]
        return Bcat @ y

    G = (B @ R).tocsc()
    if G.shape[1]:
        GtG = la.cho_factor((G.T @ G).toarray())
        natural = spla.splu((G.T @ G).tocsc(), permc_spec="MMD_AT_PLUS_A")
        P = lambda v: v - G @ la.cho_solve(GtG, G.T @ v)
        e = R.T @ ft
        lam = G @ la.cho_solve(GtG, e)
    else:
        P = lambda v: v
        lam = np.zeros(nl)
    r = P(d - F(lam))
    r0 = np.linalg.norm(r)
    z = P(precond(r))
    p = z.copy()
    rz = r @ z
    its = 0
    reached = {}  # tolerance -> the iteration that met it
    while its < maxit:
        for t in tols:
            if t not in reached and np.linalg.norm(r) <= t * r0:
                reached[t] = its
        if len(reached) == len(tols):
            break
        q = P(F(p))
        a = rz / (p @ q)
        lam += a * p
        r -= a * q
        z = P(precond(r))
        rz, rz_old = r @ z, rz
        p = z + rz / rz_old * p
        its += 1
    # the solution, and its residual in the assembled problem
    res = d - F(lam)
    alpha = -la.cho_solve(GtG, G.T @ res) if G.shape[1] else np.zeros(0)
    u = Kplus(ft - B.T @ lam) + R @ alpha
    ug = np.zeros(3 * M.nn)
    np.add.at(ug, gdof, u / copies[gdof])
    jump = np.linalg.norm(B @ u) / np.linalg.norm(u)
    # the problem every rank would share: S_PiPi for FETI-DP, G^T G for clusters
    glob = natural if G.shape[1] else coarse
    coarse_dofs = G.shape[1] if G.shape[1] else len(pcols)
    return dict(coarse_dofs=coarse_dofs, coarse_factor=glob.L.nnz, its=[reached.get(t, -1) for t in tols], nl=nl,
                floating=R.shape[1] // 6, u=ug, jump=jump, kernel=kernel_residual)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--k", type=int, default=8, help="subdomains per direction")
    ap.add_argument("--H", type=int, default=4, help="elements per subdomain and direction")
    ap.add_argument("--c", type=int, nargs="+", default=[1, 2, 4], help="subdomains per cluster and direction")
    ap.add_argument("--tol", type=float, nargs="+", default=[1e-6, 1e-10])
    ap.add_argument("--preconditioner", choices=["Dirichlet", "None"], default="Dirichlet")
    ap.add_argument("--primal", choices=["edges", "corners"], default="edges",
                    help="primal nodes: the solver's rule (nodes shared by 3 or more subdomains, or by 2 on the "
                         "mesh boundary: whole subdomain edges) or the subdomain corners alone")
    a = ap.parse_args()
    M = Model(a.k, a.H, a.primal)
    K = M.assembled()
    free = np.repeat(~M.fixed, 3)
    Kf = K[free][:, free]
    print(f"cube of {M.n}^3 Hex8, {3 * M.nn - 3 * M.fixed.sum()} DOFs, {a.k}^3 subdomains of {a.H}^3 elements")
    tols = sorted(a.tol, reverse=True)
    print("| method | clusters | floating | dual unknowns | shared coarse DOFs | its factor, entries | "
          + " | ".join(f"dual its to {t:.0e} (ratio)" for t in tols) + " | relative residual of K u = f | jump | kernel |")
    print("|---|" + "---:|" * (8 + len(tols)))
    base = None
    for c in [a.k] + a.c:
        if a.k % c:
            sys.exit(f"--c {c}: must divide --k {a.k}")
        r = solve(M, c, tols, a.preconditioner == "Dirichlet")
        res = np.linalg.norm(Kf @ r["u"][free] - M.f[free]) / np.linalg.norm(M.f[free])
        base = base or r["its"]
        name = "FETI-DP" if c == a.k else "total FETI" if c == 1 else f"clusters of {c}^3"
        its = " | ".join(f"{n} ({n / b:.2f})" for n, b in zip(r["its"], base))
        print(f"| {name} | {(a.k // c)**3} | {r['floating']} | {r['nl']} | {r['coarse_dofs']} | {r['coarse_factor']} | "
              f"{its} | {res:.1e} | {r['jump']:.1e} | {r['kernel']:.0e} |", flush=True)


if __name__ == "__main__":
    main()
