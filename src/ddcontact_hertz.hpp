// What the modes of ddcontact-hertz share (src/ddcontact_hertz.cpp: the
// sphere and the impact; src/ddcontact_hertz_cattaneo.cpp: the cylinder
// with friction; src/ddcontact_hertz_mindlin.cpp: the sphere with
// friction): the input errors, contact_nodes.csv, the materials of the
// deck, the least-squares fit of the contact half-width.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace ddc_hertz {

/// Bad input (usage, missing or malformed files, a deck that is not the
/// case): exit status 2.
struct BadInput : std::runtime_error {
  using std::runtime_error::runtime_error;
};

constexpr double kPi = 3.14159265358979323846;

/// A row of contact_nodes.csv (doc/user-guide.md, "The output directory"),
/// with r, the distance of (x, y) from the point given to readContactNodes().
struct Row {
  double r = 0, x = 0, y = 0, z = 0, multiplier = 0, tributary = 0, pressure = 0;
  bool active = false;
  double tangential[3] = {0, 0, 0};  ///< tangential force on the slave node
  double slip = 0;
  int state = 0;  ///< 0 open, 1 stick, 2 slip
};

struct Material {
  double E = 0, nu = 0;
};

/// Young's modulus and Poisson's ratio of `body` in the deck read from `file`.
Material materialOf(const Teuchos::ParameterList& deck, const std::string& body, const std::string& file);

/// The rows of a contact_nodes.csv, r measured from (cx, cy).
std::vector<Row> readContactNodes(const std::string& file, double cx, double cy);

/// The friction coefficient of the deck's one contact pair
/// ("Contact/Pairs/<pair>/Friction Coefficient", 0 without it) and its name
/// in `pair`. \throws BadInput (naming `mode`) unless the deck has one pair.
double frictionCoefficient(const Teuchos::ParameterList& deck, const std::string& xml, const std::string& mode,
                           std::string& pair);

/// The contact half-width of an elliptical profile from a least-squares fit
/// of y = A + B s^2 over the points (s, y): sqrt(-A / B), NaN where the fit
/// has no such root (y = p^2 for Hertz's p, (mu p - |q|)^2 for Cattaneo's
/// stick zone).
double fittedHalfWidth(const std::vector<double>& s, const std::vector<double>& y);

/// What a run transmits over the active slave nodes of a frictional
/// contact: P = Σ|λ_n|, Q = |Σ tangential_x| (the load along x), both times
/// `modelFactor` (the whole problem of a symmetric part model), and the
/// numbers of nodes in contact, sticking and slipping.
struct Totals {
  double P = 0, Q = 0;
  int active = 0, stick = 0, slip = 0;
};
Totals transmitted(const std::vector<Row>& rows, double modelFactor);

/// Fewest stick nodes c is fitted from (two distinct distances at least).
constexpr int kMinStickNodes = 3;

/// A number as %g prints it.
std::string num(double v);

/// The input checks of a partial-slip comparison (--cattaneo, --mindlin):
/// contact, Q < mu P (else the `body` slides; `theory` names the
/// solution), enough stick nodes to fit c, and --tolerance-c only with
/// friction and a tangential load. \throws BadInput naming `file`
void checkPartialSlipRun(const Totals& t, double mu, double toleranceC, const std::string& file,
                         const std::string& body, const std::string& theory);

/// The options of --cattaneo (see kUsage in src/ddcontact_hertz.cpp).
struct CattaneoOptions {
  std::string dir, cylinder = "Cylinder", block = "Block", profile;
  double toleranceA = -1.0, toleranceC = -1.0;  ///< <= 0: no check
};

/// Cattaneo's line contact against a run of examples/cattaneo_2d.xml; the
/// exit status. \throws BadInput
int cattaneo(const CattaneoOptions& o, const Teuchos::ParameterList& deck, const std::string& xml);

/// The options of --mindlin (see kUsage in src/ddcontact_hertz.cpp).
struct MindlinOptions {
  std::string dir, sphere = "Sphere", block = "Block", profile;
  double toleranceA = -1.0, toleranceC = -1.0;  ///< <= 0: no check
};

/// Mindlin's circular contact against a run of examples/mindlin_sphere.xml;
/// the exit status. \throws BadInput
int mindlin(const MindlinOptions& o, const Teuchos::ParameterList& deck, const std::string& xml);

}  // namespace ddc_hertz
