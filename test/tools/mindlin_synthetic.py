#!/usr/bin/env python3
"""mindlin_synthetic.py OUTDIR [--all-slip]: an output directory of the
Mindlin problem from the analytic tractions, for ddcontact-hertz --mindlin
(doc/contact.md, "Mindlin"; Johnson, Contact Mechanics, 1985, section 7.2).

Half of the problem, y >= 0: the sphere (R = 1, axis x = 0.01, y = 0, E =
1000, nu = 0.3 as the block) has slave nodes on a square grid of spacing
a/STEPS over |x - 0.01|, y < 1.3 a, on the sphere z = R - sqrt(R^2 - r^2);
each has the tributary area h^2 (half of it on y = 0). The pair's friction
coefficient is MU and Q = Q_RATIO mu P. Each node's multiplier and
tangential_x are the tractions at the node times its area:

  p(r) = p0 sqrt(1 - r^2/a^2),
  q(r) = mu p0 [sqrt(1 - r^2/a^2) - (c/a) sqrt(1 - r^2/c^2)] in r < c,
         mu p(r) in c <= r < a,  c = a (1 - Q_RATIO)^(1/3),

with p0 chosen so that twice the nodes' sum P is Hertz's for a, P = 4 E*
a^3 / (3 R): the tool's a (the fit of p^2) and its Hertz a then agree to
round-off, and its c (the fit of (mu p - |q|)^2 over the stick nodes)
differs from a (1 - Q/(mu P))^(1/3) by the node sums' quadrature only.
--all-slip marks every active node slipping (state 2): no stick zone.
Writes OUTDIR/parameters.xml and OUTDIR/contact_nodes.csv.
"""
import math
import os
import sys

R, AXIS, E, NU = 1.0, 0.01, 1000.0, 0.3
A, MU, Q_RATIO = 0.1, 0.3, 0.5
STEPS = 40  # nodes per a

DECK = """<ParameterList name="DDContact">
  <ParameterList name="Mesh">
    <ParameterList name="Bodies">
{bodies}    </ParameterList>
  </ParameterList>
  <ParameterList name="Contact">
    <ParameterList name="Pairs">
      <ParameterList name="Sphere on block">
        <Parameter name="Slave" type="string" value="Sphere/surface"/>
        <Parameter name="Master" type="string" value="Block/top"/>
        <Parameter name="Friction Coefficient" type="double" value="{mu}"/>
      </ParameterList>
    </ParameterList>
  </ParameterList>
</ParameterList>
"""
BODY = """      <ParameterList name="{name}">
        <ParameterList name="Element">
          <ParameterList name="Material">
            <Parameter name="Young's Modulus" type="double" value="{E}"/>
            <Parameter name="Poisson's Ratio" type="double" value="{nu}"/>
          </ParameterList>
        </ParameterList>
      </ParameterList>
"""


def main():
    if len(sys.argv) not in (2, 3) or (len(sys.argv) == 3 and sys.argv[2] != "--all-slip"):
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    out, all_slip = sys.argv[1], len(sys.argv) == 3
    os.makedirs(out, exist_ok=True)
    bodies = "".join(BODY.format(name=n, E=E, nu=NU) for n in ("Sphere", "Block"))
    with open(os.path.join(out, "parameters.xml"), "w") as f:
        f.write(DECK.format(bodies=bodies, mu=MU))
    estar = E / (2 * (1 - NU * NU))
    h = A / STEPS
    c = A * (1 - Q_RATIO) ** (1.0 / 3.0)
    n = int(1.3 * STEPS)
    nodes = [(i * h, j * h, h * h * (0.5 if j == 0 else 1.0)) for i in range(-n, n + 1) for j in range(0, n + 1)]
    ellipse = lambda r, w: math.sqrt(1 - r * r / (w * w)) if r < w else 0.0
    p0 = 4 * estar * A ** 3 / (3 * R) / (2 * sum(ellipse(math.hypot(x, y), A) * w for x, y, w in nodes))
    rows = ["pair,node,x,y,z,gap,multiplier,tributary_area,pressure,active,tangential_x,tangential_y,"
            "tangential_z,slip,state"]
    for k, (x, y, w) in enumerate(nodes):
        r = math.hypot(x, y)
        p = p0 * ellipse(r, A)
        q = MU * p - (MU * p0 * (c / A) * ellipse(r, c) if r < c else 0.0)
        active = r < A
        state = 0 if not active else (1 if r < c and not all_slip else 2)
        z = R - math.sqrt(R * R - r * r)
        rows.append(",".join(repr(v) for v in (0, k, x + AXIS, y, z, 0.0, -p * w, w, p, int(active), -q * w,
                                                0.0, 0.0, 0.0, state)))
    with open(os.path.join(out, "contact_nodes.csv"), "w") as f:
        f.write("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
