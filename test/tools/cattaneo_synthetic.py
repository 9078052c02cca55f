#!/usr/bin/env python3
"""cattaneo_synthetic.py OUTDIR [--all-slip]: an output directory of the
Cattaneo problem from the analytic tractions, for ddcontact-hertz --cattaneo
(doc/contact.md, "Cattaneo"; Johnson, Contact Mechanics, 1985, chapter 7).

The cylinder (R = 1, axis x = 0.01, E = 1000, nu = 0.3 as the block) has
slave nodes every a/100 along its arc over |x| < 1.3 a; the pair's friction
coefficient is MU and Q = Q_RATIO mu P. Each node's multiplier and
tangential_x are the tractions at the node times its tributary length h:

  p(x) = p0 sqrt(1 - x^2/a^2),
  q(x) = mu p0 [sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - x^2/c^2)] in |x| < c,
         mu p(x) in c <= |x| < a,  c = a sqrt(1 - Q_RATIO),

with p0 chosen so that the nodes' sum P is Hertz's for a, P = pi E* a^2 /
(4 R): the tool's a (the fit of p^2) and its Hertz a then agree to
round-off, and its c (the fit of (mu p - |q|)^2 over the stick nodes)
differs from sqrt(1 - Q/(mu P)) by the node sums' quadrature only.
--all-slip marks every active node slipping (state 2): no stick zone.
Writes OUTDIR/parameters.xml and OUTDIR/contact_nodes.csv.
"""
import math
import os
import sys

R, AXIS, E, NU = 1.0, 0.01, 1000.0, 0.3
A, MU, Q_RATIO = 0.08, 0.3, 0.5
STEPS = 100  # nodes per a

DECK = """<ParameterList name="DDContact">
  <ParameterList name="Mesh">
    <ParameterList name="Bodies">
{bodies}    </ParameterList>
  </ParameterList>
  <ParameterList name="Contact">
    <ParameterList name="Pairs">
      <ParameterList name="Cylinder on block">
        <Parameter name="Slave" type="string" value="Cylinder/surface"/>
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
    bodies = "".join(BODY.format(name=n, E=E, nu=NU) for n in ("Cylinder", "Block"))
    with open(os.path.join(out, "parameters.xml"), "w") as f:
        f.write(DECK.format(bodies=bodies, mu=MU))
    estar = E / (2 * (1 - NU * NU))
    h = A / STEPS
    c = A * math.sqrt(1 - Q_RATIO)
    xs = [k * h for k in range(-int(1.3 * STEPS), int(1.3 * STEPS) + 1)]
    ellipse = lambda x, w: math.sqrt(1 - x * x / (w * w)) if abs(x) < w else 0.0
    p0 = math.pi * estar * A * A / (4 * R) / sum(ellipse(x, A) * h for x in xs)
    rows = ["pair,node,x,y,z,gap,multiplier,tributary_area,pressure,active,tangential_x,tangential_y,"
            "tangential_z,slip,state"]
    for k, x in enumerate(xs):
        p = p0 * ellipse(x, A)
        q = MU * p - (MU * p0 * (c / A) * ellipse(x, c) if abs(x) < c else 0.0)
        active = abs(x) < A
        state = 0 if not active else (1 if abs(x) < c and not all_slip else 2)
        y = R - math.sqrt(R * R - x * x)
        rows.append(",".join(repr(v) for v in (0, k, x + AXIS, y, 0.0, 0.0, -p * h, h, p, int(active), -q * h,
                                                0.0, 0.0, 0.0, state)))
    with open(os.path.join(out, "contact_nodes.csv"), "w") as f:
        f.write("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
