#!/usr/bin/python3
"""Dual iterations of FETI-DP, clusters of subdomains, total FETI and three-level BDDC, on a model problem.

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

With --bddc, also BDDC (Dohrmann 2003) on the assembled interface problem
with the FETI-DP primal space, and three-level BDDC (Tu 2007): its coarse
solve replaced by one BDDC application to S_PiPi with clusters of c^3
subdomains as its subdomains.

Prints a markdown table; needs python3-scipy (Debian, cmake/setup.sh).

    /usr/bin/python3 test/benchmark/cluster_iterations.py --k 8 --H 4 --c 1 2 4 [--primal corners] [--bddc 2 4]
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


class Decomposition:
    """FETI-DP (cluster_size = k: one cluster), clusters of cluster_size^3
    subdomains, or total FETI (cluster_size = 1) on one model."""

    def __init__(self, model, cluster_size):
        self.M = model
        ncl = model.k // cluster_size
        self.nclusters = ncl**3
        self.cl_of = lambda box: (box[0] // cluster_size) + ncl * ((box[1] // cluster_size) + ncl * (box[2] // cluster_size))
        self._space()
        self._jumps()
        self._kernels()
        self._condensation()
        self._preconditioner()
        self.G = (self.B @ self.R).tocsc()
        if self.G.shape[1]:
            self.GtG = la.cho_factor((self.G.T @ self.G).toarray())

    def _space(self):
        """The partially assembled space: a subdomain's own copy of each
        non-primal DOF, a cluster's copy of each primal DOF; K~ and f~ (f at
        each copy divided by the copies: the sum is f)."""
        M = self.M
        ncols = 0
        primal_col = {}  # (cluster, node) -> first column
        self.col_of = []  # per subdomain: column of each local DOF (-1: fixed)
        owner = []  # per column: subdomain (>= 0) or -1 - cluster
        col_node = []
        for si, s in enumerate(M.subs):
            c = self.cl_of(s["box"])
            cols = np.full(3 * len(s["node"]), -1)
            for q, g in enumerate(s["node"]):
                if M.fixed[g]:
                    continue
                if M.primal[g]:
                    if (c, g) not in primal_col:
                        primal_col[(c, g)] = ncols
                        ncols += 3
                        owner += [-1 - c] * 3
                        col_node += [g] * 3
                    cols[3 * q:3 * q + 3] = primal_col[(c, g)] + np.arange(3)
                else:
                    cols[3 * q:3 * q + 3] = ncols + np.arange(3)
                    ncols += 3
                    owner += [si] * 3
                    col_node += [g] * 3
            self.col_of.append(cols)
        self.ncols, self.owner, self.col_node = ncols, np.array(owner), np.array(col_node)
        self.col_cluster = np.array([self.cl_of(M.subs[o]["box"]) if o >= 0 else -1 - o for o in self.owner])
        Kc = M.Ks.tocoo()
        rows, cols_, vals = [], [], []
        for cm in self.col_of:
            keep = (cm[Kc.row] >= 0) & (cm[Kc.col] >= 0)
            rows.append(cm[Kc.row[keep]]), cols_.append(cm[Kc.col[keep]]), vals.append(Kc.data[keep])
        self.Kt = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols_))),
                                shape=(ncols, ncols))
        self.copies = np.zeros(3 * M.nn)
        for d in range(3):
            np.add.at(self.copies, 3 * self.col_node[d::3] + d, 1)
        self.gdof = 3 * self.col_node + np.tile(np.arange(3), ncols // 3)
        self.ft = M.f[self.gdof] / self.copies[self.gdof]

    def _jumps(self):
        """B, fully redundant (one row per pair of copies of a DOF), and B_D
        with multiplicity scaling."""
        by_dof = {}
        for j in range(self.ncols):
            by_dof.setdefault(self.gdof[j], []).append(j)
        br, bc, bv, bd = [], [], [], []
        nl = 0
        for cs in by_dof.values():
            m = len(cs)
            for a, b in itertools.combinations(cs, 2):
                br += [nl, nl]
                bc += [a, b]
                bv += [1.0, -1.0]
                bd += [1.0 / m, -1.0 / m]
                nl += 1
        self.nl = nl
        self.B = sp.csr_matrix((bv, (br, bc)), shape=(nl, self.ncols))
        self.BD = sp.csr_matrix((bd, (br, bc)), shape=(nl, self.ncols))

    def _kernels(self):
        """R: the rigid-body modes of each floating cluster; 6 of its primal
        DOFs fixed for a generalised inverse."""
        M = self.M
        Rcols, fixdofs = [], []
        for c in range(self.nclusters):
            if any(M.fixed[s["node"]].any() for s in M.subs if self.cl_of(s["box"]) == c):
                continue
            js = np.nonzero(self.col_cluster == c)[0]
            Rc = rigid_body_modes(M.xyz[self.col_node[js]])
            prim = np.nonzero(self.owner[js] < 0)[0]
            _, _, piv = la.qr(Rc[prim].T, pivoting=True)
            fixdofs += list(js[prim[piv[:6]]])
            Rcols.append(sp.csc_matrix((Rc.ravel(), (np.repeat(js, 6), np.tile(np.arange(6), len(js)))),
                                       shape=(self.ncols, 6)))
        self.fixdofs = np.array(fixdofs, int)
        self.R = sp.hstack(Rcols).tocsc() if Rcols else sp.csc_matrix((self.ncols, 0))
        self.kernel_residual = spla.norm(self.Kt @ self.R) / spla.norm(self.Kt) if self.R.shape[1] else 0.0

    def _condensation(self):
        """K^+ by condensation on the primal columns, as FETI-DP applies
        K~^{-1}: per subdomain K_rr (dense; subdomains of one pattern share
        it), the primal problem sum_s S_PiPi^s with the fixed DOFs' rows and
        columns replaced by the identity."""
        M = self.M
        groups = {}
        for si, cm in enumerate(self.col_of):
            loc = np.nonzero(cm >= 0)[0]
            rl, pl = loc[self.owner[cm[loc]] >= 0], loc[self.owner[cm[loc]] < 0]
            g = groups.setdefault((rl.tobytes(), pl.tobytes()), (rl, pl, [], []))
            g[2].append(cm), g[3].append(si)
        Kd = M.Ks.toarray()
        self.parts = []
        srow, scol, sval = [], [], []
        self.sub_S = []  # per subdomain: (index, its primal columns, S_PiPi^s)
        for rl, pl, cms, sis in groups.values():
            cms = np.array(cms).T  # local DOF x subdomain
            Krr = la.cho_factor(Kd[np.ix_(rl, rl)])
            KrP = Kd[np.ix_(rl, pl)]
            S = Kd[np.ix_(pl, pl)] - KrP.T @ la.cho_solve(Krr, KrP)
            self.parts.append((Krr, KrP, cms[rl], cms[pl]))
            for b in range(cms.shape[1]):
                self.sub_S.append((sis[b], cms[pl, b], S))
                srow.append(np.repeat(cms[pl, b], len(pl))), scol.append(np.tile(cms[pl, b], len(pl)))
                sval.append(S.ravel())
        self.pcols = np.nonzero(self.owner < 0)[0]
        self.pidx = np.full(self.ncols, -1)
        self.pidx[self.pcols] = np.arange(len(self.pcols))
        n = len(self.pcols)
        self.Sc = Sc = sp.csr_matrix((np.concatenate(sval), (self.pidx[np.concatenate(srow)], self.pidx[np.concatenate(scol)])),
                           shape=(n, n))
        self.keep = np.ones(n)
        self.keep[self.pidx[self.fixdofs]] = 0
        Dk = sp.diags(self.keep)
        self.coarse = spla.splu((Dk @ Sc @ Dk + sp.diags(1 - self.keep)).tocsc(), permc_spec="MMD_AT_PLUS_A")
        self.coarse_solve = self.coarse.solve

    def Kplus(self, v):
        out = np.zeros(self.ncols)
        g = v[self.pcols].copy()
        ys = []
        for Krr, KrP, Rc, Pc in self.parts:
            y = la.cho_solve(Krr, v[Rc])
            np.add.at(g, self.pidx[Pc], -(KrP.T @ y))
            ys.append(y)
        up = self.keep * self.coarse_solve(self.keep * g)
        out[self.pcols] = up
        for (Krr, KrP, Rc, Pc), y in zip(self.parts, ys):
            out[Rc] = y - la.cho_solve(Krr, KrP @ up[self.pidx[Pc]])
        return out

    def F(self, lam):
        return self.B @ self.Kplus(self.B.T @ lam)

    def _preconditioner(self):
        """The Dirichlet preconditioner: per subdomain, S on the DOFs with
        rows (its dual DOFs, and the primal DOFs its cluster shares with
        another). A cluster's primal column is shared by its subdomains
        there: each applies the whole jump and the reactions add up, as in
        the cluster's own (partially assembled) Schur complement. Splitting
        the entry over them (weights 1/n) took 3 times the iterations."""
        M = self.M
        has_rows = np.diff(self.BD.tocsc().indptr) > 0
        self.blocks, allcols = [], []
        K = M.Ks
        for s, cm in zip(M.subs, self.col_of):
            loc = np.nonzero(cm >= 0)[0]
            rowed = has_rows[cm[loc]]
            interior = M.mult[s["node"][loc // 3]] == 1
            Dl, Il = loc[rowed], loc[interior & ~rowed]
            KID = K[Il][:, Dl].toarray()
            self.blocks.append(K[Dl][:, Dl].toarray() - KID.T @ la.solve(K[Il][:, Il].toarray(), KID, assume_a="pos"))
            allcols.append(cm[Dl])
        self.offsets = np.cumsum([0] + [len(x) for x in allcols])
        self.Bcat = self.BD[:, np.concatenate(allcols)].tocsr()
        self.BcatT = self.Bcat.T.tocsr()

    def dirichlet(self, r):
        v = self.BcatT @ r
        y = np.empty_like(v)
        for b, S in enumerate(self.blocks):
            y[self.offsets[b]:self.offsets[b + 1]] = S @ v[self.offsets[b]:self.offsets[b + 1]]
        return self.Bcat @ y

    def P(self, v):
        return v - self.G @ la.cho_solve(self.GtG, self.G.T @ v) if self.G.shape[1] else v

    def pcg(self, tols, dirichlet=True, maxit=1000):
        """Projected CG; returns lambda and, per tolerance, the iteration
        that met it (-1: not within maxit)."""
        precond = self.dirichlet if dirichlet else np.copy
        d = self.B @ self.Kplus(self.ft)
        lam = self.G @ la.cho_solve(self.GtG, self.R.T @ self.ft) if self.G.shape[1] else np.zeros(self.nl)
        # lambda = lambda_0 + mu, mu in ker G^T from P F mu = P (d - F lambda_0)
        mu, its = pcg(lambda v: self.P(self.F(v)), self.P(d - self.F(lam)), lambda r: self.P(precond(r)), tols,
                      maxit)
        return lam + mu, its

    def displacement(self, lam):
        """u assembled (copies averaged) and the relative jump of the copies."""
        res = self.B @ self.Kplus(self.ft) - self.F(lam)
        alpha = -la.cho_solve(self.GtG, self.G.T @ res) if self.G.shape[1] else np.zeros(0)
        u = self.Kplus(self.ft - self.B.T @ lam) + self.R @ alpha
        ug = np.zeros(3 * self.M.nn)
        np.add.at(ug, self.gdof, u / self.copies[self.gdof])
        return ug, np.linalg.norm(self.B @ u) / np.linalg.norm(u)

    def shared_coarse(self):
        """The problem every rank would share, S_PiPi for FETI-DP and G^T G
        otherwise: its DOFs and the entries of its factor."""
        if self.G.shape[1]:
            return self.G.shape[1], spla.splu((self.G.T @ self.G).tocsc(), permc_spec="MMD_AT_PLUS_A").L.nnz
        return len(self.pcols), self.coarse.L.nnz


def pcg(A, b, precond, tols, maxit=1000):
    """CG on A x = b from x = 0; x and, per tolerance, the iteration that met it."""
    x = np.zeros_like(b)
    r = b.copy()
    r0 = np.linalg.norm(r)
    z = precond(r)
    p = z.copy()
    rz = r @ z
    its, reached = 0, {}
    while its < maxit:
        for t in tols:
            if t not in reached and np.linalg.norm(r) <= t * r0:
                reached[t] = its
        if len(reached) == len(tols):
            break
        q = A(p)
        a = rz / (p @ q)
        x += a * p
        r -= a * q
        z = precond(r)
        rz, rz_old = r @ z, rz
        p = z + rz / rz_old * p
        its += 1
    return x, [reached.get(t, -1) for t in tols]


class Bddc:
    """BDDC on the assembled interface problem S u_G = g (Dohrmann 2003),
    its preconditioner R_D^T S~^{-1} R_D applied by the FETI-DP
    decomposition's K~^{-1} (the same primal space; multiplicity scaling)."""

    def __init__(self, D):
        M = D.M
        self.D = D
        free = np.repeat(~M.fixed, 3)
        K = M.assembled()[free][:, free].tocsr()
        gid = np.full(3 * M.nn, -1)
        gid[free] = np.arange(free.sum())
        self.gid = gid
        iface = np.repeat(M.mult >= 2, 3)[free]
        self.G, self.I = np.nonzero(iface)[0], np.nonzero(~iface)[0]
        self.KGG, self.KGI = K[self.G][:, self.G], K[self.G][:, self.I]
        self.KII = spla.splu(K[self.I][:, self.I].tocsc())
        f = M.f[free]
        self.fI = f[self.I]
        self.g = f[self.G] - self.KGI @ self.KII.solve(self.fI)
        self.gpos = np.full(free.sum(), -1)
        self.gpos[self.G] = np.arange(len(self.G))
        cols = np.nonzero(gid[D.gdof] >= 0)[0]
        at = self.gpos[gid[D.gdof[cols]]]
        self.cols, self.at = cols[at >= 0], at[at >= 0]  # K~ columns on the interface, their interface index
        self.w = 1.0 / D.copies[D.gdof[self.cols]]
        self.free, self.K, self.f = free, K, f

    def S(self, x):
        return self.KGG @ x - self.KGI @ self.KII.solve(self.KGI.T @ x)

    def precond(self, r):
        v = np.zeros(self.D.ncols)
        v[self.cols] = self.w * r[self.at]
        u = self.D.Kplus(v)
        z = np.zeros_like(r)
        np.add.at(z, self.at, self.w * u[self.cols])
        return z

    def solve(self, tols):
        x, its = pcg(self.S, self.g, self.precond, tols)
        u = np.zeros(len(self.f))
        u[self.G] = x
        u[self.I] = self.KII.solve(self.fI - self.KGI.T @ x)
        return u, its


class CoarseBddc:
    """One application of BDDC to the coarse matrix S_PiPi with clusters of
    cc^3 subdomains as its subdomains: the approximate coarse solve of a
    three-level BDDC (Tu 2007). At the cluster level the primal DOFs are the
    coarse DOFs shared by three or more clusters or by two on the mesh
    boundary; interior DOFs by Dohrmann's correction
    P_I + (I - P_I A) M (I - A P_I)."""

    def __init__(self, D, cc):
        M = D.M
        ncl = M.k // cc
        cl = lambda box: (box[0] // cc) + ncl * ((box[1] // cc) + ncl * (box[2] // cc))
        n = len(D.pcols)
        owners = [set() for _ in range(n)]
        per_cluster = {}
        for si, Pc, S in D.sub_S:
            c = cl(M.subs[si]["box"])
            ids = D.pidx[Pc]
            for i in ids:
                owners[i].add(c)
            per_cluster.setdefault(c, []).append((ids, S))
        mc = np.array([len(o) for o in owners])
        node = D.col_node[D.pcols]
        outer = np.any((M.xyz[node] == 0) | (M.xyz[node] == M.n), axis=1)
        prim = (mc >= 3) | ((mc == 2) & outer)
        # the cluster-level partially assembled space
        ncols, shared, rows, cols, vals = 0, {}, [], [], []
        self.copy_of = []  # (coarse DOF, column) pairs
        for c, items in per_cluster.items():
            col = {}
            for ids, _ in items:
                for i in ids:
                    if i in col:
                        continue
                    if prim[i]:
                        if i not in shared:
                            shared[i] = ncols
                            ncols += 1
                            self.copy_of.append((i, shared[i]))
                        col[i] = shared[i]
                    else:
                        col[i] = ncols
                        self.copy_of.append((i, ncols))
                        ncols += 1
            for ids, S in items:
                cc_ = np.array([col[i] for i in ids])
                rows.append(np.repeat(cc_, len(ids))), cols.append(np.tile(cc_, len(ids))), vals.append(S.ravel())
        K2 = sp.csc_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(ncols, ncols))
        self.K2 = spla.splu(K2, permc_spec="MMD_AT_PLUS_A")
        self.ids = np.array([i for i, _ in self.copy_of])
        self.cols = np.array([j for _, j in self.copy_of])
        self.w = np.where(prim[self.ids], 1.0, 1.0 / mc[self.ids])
        self.ncols = ncols
        self.A = D.Sc.tocsr()
        self.I = np.nonzero(mc == 1)[0]
        self.AII = spla.splu(self.A[self.I][:, self.I].tocsc())
        self.nprimal = int(prim.sum())

    def PI(self, g):
        z = np.zeros_like(g)
        z[self.I] = self.AII.solve(g[self.I])
        return z

    def MB(self, r):
        v = np.zeros(self.ncols)
        np.add.at(v, self.cols, self.w * r[self.ids])
        u = self.K2.solve(v)
        z = np.zeros_like(r)
        np.add.at(z, self.ids, self.w * u[self.cols])
        return z

    def __call__(self, g):
        zI = self.PI(g)
        w = self.MB(g - self.A @ zI)
        return zI + w - self.PI(self.A @ w)


def rigid_body_modes(X):
    """The six rigid-body modes (orthonormal columns) of nodes at X, three DOFs each."""
    X = X - X.mean(axis=0)
    d = np.tile(np.arange(3), len(X) // 3)
    R = np.zeros((len(X), 6))
    for t in range(3):
        R[d == t, t] = 1
    x, y, z = X[:, 0], X[:, 1], X[:, 2]
    R[d == 1, 3], R[d == 2, 3] = -z[d == 1], y[d == 2]
    R[d == 0, 4], R[d == 2, 4] = z[d == 0], -x[d == 2]
    R[d == 0, 5], R[d == 1, 5] = -y[d == 0], x[d == 1]
    return np.linalg.qr(R)[0]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--k", type=int, default=8, help="subdomains per direction")
    ap.add_argument("--H", type=int, default=4, help="elements per subdomain and direction")
    ap.add_argument("--c", type=int, nargs="+", default=[1, 2, 4], help="subdomains per cluster and direction")
    ap.add_argument("--tol", type=float, nargs="+", default=[1e-6, 1e-10])
    ap.add_argument("--preconditioner", choices=["Dirichlet", "None"], default="Dirichlet")
    ap.add_argument("--bddc", type=int, nargs="*", default=None,
                    help="also BDDC with the exact coarse solve, and with the coarse problem solved by one BDDC "
                         "application on clusters of these sizes (three-level BDDC)")
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
        D = Decomposition(M, c)
        lam, counts = D.pcg(tols, a.preconditioner == "Dirichlet")
        u, jump = D.displacement(lam)
        res = np.linalg.norm(Kf @ u[free] - M.f[free]) / np.linalg.norm(M.f[free])
        base = base or counts
        name = "FETI-DP" if c == a.k else "total FETI" if c == 1 else f"clusters of {c}^3"
        its = " | ".join(f"{n} ({n / b:.2f})" for n, b in zip(counts, base))
        dofs, entries = D.shared_coarse()
        print(f"| {name} | {D.nclusters} | {D.R.shape[1] // 6} | {D.nl} | {dofs} | {entries} | "
              f"{its} | {res:.1e} | {jump:.1e} | {D.kernel_residual:.0e} |", flush=True)
    if a.bddc is not None:
        bddc_rows(M, a, tols, Kf, free, base)


def bddc_rows(M, a, tols, Kf, free, base):
    """BDDC with the FETI-DP primal space: exact coarse solve, then three-level."""
    D = Decomposition(M, a.k)
    B = Bddc(D)
    for cc in [None] + a.bddc:
        if cc is not None and a.k % cc:
            sys.exit(f"--bddc {cc}: must divide --k {a.k}")
        if cc is None:
            D.coarse_solve, name, dofs = D.coarse.solve, "BDDC, exact coarse solve", len(D.pcols)
        else:
            C = CoarseBddc(D, cc)
            D.coarse_solve, name, dofs = C, f"BDDC, coarse by BDDC on clusters of {cc}^3", C.nprimal
        u, counts = B.solve(tols)
        res = np.linalg.norm(Kf @ u - M.f[free]) / np.linalg.norm(M.f[free])
        its = " | ".join(f"{n} ({n / b:.2f})" for n, b in zip(counts, base))
        print(f"| {name} | | | {len(B.G)} | {dofs} | | {its} | {res:.1e} | | |", flush=True)


if __name__ == "__main__":
    main()
