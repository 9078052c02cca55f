// ddcontact-hertz --cattaneo: a run of a plane-strain cylinder pressed on a
// block of the same material and pushed sideways (examples/cattaneo_2d.xml)
// against Hertz's and Cattaneo's solutions (doc/contact.md, "Cattaneo";
// Johnson, Contact Mechanics, 1985: chapter 4, Hertz's line contact, and
// chapter 7, tangential loading with partial slip after Cattaneo 1938 and
// Mindlin 1949). Per unit thickness, with
// 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2:
//
//   a = sqrt(4 P R / (pi E*)),  p(x) = p0 sqrt(1 - x^2/a^2),  p0 = 2 P / (pi a),
//   c / a = sqrt(1 - Q / (mu P)),
//   q(x) = mu p0 [sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - x^2/c^2)]  in |x| < c,
//   q(x) = mu p(x)                                             in c <= |x| < a.
//
// From the run (contact_nodes.csv, reference coordinates): R and the axis
// from the circle through the slave nodes; P = sum of the active
// multipliers' magnitudes, Q = |sum of their tangential_x|; a from a
// least-squares fit of p^2 = A + B x^2 over the active nodes (x from the
// axis), c from one of (mu p - |q|)^2 = A + B x^2 over the stick nodes
// (state 1): by the formulas above mu p - |q| = mu p0 (c/a) sqrt(1 - x^2/c^2)
// there, whatever a and p0 are. p and q are the nodal tractions,
// multiplier and tangential_x over the tributary length.
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "ddcontact_hertz.hpp"

namespace ddc_hertz {
namespace {

/// The slave nodes lie on the cylinder's surface to this fraction of R.
constexpr double kOnCircle = 1e-6;

struct Circle {
  double cx = 0, cy = 0, R = 0;
};

/// The circle through the slave nodes (Kasa's algebraic least-squares fit,
/// x^2 + y^2 + D x + E y + F = 0). \throws BadInput if they are not on one.
Circle fitCircle(const std::vector<Row>& rows, const std::string& file) {
  double M[3][3] = {{0}}, b[3] = {0};
  for (const Row& r : rows) {
    const double v[3] = {r.x, r.y, 1.0}, w = -(r.x * r.x + r.y * r.y);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) M[i][j] += v[i] * v[j];
      b[i] += v[i] * w;
    }
  }
  auto det3 = [](const double A[3][3]) {
    return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
           A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
  };
  const double d = det3(M);
  double s[3];
  for (int k = 0; k < 3; ++k) {  // Cramer's rule
    double Mk[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Mk[i][j] = j == k ? b[i] : M[i][j];
    s[k] = det3(Mk) / d;
  }
  Circle c{-s[0] / 2, -s[1] / 2, 0.0};
  c.R = std::sqrt(c.cx * c.cx + c.cy * c.cy - s[2]);
  double deviation = std::isfinite(c.R) ? 0.0 : 1.0;
  for (const Row& r : rows) deviation = std::max(deviation, std::abs(std::hypot(r.x - c.cx, r.y - c.cy) - c.R));
  if (rows.size() < 3 || !(deviation <= kOnCircle * c.R))
    throw BadInput(file + ": the slave nodes do not lie on a circle; --cattaneo needs the cylinder's surface as "
                   "the slave side of the deck's one contact pair");
  return c;
}


/// Nodal tractions p and |q| (force over tributary length).
double normalTraction(const Row& r) { return r.tributary > 0 ? std::abs(r.multiplier) / r.tributary : 0.0; }
double tangentialTraction(const Row& r) { return r.tributary > 0 ? std::abs(r.tangential[0]) / r.tributary : 0.0; }

/// c from the fit of (mu p - |q|)^2 over the stick nodes (file comment).
double fittedStickHalfWidth(const std::vector<Row>& rows, double axis, double mu) {
  std::vector<double> s, y;
  for (const Row& r : rows)
    if (r.active && r.state == 1) {
      const double g = mu * normalTraction(r) - tangentialTraction(r);
      s.push_back(r.x - axis), y.push_back(g * g);
    }
  return fittedHalfWidth(s, y);
}

/// --profile: x, p and q of the run and of the theory at every slave node.
void writeProfile(const std::string& file, const std::vector<Row>& rows, double axis, double a, double c,
                  double mu, double P) {
  std::ofstream out(file);
  out << "x,p_fe,p_hertz,q_fe,q_cattaneo,state\n";
  out.precision(10);
  const double p0 = 2.0 * P / (kPi * a);
  for (const Row& r : rows) {
    const double x = r.x - axis;
    const double p = std::abs(x) < a ? p0 * std::sqrt(1 - x * x / (a * a)) : 0.0;
    const double q = mu > 0 ? mu * p - (std::abs(x) < c ? mu * p0 * (c / a) * std::sqrt(1 - x * x / (c * c)) : 0.0) : 0.0;
    out << x << ',' << normalTraction(r) << ',' << p << ',' << tangentialTraction(r) << ',' << q << ',' << r.state
        << '\n';
  }
  if (!out.flush()) throw BadInput("cannot write '" + file + "'");
}

}  // namespace

int cattaneo(const CattaneoOptions& o, const Teuchos::ParameterList& deck, const std::string& xml) {
  const Material m1 = materialOf(deck, o.cylinder, xml), m2 = materialOf(deck, o.block, xml);
  std::string pair;
  const double mu = frictionCoefficient(deck, xml, "--cattaneo", pair);
  const std::string file = o.dir + "/contact_nodes.csv";
  const auto rows = readContactNodes(file, 0.0, 0.0);
  const Circle circle = fitCircle(rows, file);
  const Totals t = transmitted(rows, 1.0);
  checkPartialSlipRun(t, mu, o.toleranceC, file, "cylinder", "Cattaneo");
  const bool frictional = mu > 0 && t.Q > 0;

  const double Estar = 1.0 / ((1.0 - m1.nu * m1.nu) / m1.E + (1.0 - m2.nu * m2.nu) / m2.E);
  const double a = std::sqrt(4.0 * t.P * circle.R / (kPi * Estar));
  std::vector<double> s, p2;
  for (const Row& r : rows)
    if (r.active) s.push_back(r.x - circle.cx), p2.push_back(r.pressure * r.pressure);
  const double aFit = fittedHalfWidth(s, p2), errA = (aFit - a) / a;
  const double c = frictional ? a * std::sqrt(1.0 - t.Q / (mu * t.P)) : 0.0;
  const double cFit = frictional ? fittedStickHalfWidth(rows, circle.cx, mu) : 0.0;
  const double errC = frictional ? (cFit - c) / c : 0.0;

  std::printf("Cattaneo line contact: cylinder '%s' R = %g (axis x = %g, from its %zu slave nodes; E = %g, nu = %g) "
              "on '%s' (E = %g, nu = %g): E* = %.6g, mu = %g (pair '%s')\n",
              o.cylinder.c_str(), circle.R, circle.cx, rows.size(), m1.E, m1.nu, o.block.c_str(), m2.E, m2.nu, Estar,
              mu, pair.c_str());
  if (m1.E != m2.E || m1.nu != m2.nu)
    std::printf("note: the bodies' materials differ: the tangential problem is Cattaneo's only for equal ones\n");
  std::printf("per unit thickness: P = %.6g, Q = %.6g (Q / (mu P) = %.4g); %d active slave nodes: %d stick, %d slip; "
              "a/R = %.4f\n",
              t.P, t.Q, mu > 0 ? t.Q / (mu * t.P) : 0.0, t.active, t.stick, t.slip, a / circle.R);
  std::printf("%-26s %12s %12s %10s\n", "quantity", "ddcontact", "theory", "rel. error");
  std::printf("%-26s %12.6g %12.6g %+10.5f\n", "half-width a (fit)", aFit, a, errA);
  if (frictional) std::printf("%-26s %12.6g %12.6g %+10.5f\n", "stick half-width c (fit)", cFit, c, errC);
  if (!o.profile.empty()) writeProfile(o.profile, rows, circle.cx, a, c, mu, t.P);
  bool ok = true;
  if (o.toleranceA > 0) {
    const bool pass = std::abs(errA) <= o.toleranceA;  // false for a NaN fit
    std::printf("check: |a error| <= %g: %s\n", o.toleranceA, pass ? "passed" : "FAILED");
    ok = ok && pass;
  }
  if (o.toleranceC > 0) {
    const bool pass = std::abs(errC) <= o.toleranceC;
    std::printf("check: |c error| <= %g: %s\n", o.toleranceC, pass ? "passed" : "FAILED");
    ok = ok && pass;
  }
  return ok ? 0 : 1;
}

}  // namespace ddc_hertz
