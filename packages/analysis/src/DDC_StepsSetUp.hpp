// From the validated parameters to the steps of a run: the step
// controller (equal steps halved on Newton failure, or steps sized by the
// frozen-geometry error: "Step Control"), the dynamics ("Dynamics": the
// integrator, initial velocities, gravity) and how the step loop words its
// messages.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <memory>
#include <string>

#include "DDC_Dynamics.hpp"
#include "DDC_StepController.hpp"
#include "DDC_StepLoop.hpp"

namespace ddc {

/// "Step Control", resolved (tolerance 0: off).
struct StepControlSettings {
  double tolerance = 0.0;
  double first = 0.0, minSize = 0.0, maxSize = 0.0;  ///< step sizes (load factor or time)
  int corrections = 0;  ///< Geometry Corrections
};

/// The smallest Step Control/Error Tolerance: 10^6 units of round-off
/// (2.2e-10). The indicator is a ratio of energies summed over slave nodes
/// and ranks; steps whose geometry repeats have converged leave it at
/// round-off, measured 6e-14 to 9e-13 on the half-rings. Near that its
/// round-off decides: steps could never meet the tolerance and the verdicts
/// would depend on the rank count (the order of the sums).
constexpr double kMinErrorTolerance = 1e6 * 2.220446049250313e-16;

/// The most time steps a dynamic analysis may take (Final Time / Time
/// Step): the steps are counted in an int.
constexpr double kMaxTimeSteps = 1e9;

/// A quasi-static run (Dynamics/Integrator = None) has no inertia: refuse
/// the initial velocities and the gravity it would ignore.
/// \throws InputError naming the condition
void requireDynamicsForDynamicConditions(const Teuchos::ParameterList& dynamics);

/// Check the "Step Control" list of `params` against the run (decomposed
/// contact, the sizes) and resolve its defaults.
/// \throws InputError naming the parameter
StepControlSettings stepControlSettings(const Teuchos::ParameterList& params, bool dynamic, bool decomposedContact);

/// The controller the parameters describe: AdaptiveSteps with a Step
/// Control tolerance, else BisectingSteps over Load Stepping (or the time
/// steps of Dynamics).
std::unique_ptr<StepController> makeStepController(const Teuchos::ParameterList& params, bool dynamic,
                                                   const StepControlSettings& control);

/// How the loop names the steps of this run in its messages.
StepLoopSettings stepLoopSettings(const Teuchos::ParameterList& params, bool dynamic);

/// The dynamic part of a run from the validated "Dynamics" list: checks the
/// masses and the time step, sets the mass matrices of `model`, builds the
/// integrator, the initial velocities and the gravity (Model::setBodyForce());
/// `strategy` assembles with its inertia.
/// \throws InputError naming the parameter path
std::unique_ptr<Dynamics> makeDynamics(Teuchos::ParameterList& dynamics, Model& model, SolutionStrategy& strategy);

}  // namespace ddc
