// ddcontact-hertz: a ddcontact run of a sphere pressed on a block against
// Hertz's solution (doc/contact.md, "Hertz contact"; Johnson, Contact
// Mechanics, 1985, section 4.2).
//
//   ddcontact-hertz OUT_DIR [--sphere BODY] [--block BODY] [--profile FILE]
//                   [--tolerance T]
//   ddcontact-hertz --cattaneo OUT_DIR [--cylinder BODY] [--block BODY]
//                   [--profile FILE] [--tolerance-a T] [--tolerance-c T]
//   ddcontact-hertz --mindlin OUT_DIR [--sphere BODY] [--block BODY]
//                   [--profile FILE] [--tolerance-a T] [--tolerance-c T]
//
// It reads OUT_DIR/parameters.xml (the run's validated parameters) and
// OUT_DIR/contact_nodes.csv (Output/Contact Nodes = true). The sphere body
// must be a "Sphere Octant" (a quarter of a hemisphere, pole down, with the
// symmetry planes held: the whole contact force is 4 times the model's); its
// radius, axis and the two bodies' Young's moduli and Poisson's ratios give
// the theory for the contact force F the run transmits:
//
//   1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,  a = (3 F R / (4 E*))^(1/3),
//   p0 = 3 F / (2 pi a^2),  p(r) = p0 sqrt(1 - r^2/a^2).
//
// From the run: F = sum of the active multipliers' magnitudes (times 4); p0
// = the pressure at the slave node on the axis; a from a least-squares fit of
// p^2 = p0^2 (1 - r^2/a^2) to the active nodes' pressures (r from the axis,
// reference coordinates), and the bracket [outermost active node, nearest
// inactive node beyond it]. --profile writes r, p_fe, p_hertz per slave node.
//
// A dynamic run (Dynamics/Integrator set: examples/sphere_impact.xml, the
// sphere given a velocity v_z < 0 by an Initial Velocity condition on the
// sphere body, touching the block at t = 0) is compared with Hertz's impact
// solution instead (Johnson 1985, section 11.4): for the modelled
// hemisphere's mass m = rho 2 pi R^3 / 3 (4 times the quarter model),
//
//   delta_max = (15 m v^2 / (16 E* sqrt(R)))^(2/5),
//   F_max = 4/3 E* sqrt(R) delta_max^(3/2),  t_c = 2.9432 delta_max / v,
//
// against the run's history.csv: F_max = 4 x the largest |contact_force_z|,
// t_c = the last time in contact plus half a step (the release lies within
// the next step).
//
// --cattaneo compares a plane-strain cylinder pressed on a block and pushed
// sideways (examples/cattaneo_2d.xml) with Hertz's line contact and
// Cattaneo's stick zone instead (src/ddcontact_hertz_cattaneo.cpp);
// --mindlin a sphere pressed on a block and pushed sideways
// (examples/mindlin_sphere.xml, a half model) with Hertz's circular contact
// and Mindlin's stick zone (src/ddcontact_hertz_mindlin.cpp).
//
// Exit status: 0 done, 1 --tolerance given and |a or p0 relative error| > T
// (impact: t_c or F_max; --cattaneo, --mindlin: a or c beyond
// --tolerance-a / -c), 2
// bad input (usage, missing / malformed files, a deck that is no Hertz
// case, no active node on the axis, no contact, no stick zone to fit).
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_XMLParameterListCoreHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "ddcontact_hertz.hpp"

namespace ddc_hertz {

Material materialOf(const Teuchos::ParameterList& deck, const std::string& body, const std::string& file) {
  const std::string path = "Mesh/Bodies/" + body + "/Element/Material";
  const auto& bodies = deck.sublist("Mesh").sublist("Bodies");
  if (!bodies.isSublist(body)) throw BadInput(file + ": no body '" + body + "' (name it with --sphere, --cylinder or --block)");
  const auto& m = bodies.sublist(body).sublist("Element").sublist("Material");
  if (!m.isParameter("Young's Modulus") || !m.isParameter("Poisson's Ratio"))
    throw BadInput(file + ": '" + path + "' has no Young's Modulus / Poisson's Ratio");
  return {m.get<double>("Young's Modulus"), m.get<double>("Poisson's Ratio")};
}

std::vector<Row> readContactNodes(const std::string& file, double cx, double cy) {
  std::ifstream in(file);
  if (!in) throw BadInput("cannot read '" + file + "' (run with Output/Contact Nodes = true)");
  std::string line;
  std::getline(in, line);
  const std::string header =
      "pair,node,x,y,z,gap,multiplier,tributary_area,pressure,active,tangential_x,tangential_y,tangential_z,slip,state";
  if (line != header) throw BadInput(file + ": header is not '" + header + "'");
  std::vector<Row> rows;
  int lineNo = 1;
  while (std::getline(in, line)) {
    ++lineNo;
    std::istringstream ls(line);
    std::vector<double> v;
    std::string cell;
    while (std::getline(ls, cell, ',')) {
      char* end = nullptr;
      const double d = std::strtod(cell.c_str(), &end);
      if (cell.empty() || *end != '\0') throw BadInput(file + ":" + std::to_string(lineNo) + ": not a number: '" + cell + "'");
      v.push_back(d);
    }
    if (v.size() != 15) throw BadInput(file + ":" + std::to_string(lineNo) + ": expected 15 columns");
    Row r;
    r.r = std::hypot(v[2] - cx, v[3] - cy), r.x = v[2], r.y = v[3], r.z = v[4];
    r.multiplier = v[6], r.tributary = v[7], r.pressure = v[8], r.active = v[9] != 0.0;
    r.tangential[0] = v[10], r.tangential[1] = v[11], r.tangential[2] = v[12], r.slip = v[13];
    r.state = int(v[14]);
    rows.push_back(r);
  }
  if (rows.empty()) throw BadInput(file + ": no slave nodes");
  return rows;
}

double frictionCoefficient(const Teuchos::ParameterList& deck, const std::string& xml, const std::string& mode,
                           std::string& pair) {
  const auto& pairs = deck.sublist("Contact").sublist("Pairs");
  int n = 0;
  for (auto it = pairs.begin(); it != pairs.end(); ++it)
    if (pairs.isSublist(pairs.name(it))) ++n, pair = pairs.name(it);
  if (n != 1) throw BadInput(xml + ": " + mode + " needs exactly one pair in 'Contact/Pairs', found " + std::to_string(n));
  const auto& p = pairs.sublist(pair);
  return p.isParameter("Friction Coefficient") ? p.get<double>("Friction Coefficient") : 0.0;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

void checkPartialSlipRun(const Totals& t, double mu, double toleranceC, const std::string& file,
                         const std::string& body, const std::string& theory) {
  if (t.active == 0) throw BadInput(file + ": no active slave node (no contact)");
  const bool frictional = mu > 0 && t.Q > 0;
  if (frictional && t.Q >= mu * t.P)
    throw BadInput(file + ": Q / (mu P) = " + num(t.Q / (mu * t.P)) + " >= 1: the " + body + " slides; " + theory +
                   "'s partial slip needs Q < mu P");
  if (frictional && t.stick < kMinStickNodes)
    throw BadInput(file + ": " + std::to_string(t.stick) + " stick node(s) (state 1) with mu = " + num(mu) +
                   " and Q > 0: the stick zone needs at least " + std::to_string(kMinStickNodes) +
                   " to fit c (a frictionless run, or a contact zone too coarse)");
  if (toleranceC > 0 && !frictional)
    throw BadInput("--tolerance-c needs a run with friction and a tangential load (here mu = " + num(mu) +
                   ", Q = " + num(t.Q) + ")");
}

Totals transmitted(const std::vector<Row>& rows, double modelFactor) {
  Totals t;
  double qx = 0.0;
  for (const Row& r : rows)
    if (r.active) {
      t.P += std::abs(r.multiplier), qx += r.tangential[0], ++t.active;
      t.stick += r.state == 1, t.slip += r.state == 2;
    }
  t.P *= modelFactor, t.Q = modelFactor * std::abs(qx);
  return t;
}

double fittedHalfWidth(const std::vector<double>& s, const std::vector<double>& y) {
  double s1 = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    const double x = s[i] * s[i];
    s1 += 1, sx += x, sy += y[i], sxx += x * x, sxy += x * y[i];
  }
  const double det = s1 * sxx - sx * sx;
  const double B = det > 0 ? (s1 * sxy - sx * sy) / det : 0.0, A = det > 0 ? (sy - B * sx) / s1 : 0.0;
  return (A > 0 && B < 0) ? std::sqrt(-A / B) : std::nan("");
}

}  // namespace ddc_hertz

namespace {

using namespace ddc_hertz;

const char* kUsage =
    "usage: ddcontact-hertz OUT_DIR [--sphere BODY] [--block BODY] [--profile FILE] [--tolerance T]\n"
    "       ddcontact-hertz --cattaneo OUT_DIR [--cylinder BODY] [--block BODY] [--profile FILE]\n"
    "                       [--tolerance-a T] [--tolerance-c T]\n"
    "       ddcontact-hertz --mindlin OUT_DIR [--sphere BODY] [--block BODY] [--profile FILE]\n"
    "                       [--tolerance-a T] [--tolerance-c T]\n"
    "\n"
    "Compares a ddcontact run of a sphere on a block (examples/hertz_sphere.xml) with Hertz's\n"
    "solution for the contact force the run transmits (doc/contact.md, \"Hertz contact\").\n"
    "\n"
    "  OUT_DIR         the run's output directory: parameters.xml and contact_nodes.csv\n"
    "                  (Output/Contact Nodes = true)\n"
    "  --sphere BODY   the sphere body, a Sphere Octant (default: Sphere)\n"
    "  --block BODY    the block body (default: Block)\n"
    "  --profile FILE  write r,p_fe,p_hertz for every slave node\n"
    "  --tolerance T   exit 1 if the contact radius or peak pressure differs from Hertz's by\n"
    "                  more than T (relative)\n"
    "\n"
    "A dynamic run (examples/sphere_impact.xml) is compared with Hertz's impact solution\n"
    "instead: contact time and peak force from OUT_DIR/history.csv (--tolerance applies to both).\n"
    "\n"
    "--cattaneo: a plane-strain cylinder pressed on a block of the same material and pushed\n"
    "sideways by Q < mu P (examples/cattaneo_2d.xml; doc/contact.md, \"Cattaneo\"): the contact\n"
    "half-width a against Hertz's for the transmitted P, and with friction (the pair's Friction\n"
    "Coefficient mu > 0) and Q > 0 the stick half-width c against Cattaneo's a sqrt(1 - Q/(mu P)).\n"
    "The deck has one contact pair, the cylinder's surface its slave side (R and the axis are\n"
    "fitted to the slave nodes), the contact normal along y and Q along x.\n"
    "  --cylinder BODY  the cylinder body (default: Cylinder)\n"
    "  --profile FILE   write x,p_fe,p_hertz,q_fe,q_cattaneo,state for every slave node\n"
    "  --tolerance-a T  exit 1 if a differs from Hertz's by more than T (relative)\n"
    "  --tolerance-c T  exit 1 if c differs from Cattaneo's by more than T (relative; needs\n"
    "                   mu > 0 and Q > 0)\n"
    "\n"
    "--mindlin: a sphere pressed on a block of the same material and pushed sideways by\n"
    "Q < mu P (examples/mindlin_sphere.xml, half of the problem, the plane y = 0 a symmetry\n"
    "plane; doc/contact.md, \"Mindlin\"): the contact radius a against Hertz's for the\n"
    "transmitted P, and with friction and Q > 0 the stick radius c against Mindlin's\n"
    "a (1 - Q/(mu P))^(1/3). P and Q are twice the model's. The deck has one contact pair, the\n"
    "sphere's surface its slave side (R and the axis are fitted to the slave nodes), the\n"
    "contact normal along z and Q along x. --sphere names the sphere body (default: Sphere),\n"
    "--profile writes x,y,r,p_fe,p_hertz,q_fe,q_mindlin,state, --tolerance-a / -c as above.\n";

/// The Sphere Octant is a quarter of a hemisphere: the whole sphere's
/// contact force is 4 times the model's.
constexpr double kQuarterModel = 4.0;
/// A slave node "on the axis": within this fraction of the radius of it
/// (the generator puts the pole node exactly on it).
constexpr double kOnAxis = 1e-9;

/// A column of history.csv by name.
std::vector<double> historyColumn(const std::string& file, const std::string& name) {
  std::ifstream in(file);
  if (!in) throw BadInput("cannot read '" + file + "'");
  std::string line;
  std::getline(in, line);
  std::istringstream hs(line);
  std::string cell;
  int col = -1;
  for (int i = 0; std::getline(hs, cell, ','); ++i)
    if (cell == name) col = i;
  if (col < 0) throw BadInput(file + ": no column '" + name + "'");
  std::vector<double> out;
  int lineNo = 1;
  while (std::getline(in, line)) {
    ++lineNo;
    std::istringstream ls(line);
    for (int i = 0; std::getline(ls, cell, ','); ++i)
      if (i == col) {
        char* end = nullptr;
        out.push_back(std::strtod(cell.c_str(), &end));
        if (cell.empty() || *end != '\0')
          throw BadInput(file + ":" + std::to_string(lineNo) + ": not a number: '" + cell + "'");
      }
    if (out.size() != size_t(lineNo - 1)) throw BadInput(file + ":" + std::to_string(lineNo) + ": too few columns");
  }
  if (out.size() < 2) throw BadInput(file + ": fewer than two steps");
  return out;
}

/// Hertz's impact solution against a dynamic run (see the top of this file).
int impact(const std::string& dir, const Teuchos::ParameterList& deck, const std::string& xml,
           const std::string& sphere, const std::string& block, double R, double tolerance) {
  const Material m1 = materialOf(deck, sphere, xml), m2 = materialOf(deck, block, xml);
  const auto& mat = deck.sublist("Mesh").sublist("Bodies").sublist(sphere).sublist("Element").sublist("Material");
  const double rho = mat.isParameter("Density") ? mat.get<double>("Density") : 0.0;
  if (!(rho > 0)) throw BadInput(xml + ": 'Mesh/Bodies/" + sphere + "/Element/Material/Density' must be > 0");
  double v = 0.0;
  const auto& conditions = deck.sublist("Dynamics").sublist("Initial Velocity");
  for (auto it = conditions.begin(); it != conditions.end(); ++it) {
    const auto& c = conditions.sublist(conditions.name(it));
    if (c.get<std::string>("Set") == sphere) v = -c.get<double>("Velocity Z");
  }
  if (!(v > 0))
    throw BadInput(xml + ": no 'Dynamics/Initial Velocity' condition gives the body '" + sphere +
                   "' a velocity Z < 0 (towards the block)");
  const std::string file = dir + "/history.csv";
  const auto t = historyColumn(file, "time"), fz = historyColumn(file, "contact_force_z");
  const auto active = historyColumn(file, "active_contacts");
  double fMax = 0.0, last = -1.0;
  for (size_t i = 0; i < t.size(); ++i) {
    fMax = std::max(fMax, std::abs(fz[i]));
    if (active[i] > 0) last = t[i];
  }
  if (last < 0) throw BadInput(file + ": no step in contact");
  if (last == t.back()) throw BadInput(file + ": still in contact at the last step (a longer Final Time)");
  const double h = t[1] - t[0];
  const double tc = last + 0.5 * h;
  fMax *= kQuarterModel;
  const double m = rho * 2.0 * kPi * R * R * R / 3.0;
  const double Estar = 1.0 / ((1.0 - m1.nu * m1.nu) / m1.E + (1.0 - m2.nu * m2.nu) / m2.E);
  const double delta = std::pow(15.0 * m * v * v / (16.0 * Estar * std::sqrt(R)), 0.4);
  const double fHertz = 4.0 / 3.0 * Estar * std::sqrt(R) * std::pow(delta, 1.5);
  const double tcHertz = 2.9432 * delta / v;
  const double errT = (tc - tcHertz) / tcHertz, errF = (fMax - fHertz) / fHertz;
  std::printf("Hertz impact: hemisphere '%s' R = %g, rho = %g (m = %.6g, 4 x the quarter model), v = %g, on '%s': "
              "E* = %.6g\n",
              sphere.c_str(), R, rho, m, v, block.c_str(), Estar);
  std::printf("delta_max = %.6g (delta_max / R = %.4g), time step %g\n", delta, delta / R, h);
  std::printf("%-22s %12s %12s %10s\n", "quantity", "ddcontact", "Hertz", "rel. error");
  std::printf("%-22s %12.6g %12.6g %+10.4f\n", "contact time t_c", tc, tcHertz, errT);
  std::printf("%-22s %12.6g %12.6g %+10.4f\n", "peak force F_max", fMax, fHertz, errF);
  if (tolerance > 0) {
    const bool ok = std::abs(errT) <= tolerance && std::abs(errF) <= tolerance;
    std::printf("check: |errors| <= %g: %s\n", tolerance, ok ? "passed" : "FAILED");
    return ok ? 0 : 1;
  }
  return 0;
}

/// The command line (kUsage).
struct Options {
  std::string dir, sphere = "Sphere", block = "Block", profile, cylinder = "Cylinder";
  double tolerance = -1.0, toleranceA = -1.0, toleranceC = -1.0;
  bool cattaneo = false, mindlin = false;
  bool help = false;  ///< --help: print kUsage, nothing else
};

/// The value of option `name`, a number > 0. \throws BadInput
double positiveNumber(const std::string& name, const std::string& t) {
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (t.empty() || *end != '\0' || !(v > 0)) throw BadInput(name + " needs a number > 0, got '" + t + "'");
  return v;
}

/// The options; stops at --help. \throws BadInput for a bad command line.
Options parseArguments(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw BadInput("option " + a + " needs a value");
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      o.help = true;
      return o;
    } else if (a == "--sphere") {
      o.sphere = value();
    } else if (a == "--block") {
      o.block = value();
    } else if (a == "--profile") {
      o.profile = value();
    } else if (a == "--tolerance") {
      o.tolerance = positiveNumber(a, value());
    } else if (a == "--cattaneo") {
      o.cattaneo = true;
    } else if (a == "--mindlin") {
      o.mindlin = true;
    } else if (a == "--cylinder") {
      o.cylinder = value();
    } else if (a == "--tolerance-a") {
      o.toleranceA = positiveNumber(a, value());
    } else if (a == "--tolerance-c") {
      o.toleranceC = positiveNumber(a, value());
    } else if (!a.empty() && a[0] == '-') {
      throw BadInput("unknown option '" + a + "'");
    } else if (o.dir.empty()) {
      o.dir = a;
    } else {
      throw BadInput("more than one output directory ('" + o.dir + "', '" + a + "')");
    }
  }
  if (o.dir.empty()) throw BadInput("no output directory given");
  if (o.cattaneo && o.mindlin) throw BadInput("--cattaneo and --mindlin exclude each other; give one");
  if (o.cattaneo && o.tolerance > 0) throw BadInput("--cattaneo takes --tolerance-a and --tolerance-c, not --tolerance");
  if (o.mindlin && o.tolerance > 0) throw BadInput("--mindlin takes --tolerance-a and --tolerance-c, not --tolerance");
  if (!o.cattaneo && !o.mindlin && (o.toleranceA > 0 || o.toleranceC > 0))
    throw BadInput("--tolerance-a and --tolerance-c apply to --cattaneo and --mindlin only (use --tolerance)");
  return o;
}

/// The contact radius from a least-squares fit of p^2 = A + B r^2 over the
/// active nodes: sqrt(-A / B), NaN where the fit has no such root.
double fittedContactRadius(const std::vector<Row>& rows) {
  std::vector<double> r, p2;
  for (const Row& row : rows)
    if (row.active) r.push_back(row.r), p2.push_back(row.pressure * row.pressure);
  return fittedHalfWidth(r, p2);
}

/// Hertz's static solution against the contact nodes of a static run
/// (see the top of this file); the sphere's radius R and axis (cx, cy).
int staticContact(const Options& o, const Material& m1, const Material& m2, double R, double cx, double cy) {
  const auto rows = readContactNodes(o.dir + "/contact_nodes.csv", cx, cy);
  double force = 0.0, p0 = -1.0, rActive = 0.0;
  int active = 0;
  for (const Row& r : rows)
    if (r.active) {
      force += std::abs(r.multiplier);
      ++active;
      rActive = std::max(rActive, r.r);
      if (r.r <= kOnAxis * R) p0 = r.pressure;
    }
  if (p0 < 0) throw BadInput(o.dir + "/contact_nodes.csv: no active slave node on the sphere's axis");
  double rInactive = std::numeric_limits<double>::infinity();
  for (const Row& r : rows)
    if (!r.active && r.r > rActive) rInactive = std::min(rInactive, r.r);
  const double aFit = fittedContactRadius(rows);

  force *= kQuarterModel;
  const double Estar = 1.0 / ((1.0 - m1.nu * m1.nu) / m1.E + (1.0 - m2.nu * m2.nu) / m2.E);
  const double a = std::cbrt(3.0 * force * R / (4.0 * Estar));
  const double p0Hertz = 3.0 * force / (2.0 * kPi * a * a);
  const double errA = (aFit - a) / a, errP = (p0 - p0Hertz) / p0Hertz;

  std::printf("Hertz contact: sphere '%s' R = %g (E = %g, nu = %g) on '%s' (E = %g, nu = %g): E* = %.6g\n",
              o.sphere.c_str(), R, m1.E, m1.nu, o.block.c_str(), m2.E, m2.nu, Estar);
  std::printf("contact force F = %.6g (4 x the quarter model), %d active slave nodes, a/R = %.4f\n", force, active, a / R);
  std::printf("%-22s %12s %12s %10s\n", "quantity", "ddcontact", "Hertz", "rel. error");
  std::printf("%-22s %12.6g %12.6g %+10.4f\n", "contact radius a (fit)", aFit, a, errA);
  std::printf("%-22s %12.6g %12.6g %+10.4f\n", "peak pressure p0", p0, p0Hertz, errP);
  std::printf("active nodes reach r = %.6g; the next inactive node is at r = %.6g\n", rActive, rInactive);

  if (!o.profile.empty()) {
    std::ofstream out(o.profile);
    out << "r,p_fe,p_hertz\n";
    out.precision(10);
    for (const Row& r : rows) out << r.r << ',' << r.pressure << ',' << (r.r < a ? p0Hertz * std::sqrt(1 - r.r * r.r / (a * a)) : 0.0) << '\n';
    if (!out.flush()) throw BadInput("cannot write '" + o.profile + "'");
  }
  if (o.tolerance > 0) {
    const bool ok = std::abs(errA) <= o.tolerance && std::abs(errP) <= o.tolerance;
    std::printf("check: |errors| <= %g: %s\n", o.tolerance, ok ? "passed" : "FAILED");
    return ok ? 0 : 1;
  }
  return 0;
}

int run(int argc, char** argv) {
  const Options o = parseArguments(argc, argv);
  if (o.help) {
    std::cout << kUsage;
    return 0;
  }
  const std::string xml = o.dir + "/parameters.xml";
  if (!std::ifstream(xml)) throw BadInput("cannot read '" + xml + "'");
  Teuchos::RCP<Teuchos::ParameterList> deck;
  try {
    deck = Teuchos::getParametersFromXmlFile(xml);
  } catch (const std::exception& e) {
    throw BadInput(xml + ": " + e.what());
  }
  if (o.cattaneo) {
    CattaneoOptions c;
    c.dir = o.dir, c.cylinder = o.cylinder, c.block = o.block, c.profile = o.profile;
    c.toleranceA = o.toleranceA, c.toleranceC = o.toleranceC;
    return cattaneo(c, *deck, xml);
  }
  if (o.mindlin) {
    MindlinOptions m;
    m.dir = o.dir, m.sphere = o.sphere, m.block = o.block, m.profile = o.profile;
    m.toleranceA = o.toleranceA, m.toleranceC = o.toleranceC;
    return mindlin(m, *deck, xml);
  }
  const auto& bodies = deck->sublist("Mesh").sublist("Bodies");
  if (!bodies.isSublist(o.sphere)) throw BadInput(xml + ": no body '" + o.sphere + "' (use --sphere)");
  const auto& sb = bodies.sublist(o.sphere);
  if (!sb.isParameter("Generator") || sb.get<std::string>("Generator") != "Sphere Octant")
    throw BadInput(xml + ": 'Mesh/Bodies/" + o.sphere + "/Generator' must be 'Sphere Octant'");
  const auto& oct = sb.sublist("Sphere Octant");
  const double R = oct.get<double>("Radius"), cx = oct.get<double>("Center X"), cy = oct.get<double>("Center Y");
  if (deck->isSublist("Dynamics") && deck->sublist("Dynamics").isParameter("Integrator") &&
      deck->sublist("Dynamics").get<std::string>("Integrator") != "None")
    return impact(o.dir, *deck, xml, o.sphere, o.block, R, o.tolerance);
  const Material m1 = materialOf(*deck, o.sphere, xml), m2 = materialOf(*deck, o.block, xml);
  return staticContact(o, m1, m2, R, cx, cy);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const BadInput& e) {
    std::cerr << "ddcontact-hertz: " << e.what() << "\n" << (argc < 2 ? kUsage : "");
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "ddcontact-hertz: " << e.what() << "\n";
    return 2;
  }
}
