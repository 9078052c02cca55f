// ddcontact-hertz --mindlin: a run of a sphere pressed on a block of the
// same material and pushed sideways (examples/mindlin_sphere.xml, half of
// the problem: the plane y = 0 a symmetry plane) against Hertz's and
// Mindlin's solutions (doc/contact.md, "Mindlin"; Johnson, Contact
// Mechanics, 1985: section 4.2, Hertz's circular contact, and section 7.2,
// tangential loading with partial slip after Cattaneo 1938 and Mindlin
// 1949). With 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2:
//
//   a = (3 P R / (4 E*))^(1/3),  p(r) = p0 sqrt(1 - r^2/a^2),  p0 = 3 P / (2 pi a^2),
//   c / a = (1 - Q / (mu P))^(1/3),
//   q(r) = mu p0 [sqrt(1 - r^2/a^2) - (c/a) sqrt(1 - r^2/c^2)]  in r < c,
//   q(r) = mu p(r)                                             in c <= r < a.
//
// From the run (contact_nodes.csv, reference coordinates): R and the axis
// from the sphere through the slave nodes; P = 2 x the sum of the active
// multipliers' magnitudes, Q = 2 x |sum of their tangential_x| (the half
// model); a from a least-squares fit of p^2 = A + B r^2 over the active
// nodes (r from the axis; p the pressure column), c from one of
// (mu p - |q|)^2 = A + B r^2 over the stick nodes (state 1): by the
// formulas above mu p - |q| = mu p0 (c/a) sqrt(1 - r^2/c^2) there, whatever
// a and p0 are. p and |q| are the nodal tractions, |multiplier| and the
// tangential force's magnitude over the tributary area.
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "ddcontact_hertz.hpp"

namespace ddc_hertz {
namespace {

/// The slave nodes lie on the sphere's surface to this fraction of R.
constexpr double kOnSphere = 1e-6;
/// The model is half of the problem (the symmetry plane y = 0).
constexpr double kHalfModel = 2.0;

struct Sphere {
  double cx = 0, cy = 0, cz = 0, R = 0;
};

/// The solution of the 4 x 4 system M s = b by Gaussian elimination with
/// partial pivoting; false if M is singular.
bool solve4(double M[4][5], double s[4]) {
  for (int k = 0; k < 4; ++k) {
    int piv = k;
    for (int i = k + 1; i < 4; ++i)
      if (std::abs(M[i][k]) > std::abs(M[piv][k])) piv = i;
    if (!(std::abs(M[piv][k]) > 1e-300)) return false;
    for (int j = 0; j < 5; ++j) std::swap(M[k][j], M[piv][j]);
    for (int i = k + 1; i < 4; ++i) {
      const double f = M[i][k] / M[k][k];
      for (int j = k; j < 5; ++j) M[i][j] -= f * M[k][j];
    }
  }
  for (int k = 3; k >= 0; --k) {
    double v = M[k][4];
    for (int j = k + 1; j < 4; ++j) v -= M[k][j] * s[j];
    s[k] = v / M[k][k];
  }
  return true;
}

/// The sphere through the slave nodes (the algebraic least-squares fit of
/// x^2 + y^2 + z^2 + D x + E y + F z + G = 0). \throws BadInput if they do
/// not lie on one.
Sphere fitSphere(const std::vector<Row>& rows, const std::string& file) {
  double M[4][5] = {{0}};
  for (const Row& r : rows) {
    const double v[4] = {r.x, r.y, r.z, 1.0}, w = -(r.x * r.x + r.y * r.y + r.z * r.z);
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) M[i][j] += v[i] * v[j];
      M[i][4] += v[i] * w;
    }
  }
  double s[4] = {0, 0, 0, 0};
  const bool solved = rows.size() >= 4 && solve4(M, s);
  Sphere c{-s[0] / 2, -s[1] / 2, -s[2] / 2, 0.0};
  c.R = std::sqrt(c.cx * c.cx + c.cy * c.cy + c.cz * c.cz - s[3]);
  double deviation = solved && std::isfinite(c.R) ? 0.0 : 1.0;
  for (const Row& r : rows)
    deviation = std::max(deviation, std::abs(std::sqrt((r.x - c.cx) * (r.x - c.cx) + (r.y - c.cy) * (r.y - c.cy) +
                                                       (r.z - c.cz) * (r.z - c.cz)) - c.R));
  if (!(deviation <= kOnSphere * c.R))
    throw BadInput(file + ": the slave nodes do not lie on a sphere; --mindlin needs the sphere's surface as the "
                   "slave side of the deck's one contact pair");
  return c;
}


/// Nodal tractions p and |q| (force over tributary area).
double normalTraction(const Row& r) { return r.tributary > 0 ? std::abs(r.multiplier) / r.tributary : 0.0; }
double tangentialTraction(const Row& r) {
  const double* t = r.tangential;
  return r.tributary > 0 ? std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]) / r.tributary : 0.0;
}

/// c from the fit of (mu p - |q|)^2 over the stick nodes (file comment).
double fittedStickRadius(const std::vector<Row>& rows, double mu) {
  std::vector<double> s, y;
  for (const Row& r : rows)
    if (r.active && r.state == 1) {
      const double g = mu * normalTraction(r) - tangentialTraction(r);
      s.push_back(r.r), y.push_back(g * g);
    }
  return fittedHalfWidth(s, y);
}

/// --profile: r, p and q of the run and of the theory at every slave node.
void writeProfile(const std::string& file, const std::vector<Row>& rows, double a, double c, double mu, double P) {
  std::ofstream out(file);
  out << "x,y,r,p_fe,p_hertz,q_fe,q_mindlin,state\n";
  out.precision(10);
  const double p0 = 3.0 * P / (2.0 * kPi * a * a);
  for (const Row& row : rows) {
    const double r = row.r;
    const double p = r < a ? p0 * std::sqrt(1 - r * r / (a * a)) : 0.0;
    const double q = mu > 0 ? mu * p - (r < c ? mu * p0 * (c / a) * std::sqrt(1 - r * r / (c * c)) : 0.0) : 0.0;
    out << row.x << ',' << row.y << ',' << r << ',' << normalTraction(row) << ',' << p << ','
        << tangentialTraction(row) << ',' << q << ',' << row.state << '\n';
  }
  if (!out.flush()) throw BadInput("cannot write '" + file + "'");
}

/// "check: ... passed / FAILED" for one tolerance; whether it passed.
bool check(const char* what, double err, double tolerance) {
  const bool pass = std::abs(err) <= tolerance;  // false for a NaN fit
  std::printf("check: |%s error| <= %g: %s\n", what, tolerance, pass ? "passed" : "FAILED");
  return pass;
}

}  // namespace

int mindlin(const MindlinOptions& o, const Teuchos::ParameterList& deck, const std::string& xml) {
  const Material m1 = materialOf(deck, o.sphere, xml), m2 = materialOf(deck, o.block, xml);
  std::string pair;
  const double mu = frictionCoefficient(deck, xml, "--mindlin", pair);
  const std::string file = o.dir + "/contact_nodes.csv";
  const Sphere sphere = fitSphere(readContactNodes(file, 0.0, 0.0), file);
  const auto rows = readContactNodes(file, sphere.cx, sphere.cy);
  const Totals t = transmitted(rows, kHalfModel);
  checkPartialSlipRun(t, mu, o.toleranceC, file, "sphere", "Mindlin");
  const bool frictional = mu > 0 && t.Q > 0;

  const double Estar = 1.0 / ((1.0 - m1.nu * m1.nu) / m1.E + (1.0 - m2.nu * m2.nu) / m2.E);
  const double a = std::cbrt(3.0 * t.P * sphere.R / (4.0 * Estar));
  std::vector<double> s, p2;
  for (const Row& r : rows)
    if (r.active) s.push_back(r.r), p2.push_back(r.pressure * r.pressure);
  const double aFit = fittedHalfWidth(s, p2), errA = (aFit - a) / a;
  const double c = frictional ? a * std::cbrt(1.0 - t.Q / (mu * t.P)) : 0.0;
  const double cFit = frictional ? fittedStickRadius(rows, mu) : 0.0;
  const double errC = frictional ? (cFit - c) / c : 0.0;

  std::printf("Mindlin circular contact: sphere '%s' R = %g (axis x = %g, y = %g, from its %zu slave nodes; E = %g, "
              "nu = %g) on '%s' (E = %g, nu = %g): E* = %.6g, mu = %g (pair '%s')\n",
              o.sphere.c_str(), sphere.R, sphere.cx, sphere.cy, rows.size(), m1.E, m1.nu, o.block.c_str(), m2.E,
              m2.nu, Estar, mu, pair.c_str());
  if (m1.E != m2.E || m1.nu != m2.nu)
    std::printf("note: the bodies' materials differ: the tangential problem is Mindlin's only for equal ones\n");
  std::printf("whole problem (2 x the half model): P = %.6g, Q = %.6g (Q / (mu P) = %.4g); %d active slave nodes: %d "
              "stick, %d slip; a/R = %.4f\n",
              t.P, t.Q, mu > 0 ? t.Q / (mu * t.P) : 0.0, t.active, t.stick, t.slip, a / sphere.R);
  std::printf("%-26s %12s %12s %10s\n", "quantity", "ddcontact", "theory", "rel. error");
  std::printf("%-26s %12.6g %12.6g %+10.5f\n", "contact radius a (fit)", aFit, a, errA);
  if (frictional) std::printf("%-26s %12.6g %12.6g %+10.5f\n", "stick radius c (fit)", cFit, c, errC);
  if (!o.profile.empty()) writeProfile(o.profile, rows, a, c, mu, t.P);
  bool ok = true;
  if (o.toleranceA > 0) ok = check("a", errA, o.toleranceA) && ok;
  if (o.toleranceC > 0) ok = check("c", errC, o.toleranceC) && ok;
  return ok ? 0 : 1;
}

}  // namespace ddc_hertz
