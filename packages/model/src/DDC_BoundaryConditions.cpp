#include "DDC_BoundaryConditions.hpp"

#include <cctype>
#include <cmath>
#include <sstream>

#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

double loadCurveValue(const std::vector<std::array<double, 2>>& curve, double lambda) {
  if (curve.empty()) return lambda;
  if (lambda <= curve.front()[0]) return curve.front()[1];
  for (std::size_t i = 1; i < curve.size(); ++i)
    if (lambda <= curve[i][0]) {
      const double t = (lambda - curve[i - 1][0]) / (curve[i][0] - curve[i - 1][0]);
      return (1.0 - t) * curve[i - 1][1] + t * curve[i][1];
    }
  return curve.back()[1];
}

double DisplacementCondition::scale(double lambda) const { return loadCurveValue(curve, lambda); }

double TractionCondition::scale(double lambda) const { return loadCurveValue(curve, lambda); }

double DisplacementCondition::prescribed(int c, const std::array<double, 3>& X, double loadFactor) const {
  const double lambda = scale(loadFactor);
  const double d[3] = {X[0] - center[0], X[1] - center[1], X[2] - center[2]};
  double u = lambda * (value[c] + gradient[c][0] * d[0] + gradient[c][1] * d[1] + gradient[c][2] * d[2]);
  if (angleRadians != 0.0) {
    // Rodrigues: R d = cos(a) d + sin(a) (k x d) + (1 - cos(a)) (k . d) k.
    const double a = lambda * angleRadians, ca = std::cos(a), sa = std::sin(a);
    const double* k = axis;
    const double kxd[3] = {k[1] * d[2] - k[2] * d[1], k[2] * d[0] - k[0] * d[2], k[0] * d[1] - k[1] * d[0]};
    const double kd = k[0] * d[0] + k[1] * d[1] + k[2] * d[2];
    u += ca * d[c] + sa * kxd[c] + (1.0 - ca) * kd * k[c] - d[c];
  }
  return u;
}

namespace {
const char* const kAxes[3] = {"X", "Y", "Z"};

/// "λ s, λ s, ..." -> points; at least two, λ strictly increasing, all finite.
std::vector<std::array<double, 2>> parseLoadCurve(const std::string& text, const std::string& where) {
  std::vector<std::array<double, 2>> points;
  std::istringstream all(text);
  std::string item;
  const std::string expected = "expected pairs 'load-factor value' separated by commas, e.g. '0 0, 0.25 1, 1 1'";
  while (std::getline(all, item, ',')) {
    std::istringstream one(item);
    std::array<double, 2> p{};
    std::string rest;
    DDC_INPUT_REQUIRE((one >> p[0] >> p[1]) && !(one >> rest) && std::isfinite(p[0]) && std::isfinite(p[1]),
                      "parameter '" << where << "' = '" << text << "': cannot read '" << item << "' ("
                                    << expected << ")");
    DDC_INPUT_REQUIRE(points.empty() || p[0] > points.back()[0],
                      "parameter '" << where << "' = '" << text << "': the load factors must increase strictly ("
                                    << p[0] << " follows " << points.back()[0] << ")");
    points.push_back(p);
  }
  DDC_INPUT_REQUIRE(points.size() >= 2, "parameter '" << where << "' = '" << text << "': a load curve needs at least "
                                                         "two points (" << expected << ")");
  return points;
}
}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> BoundaryConditions::getValidParameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<Condition Name>"));
  pl->set("Type", "Displacement",
          "Displacement: prescribed displacement on a node set. Traction: dead force per unit "
          "reference length (2-D) or area (3-D) on a side set. Both are scaled by the load factor.",
          enumValidator({"Displacement", "Traction"}, "Type"));
  pl->set("Set", "", "Qualified set name 'Body/set', e.g. 'Block/left' (a node set for "
                     "Displacement, a side set for Traction).");
  pl->set("Components", "All",
          "Displacement: which components are prescribed; All = X and Y in 2-D, X, Y and Z in 3-D. "
          "Components with Z need a 3-D model.",
          enumValidator({"All", "X", "Y", "Z", "XY", "XZ", "YZ", "XYZ"}, "Components"));
  // Every value must be finite (the validators): a NaN or inf would reach the
  // solver as a non-finite residual and end the run with bisections. Values
  // and tractions also stay below kMaxLoadMagnitude: a traction of 1e300
  // times an area, or a displacement of 1e300 squared in a strain, overflowed
  // in the element arithmetic and the message named a node, not the value.
  constexpr double kMaxLoadMagnitude = 1e100;
  for (const char* a : kAxes)
    pl->set(std::string("Value ") + a, 0.0,
            std::string("Displacement: ") + char(std::tolower(a[0])) +
                " displacement at load factor 1 (scaled by the load factor)" + (a[0] == 'Z' ? "; 3-D only." : "."),
            finiteMagnitude(kMaxLoadMagnitude));
  for (const char* r : kAxes)
    for (const char* c : kAxes)
      pl->set(std::string("Gradient ") + r + c, 0.0,
              "Displacement: component of the displacement gradient H at load factor 1 (Gradient XY = "
              "du_x/dY); adds H (X - centre) to the values, for affine fields. Entries with Z: 3-D only.",
              finiteNumber());
  pl->set("Load Curve", "",
          "Piecewise-linear factor s(load factor) of a displacement's values, gradient and angle or of a "
          "traction, as points 'load-factor value' separated by commas, load factors strictly increasing, "
          "constant beyond the first and last point; e.g. '0 0, 0.25 1, 1 1' applies the values by load "
          "factor 0.25 and holds them, '0 0, 0.25 0, 1 1' starts them at 0.25. Empty: s = the load factor. "
          "A traction's Load Curve is for static runs (Dynamics/Integrator = None).");
  pl->set("Rotation Angle", 0.0,
          "Displacement: rigid rotation (degrees, counter-clockwise about the rotation axis) about the centre at "
          "load factor 1, added to the values; the angle grows linearly with the load factor. Needs every "
          "component prescribed (Components = All).",
          finiteNumber());
  for (const char* a : kAxes)
    pl->set(std::string("Rotation Axis ") + a, a[0] == 'Z' ? 1.0 : 0.0,
            "Displacement: component of the rotation axis (any length > 0; normalised). 2-D models rotate "
            "about z only (the default).",
            finiteNumber());
  for (const char* a : kAxes)
    pl->set(std::string("Center ") + a, 0.0,
            std::string("Displacement: ") + char(std::tolower(a[0])) +
                " of the centre of the rotation and of the gradient field" + (a[0] == 'Z' ? "; 3-D only." : "."),
            finiteNumber());
  for (const char* a : kAxes)
    pl->set(std::string("Traction ") + a, 0.0,
            std::string("Traction: ") + char(std::tolower(a[0])) +
                " force per unit reference length (2-D) or area (3-D) at load factor 1" +
                (a[0] == 'Z' ? "; 3-D only." : "."),
            finiteMagnitude(kMaxLoadMagnitude));
  return pl;
}

namespace {

/// One condition's sublist `p` at `where`, validated, with the checks the
/// two types share: which parameters are set (differ from their defaults)
/// and may be.
struct ConditionList {
  Teuchos::ParameterList& p;
  const Teuchos::ParameterList& valid;
  const std::string& where;
  const std::string& type;
  const int dim;

  bool isSet(const std::string& key) const {
    return p.isParameter(key) && p.get<double>(key) != valid.get<double>(key);
  }
  void forbid(const std::string& key) const {
    DDC_INPUT_REQUIRE(!isSet(key), "parameter '" << where << "/" << key << "' does not apply to Type = " << type);
  }
  /// Z parameters need a 3-D model; a 2-D model also rotates about z only.
  void forbid2d(const std::string& key) const {
    DDC_INPUT_REQUIRE(dim == 3 || !isSet(key), "parameter '" << where << "/" << key << "' is set but the model is "
                                                             << dim << "-D; Z applies to 3-D models only");
  }
};

/// The rotation and the checks between components, values and gradients
/// of a displacement condition whose other fields are read.
void readRotation(const ConditionList& c, const std::string& comps, DisplacementCondition& d) {
  Teuchos::ParameterList& p = c.p;
  const std::string& where = c.where;
  const int dim = c.dim;
  d.angleRadians = p.get<double>("Rotation Angle") * M_PI / 180.0;
  const double ax[3] = {p.get<double>("Rotation Axis X"), p.get<double>("Rotation Axis Y"),
                        p.get<double>("Rotation Axis Z")};
  const double axisLength = std::sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
  DDC_INPUT_REQUIRE(axisLength > 0.0 && std::isfinite(axisLength),
                    "'" << where << "': the rotation axis (Rotation Axis X/Y/Z) must have a finite length > 0");
  for (int k = 0; k < 3; ++k) d.axis[k] = dim == 2 ? (k == 2 ? 1.0 : 0.0) : ax[k] / axisLength;
  for (int k = 0; k < dim; ++k) {
    const std::string a = kAxes[k];
    DDC_INPUT_REQUIRE(d.fix[k] || (d.gradient[k][0] == 0.0 && d.gradient[k][1] == 0.0 && d.gradient[k][2] == 0.0),
                      "'" << where << "': Gradient " << a << "X/" << a << "Y" << (dim == 3 ? "/" + a + "Z" : "")
                          << " set but Components = " << comps << " does not prescribe " << a);
    DDC_INPUT_REQUIRE(d.fix[k] || d.value[k] == 0.0,
                      "'" << where << "/Value " << a << "' is set but Components = " << comps
                          << " does not prescribe " << a);
  }
  bool all = true;
  for (int k = 0; k < dim; ++k) all = all && d.fix[k];
  DDC_INPUT_REQUIRE(d.angleRadians == 0.0 || all,
                    "'" << where << "': a Rotation Angle needs every component prescribed (Components = All)");
}

/// Type = Displacement: on a node set of the mesh.
DisplacementCondition readDisplacement(const ConditionList& c, const std::string& name, const std::string& set,
                                       const Mesh& mesh) {
  Teuchos::ParameterList& p = c.p;
  const std::string& where = c.where;
  const int dim = c.dim;
  for (const char* a : kAxes) c.forbid(std::string("Traction ") + a);
  try {
    mesh.nodeSet(set);
  } catch (const InputError& e) {
    throw InputError("boundary condition '" + where + "': " + e.what());
  }
  DisplacementCondition d;
  d.name = name;
  d.setName = set;
  const std::string comps = p.get<std::string>("Components");
  DDC_INPUT_REQUIRE(dim == 3 || comps.find('Z') == std::string::npos,
                    "parameter '" << where << "/Components' = " << comps << " prescribes Z but the model is "
                                  << dim << "-D; Z applies to 3-D models only");
  for (const char* key : {"Value Z", "Gradient XZ", "Gradient YZ", "Gradient ZX", "Gradient ZY", "Gradient ZZ",
                          "Center Z", "Rotation Axis X", "Rotation Axis Y"})
    c.forbid2d(key);
  DDC_INPUT_REQUIRE(dim == 3 || p.get<double>("Rotation Axis Z") > 0.0,
                    "parameter '" << where << "/Rotation Axis Z' must be > 0 in a 2-D model (rotation about z)");
  for (int k = 0; k < 3; ++k) {
    d.fix[k] = k < dim && (comps == "All" || comps.find(kAxes[k][0]) != std::string::npos);
    d.value[k] = p.get<double>(std::string("Value ") + kAxes[k]);
    d.center[k] = p.get<double>(std::string("Center ") + kAxes[k]);
    for (int l = 0; l < 3; ++l) d.gradient[k][l] = p.get<double>(std::string("Gradient ") + kAxes[k] + kAxes[l]);
  }
  if (!p.get<std::string>("Load Curve").empty())
    d.curve = parseLoadCurve(p.get<std::string>("Load Curve"), where + "/Load Curve");
  readRotation(c, comps, d);
  return d;
}

/// Type = Traction: on a side set of the mesh.
TractionCondition readTraction(const ConditionList& c, const std::string& name, const std::string& set,
                               const Mesh& mesh) {
  Teuchos::ParameterList& p = c.p;
  const std::string& where = c.where;
  const int dim = c.dim;
  for (const char* a : kAxes) {
    c.forbid(std::string("Value ") + a);
    c.forbid(std::string("Center ") + a);
    for (const char* b : kAxes) c.forbid(std::string("Gradient ") + a + b);
  }
  for (const char* key : {"Rotation Angle", "Rotation Axis X", "Rotation Axis Y", "Rotation Axis Z"}) c.forbid(key);
  // "XY" was the default in 2-D before "All"; decks that spell it out keep working.
  const std::string comps = p.isParameter("Components") ? p.get<std::string>("Components") : "All";
  DDC_INPUT_REQUIRE(comps == "All" || (dim == 2 && comps == "XY"),
                    "parameter '" << where << "/Components' does not apply to Type = Traction");
  c.forbid2d("Traction Z");
  // A node set of points or edges (a Gmsh physical point or curve of a
  // 3-D body) has nothing to integrate a traction over.
  DDC_INPUT_REQUIRE(mesh.hasSideSet(set) || !mesh.hasNodeSet(set),
                    "boundary condition '" << where << "': 'Set' = '" << set << "' is a set of nodes, not of "
                                           << (dim == 2 ? "element sides" : "element faces")
                                           << "; a traction acts on a side set (a generator's named "
                                              "face, a Gmsh physical surface of a 3-D body or physical "
                                              "curve of a 2-D body)");
  try {
    mesh.sideSet(set);
  } catch (const InputError& e) {
    throw InputError("boundary condition '" + where + "': " + e.what());
  }
  TractionCondition t;
  t.name = name;
  t.setName = set;
  for (int k = 0; k < 3; ++k) t.traction[k] = p.get<double>(std::string("Traction ") + kAxes[k]);
  if (!p.get<std::string>("Load Curve").empty())
    t.curve = parseLoadCurve(p.get<std::string>("Load Curve"), where + "/Load Curve");
  return t;
}

}  // namespace

BoundaryConditions BoundaryConditions::fromParameters(Teuchos::ParameterList& list, const Mesh& mesh,
                                                      const std::string& path) {
  BoundaryConditions bcs;
  const auto valid = getValidParameters();
  for (auto it = list.begin(); it != list.end(); ++it) {
    const std::string& name = list.name(it);
    const std::string where = joinPath(path, name);
    DDC_INPUT_REQUIRE(list.isSublist(name), "'" << where << "' must be a sublist describing one condition");
    auto& p = list.sublist(name);
    validateLevel(p, *valid, where);
    const std::string type = p.get<std::string>("Type");
    const std::string set = p.get<std::string>("Set");
    DDC_INPUT_REQUIRE(!set.empty(), "parameter '" << where << "/Set' is required (a set name 'Body/set')");
    const ConditionList condition{p, *valid, where, type, mesh.dim()};
    if (type == "Displacement")
      bcs.displacements.push_back(readDisplacement(condition, name, set, mesh));
    else
      bcs.tractions.push_back(readTraction(condition, name, set, mesh));
  }
  return bcs;
}

}  // namespace ddc
