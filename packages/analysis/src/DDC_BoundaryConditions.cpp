#include "DDC_BoundaryConditions.hpp"

#include <cmath>

#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

double DisplacementCondition::prescribed(int c, const std::array<double, 3>& X, double lambda) const {
  const double dx = X[0] - center[0], dy = X[1] - center[1];
  double u = lambda * (value[c] + gradient[c][0] * dx + gradient[c][1] * dy);
  if (angleRadians != 0.0) {
    const double a = lambda * angleRadians;
    const double rx = std::cos(a) * dx - std::sin(a) * dy;
    const double ry = std::sin(a) * dx + std::cos(a) * dy;
    u += (c == 0) ? rx - dx : ry - dy;
  }
  return u;
}

Teuchos::RCP<const Teuchos::ParameterList> BoundaryConditions::getValidParameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<Condition Name>"));
  pl->set("Type", "Displacement",
          "Displacement: prescribed displacement on a node set. Traction: dead force per unit "
          "reference length on a side set. Both are scaled by the load factor.",
          enumValidator({"Displacement", "Traction"}, "Type"));
  pl->set("Set", "", "Qualified set name 'Body/set', e.g. 'Block/left' (a node set for "
                     "Displacement, a side set for Traction).");
  pl->set("Components", "XY", "Displacement: which components are prescribed.",
          enumValidator({"X", "Y", "XY"}, "Components"));
  // Every value must be finite (the validators): a NaN or inf would reach the
  // solver as a non-finite residual and end the run with bisections.
  pl->set("Value X", 0.0, "Displacement: x displacement at load factor 1 (scaled by the load factor).",
          finiteNumber());
  pl->set("Value Y", 0.0, "Displacement: y displacement at load factor 1 (scaled by the load factor).",
          finiteNumber());
  for (const char* g : {"Gradient XX", "Gradient XY", "Gradient YX", "Gradient YY"})
    pl->set(g, 0.0,
            "Displacement: component of the displacement gradient H at load factor 1 (Gradient XY = "
            "du_x/dY); adds H (X - centre) to the values, for affine fields.",
            finiteNumber());
  pl->set("Rotation Angle", 0.0,
          "Displacement: rigid rotation (degrees, counter-clockwise) about the centre at load factor 1, "
          "added to the values; the angle grows linearly with the load factor. Needs Components = XY.",
          finiteNumber());
  pl->set("Center X", 0.0, "Displacement: x of the centre of the rotation and of the gradient field.",
          finiteNumber());
  pl->set("Center Y", 0.0, "Displacement: y of the centre of the rotation and of the gradient field.",
          finiteNumber());
  pl->set("Traction X", 0.0, "Traction: x force per unit reference length at load factor 1.", finiteNumber());
  pl->set("Traction Y", 0.0, "Traction: y force per unit reference length at load factor 1.", finiteNumber());
  return pl;
}

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
    const bool isDisp = type == "Displacement";
    auto forbid = [&](const char* key) {
      DDC_INPUT_REQUIRE(!p.isParameter(key) || p.get<double>(key) == valid->get<double>(key),
                        "parameter '" << where << "/" << key << "' does not apply to Type = " << type);
    };
    if (isDisp) {
      forbid("Traction X");
      forbid("Traction Y");
      try {
        mesh.nodeSet(set);
      } catch (const InputError& e) {
        throw InputError("boundary condition '" + where + "': " + e.what());
      }
      DisplacementCondition d;
      d.name = name;
      d.setName = set;
      const std::string comps = p.get<std::string>("Components");
      d.fix[0] = comps.find('X') != std::string::npos;
      d.fix[1] = comps.find('Y') != std::string::npos;
      d.value[0] = p.get<double>("Value X");
      d.value[1] = p.get<double>("Value Y");
      d.angleRadians = p.get<double>("Rotation Angle") * M_PI / 180.0;
      d.center[0] = p.get<double>("Center X");
      d.center[1] = p.get<double>("Center Y");
      d.gradient[0][0] = p.get<double>("Gradient XX");
      d.gradient[0][1] = p.get<double>("Gradient XY");
      d.gradient[1][0] = p.get<double>("Gradient YX");
      d.gradient[1][1] = p.get<double>("Gradient YY");
      DDC_INPUT_REQUIRE(d.fix[0] || (d.gradient[0][0] == 0.0 && d.gradient[0][1] == 0.0),
                        "'" << where << "': Gradient XX/XY set but Components = " << comps << " does not prescribe X");
      DDC_INPUT_REQUIRE(d.fix[1] || (d.gradient[1][0] == 0.0 && d.gradient[1][1] == 0.0),
                        "'" << where << "': Gradient YX/YY set but Components = " << comps << " does not prescribe Y");
      DDC_INPUT_REQUIRE(d.angleRadians == 0.0 || (d.fix[0] && d.fix[1]),
                        "'" << where << "': a Rotation Angle needs Components = XY");
      DDC_INPUT_REQUIRE(d.fix[0] || d.value[0] == 0.0,
                        "'" << where << "/Value X' is set but Components = " << comps << " does not prescribe X");
      DDC_INPUT_REQUIRE(d.fix[1] || d.value[1] == 0.0,
                        "'" << where << "/Value Y' is set but Components = " << comps << " does not prescribe Y");
      bcs.displacements.push_back(d);
    } else {
      for (const char* key : {"Value X", "Value Y", "Rotation Angle", "Center X", "Center Y", "Gradient XX",
                              "Gradient XY", "Gradient YX", "Gradient YY"})
        forbid(key);
      DDC_INPUT_REQUIRE(!p.isParameter("Components") || p.get<std::string>("Components") == "XY",
                        "parameter '" << where << "/Components' does not apply to Type = Traction");
      try {
        mesh.sideSet(set);
      } catch (const InputError& e) {
        throw InputError("boundary condition '" + where + "': " + e.what());
      }
      TractionCondition t;
      t.name = name;
      t.setName = set;
      t.traction[0] = p.get<double>("Traction X");
      t.traction[1] = p.get<double>("Traction Y");
      bcs.tractions.push_back(t);
    }
  }
  return bcs;
}

}  // namespace ddc
