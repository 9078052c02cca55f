#include "DDC_StepsSetUp.hpp"

#include <algorithm>
#include <cmath>

#include "DDC_AnalysisParameters.hpp"
#include "DDC_Error.hpp"
#include "DDC_Memory.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

using PL = Teuchos::ParameterList;

namespace {

/// Each condition sublist of "Dynamics/<group>" (Initial Velocity,
/// Gravity), validated against its template, with its parameter path.
template <class F>
void forEachCondition(PL& dyn, const std::string& group, const char* keys, F f) {
  PL& list = dyn.sublist(group);
  const PL& valid = dynamicsValidParameters()->sublist(group).sublist("<Condition Name>");
  for (auto it = list.begin(); it != list.end(); ++it) {
    const std::string& name = list.name(it);
    const std::string where = "Dynamics/" + group + "/" + name;
    DDC_INPUT_REQUIRE(list.isSublist(name), "'" << where << "' must be a sublist (" << keys << ")");
    PL& c = list.sublist(name);
    validateLevel(c, valid, where);
    f(c, where);
  }
}

/// The initial velocities of "Dynamics/Initial Velocity" by body or node
/// set; prescribed DOFs start at rest.
Teuchos::RCP<Vector> initialVelocities(PL& dyn, const Model& model) {
  const Mesh& mesh = model.mesh();
  auto initialVelocity = model.createVector();
  forEachCondition(dyn, "Initial Velocity", "Set, Velocity X/Y/Z", [&](PL& c, const std::string& where) {
    const std::string set = c.get<std::string>("Set");
    std::vector<int> nodes;
    try {
      if (set.find('/') == std::string::npos) {
        const Body& body = mesh.body(mesh.bodyIndex(set));
        for (int n = 0; n < body.numNodes; ++n) nodes.push_back(body.firstNode + n);
      } else {
        nodes = mesh.nodeSet(set);
      }
    } catch (const InputError& e) {
      throw InputError("'" + where + "/Set' = '" + set + "' is neither a body nor a qualified node set "
                       "'Body/set': " + e.what());
    }
    DDC_INPUT_REQUIRE(mesh.dim() == 3 || c.get<double>("Velocity Z") == 0.0,
                      "'" << where << "/Velocity Z' is set but the model is 2-D");
    const double v[3] = {c.get<double>("Velocity X"), c.get<double>("Velocity Y"), c.get<double>("Velocity Z")};
    for (int n : nodes)
      for (int k = 0; k < mesh.dim(); ++k) {
        const GO g = model.dof(n, k);
        if (initialVelocity->getMap()->isNodeGlobalElement(g) && !model.isConstrained(g))
          initialVelocity->replaceGlobalValue(g, v[k]);
      }
  });
  return initialVelocity;
}

/// Gravity by body ("Dynamics/Gravity"): the force M g with the run's mass
/// matrices, as the model's body force.
void applyGravity(PL& dyn, Model& model) {
  const Mesh& mesh = model.mesh();
  auto g = model.createVector();
  bool anyGravity = false;
  forEachCondition(dyn, "Gravity", "Set, Acceleration X/Y/Z", [&](PL& c, const std::string& where) {
    const std::string set = c.get<std::string>("Set");
    int b = -1;
    try {
      b = mesh.bodyIndex(set);
    } catch (const InputError& e) {
      throw InputError("'" + where + "/Set' = '" + set + "' is not a body: " + e.what());
    }
    DDC_INPUT_REQUIRE(mesh.dim() == 3 || c.get<double>("Acceleration Z") == 0.0,
                      "'" << where << "/Acceleration Z' is set but the model is 2-D");
    const double a[3] = {c.get<double>("Acceleration X"), c.get<double>("Acceleration Y"),
                         c.get<double>("Acceleration Z")};
    const Body& body = mesh.body(b);
    for (int n = body.firstNode; n < body.firstNode + body.numNodes; ++n)
      for (int k = 0; k < mesh.dim(); ++k) {
        const GO gid = model.dof(n, k);
        if (g->getMap()->isNodeGlobalElement(gid)) g->replaceGlobalValue(gid, a[k]);
      }
    anyGravity = anyGravity || a[0] != 0.0 || a[1] != 0.0 || a[2] != 0.0;
  });
  if (anyGravity) {
    auto f = model.createVector();
    model.applyMass(*g, *f);
    model.setBodyForce(*f);
  }
}

}  // namespace

void requireDynamicsForDynamicConditions(const PL& dyn) {
  for (const char* group : {"Gravity", "Initial Velocity"}) {
    if (!dyn.isSublist(group)) continue;
    const PL& list = dyn.sublist(group);
    for (auto it = list.begin(); it != list.end(); ++it)
      DDC_THROW(InputError, "'Dynamics/" << group << "/" << list.name(it) << "' is given, but 'Dynamics/Integrator' = "
                                         << dyn.get<std::string>("Integrator")
                                         << " (a quasi-static analysis, without inertia) would ignore it: set "
                                            "'Dynamics/Integrator' to Newmark, HHT-alpha or Generalized-alpha, "
                                            "or remove 'Dynamics/"
                                         << group << "/" << list.name(it) << "'");
  }
}

StepControlSettings stepControlSettings(const PL& params, bool dynamic, bool decomposedContact) {
  const PL& sc = params.sublist("Step Control");
  StepControlSettings control;
  control.tolerance = sc.get<double>("Error Tolerance");
  control.corrections = sc.get<int>("Geometry Corrections");
  if (control.tolerance == 0.0) return control;
  DDC_INPUT_REQUIRE(control.tolerance >= kMinErrorTolerance,
                    "'Step Control/Error Tolerance' = "
                        << control.tolerance << " is below " << kMinErrorTolerance
                        << " (10^6 units of round-off): the frozen-geometry error indicator, a relative energy, "
                           "sits at round-off (up to about 1e-12) once a step's geometry has converged, so a "
                           "smaller tolerance could not be met reliably and which steps are accepted would depend "
                           "on the rank count; set it to at least "
                        << kMinErrorTolerance << " (doc/user-guide.md, \"Step control\")");
  DDC_INPUT_REQUIRE(decomposedContact,
                    "'Step Control/Error Tolerance' = "
                        << control.tolerance
                        << " controls the frozen-geometry error of the decomposed contact element, and this run "
                           "has none (Contact/Formulation = Decomposed Node-To-Segment or Decomposed "
                           "Node-To-Surface, with a contact pair); set it to 0");
  const PL& ls = params.sublist(dynamic ? "Dynamics" : "Load Stepping");
  const double first = dynamic ? ls.get<double>("Time Step")
                                : ls.get<double>("Final Load Factor") / ls.get<int>("Number of Steps");
  const double finalValue = dynamic ? ls.get<double>("Final Time") : ls.get<double>("Final Load Factor");
  const char* firstName = dynamic ? "'Dynamics/Time Step'" : "'Load Stepping/Final Load Factor' / 'Number of Steps'";
  const double minSize = sc.get<double>("Minimum Step Size"), maxSize = sc.get<double>("Maximum Step Size");
  // The default minimum: the first step halved Max Bisections times, but
  // not below the resolution of the value (kStepResolution).
  const double resolution = kStepResolution * finalValue;
  control.minSize = minSize > 0.0 ? minSize : std::max(std::ldexp(first, -ls.get<int>("Max Bisections")), resolution);
  DDC_INPUT_REQUIRE(minSize == 0.0 || minSize >= resolution,
                    "'Step Control/Minimum Step Size' = "
                        << minSize << " is below the resolution of the " << (dynamic ? "time" : "load factor")
                        << " at its final value (" << kStepResolution << " x "
                        << (dynamic ? "Dynamics/Final Time" : "Load Stepping/Final Load Factor") << " = "
                        << resolution << "), where a smaller step no longer changes it; set it to at least "
                        << resolution << " or to 0 (the first step halved Max Bisections times)");
  control.maxSize = maxSize > 0.0 ? maxSize : first;
  control.first = std::clamp(first, control.minSize, control.maxSize);
  DDC_INPUT_REQUIRE(control.minSize <= control.maxSize,
                    "'Step Control/Minimum Step Size' = " << control.minSize
                                                          << " exceeds 'Step Control/Maximum Step Size' = "
                                                          << control.maxSize
                                                          << (maxSize > 0.0 ? "" : " (0: the first step)"));
  DDC_INPUT_REQUIRE(control.maxSize <= finalValue,
                    "'Step Control/Maximum Step Size' = " << control.maxSize << " exceeds the whole analysis ("
                                                          << (dynamic ? "Dynamics/Final Time" : "Load Stepping/Final Load Factor")
                                                          << " = " << finalValue << ")");
  DDC_INPUT_REQUIRE(minSize == 0.0 || minSize <= first,
                    "'Step Control/Minimum Step Size' = " << minSize << " exceeds the first step " << first << " ("
                                                          << firstName << ")");
  return control;
}

StepLoopSettings stepLoopSettings(const PL& params, bool dynamic) {
  StepLoopSettings s;
  const PL& ls = params.sublist(dynamic ? "Dynamics" : "Load Stepping");
  s.stepping = dynamic ? "Dynamics" : "Load Stepping";
  s.factorName = dynamic ? "time" : "load factor";
  s.finalValue = dynamic ? ls.get<double>("Final Time") : ls.get<double>("Final Load Factor");
  s.numSteps = dynamic ? static_cast<int>(std::round(s.finalValue / ls.get<double>("Time Step")))
                       : ls.get<int>("Number of Steps");
  return s;
}

std::unique_ptr<StepController> makeStepController(const PL& params, bool dynamic,
                                                   const StepControlSettings& control) {
  const StepLoopSettings s = stepLoopSettings(params, dynamic);
  const int maxBisections = params.sublist(s.stepping).get<int>("Max Bisections");
  if (control.tolerance > 0.0)
    return std::make_unique<AdaptiveSteps>(s.finalValue, control.first, control.minSize, control.maxSize,
                                           control.tolerance, maxBisections, control.corrections);
  return std::make_unique<BisectingSteps>(s.finalValue, s.numSteps, maxBisections);
}

std::unique_ptr<Dynamics> makeDynamics(PL& dyn, Model& model, SolutionStrategy& strategy) {
  const Mesh& mesh = model.mesh();
  // Every body needs inertia.
  for (const auto& name : model.bodiesWithoutMass())
    DDC_THROW(InputError, "'Dynamics/Integrator' = " << dyn.get<std::string>("Integrator") << " needs the mass of "
                          "every body, but body '" << name << "' has none: set 'Mesh/Bodies/" << name
                          << "/Element/Material/Density' > 0");
  // A whole number of time steps, fewer than a run can count.
  const double T = dyn.get<double>("Final Time"), h = dyn.get<double>("Time Step");
  const double steps = std::round(T / h);
  DDC_INPUT_REQUIRE(!(T / h >= kMaxTimeSteps),
                    "'Dynamics/Time Step' = " << h << " makes " << T / h << " steps of 'Dynamics/Final Time' = " << T
                                              << ", more than the " << kMaxTimeSteps
                                              << " time steps a run can take; set it to at least Final Time / "
                                              << kMaxTimeSteps << " = " << T / kMaxTimeSteps);
  DDC_INPUT_REQUIRE(steps >= 1 && std::abs(steps * h - T) <= 1e-9 * T,
                    "'Dynamics/Final Time' = " << T << " is not a whole number of 'Dynamics/Time Step' = " << h
                                               << " (" << T / h << " steps)");
  const std::string mass = dyn.get<std::string>("Mass Matrix");
  const MassLumping lumping = mass == "HRZ"       ? MassLumping::HRZ
                              : mass == "Row-Sum" ? MassLumping::RowSum
                                                  : MassLumping::Consistent;
  if (lumping == MassLumping::RowSum)
    for (int b = 0; b < mesh.numBodies(); ++b) {
      const CellType t = mesh.body(b).cellType;
      DDC_INPUT_REQUIRE(t != CellType::Hex20 && t != CellType::Tet10,
                        "'Dynamics/Mass Matrix' = Row-Sum gives zero or negative masses at the corners of "
                            << cellTypeName(t) << " elements (body '" << mesh.body(b).name
                            << "'); use HRZ or Consistent");
    }
  model.setMassLumping(lumping);
  try {
    model.setContactSurfaceMassRedistributed(dyn.get<std::string>("Contact Surface Mass") == "Redistributed");
  } catch (const InputError& e) {
    throw InputError(std::string("'Dynamics/Contact Surface Mass' = Redistributed: ") + e.what() +
                     " (or set it to Kept)");
  }
  const std::string scheme = dyn.get<std::string>("Integrator");
  auto integrator = std::make_unique<NewmarkIntegrator>(
      scheme == "HHT-alpha"           ? NewmarkParameters::hht(dyn.get<double>("HHT Alpha"), "Dynamics")
      : scheme == "Generalized-alpha" ? NewmarkParameters::generalisedAlpha(dyn.get<double>("Spectral Radius"), "Dynamics")
                                      : NewmarkParameters::newmark(dyn.get<double>("Newmark Beta"),
                                                                   dyn.get<double>("Newmark Gamma"), "Dynamics"));
  integrator->setRayleighDamping(dyn.get<double>("Rayleigh Alpha"), dyn.get<double>("Rayleigh Beta"));
  auto initialVelocity = initialVelocities(dyn, model);
  applyGravity(dyn, model);
  return std::make_unique<Dynamics>(std::move(integrator), initialVelocity, model, strategy);
}

}  // namespace ddc
