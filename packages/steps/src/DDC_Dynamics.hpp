// Implicit dynamics as the step loop drives it: the time integrator
// (DDC_TimeIntegrator.hpp), the initial velocities, and the inertia term the
// solution strategy assembles with, kept current at each Newton iterate.
#pragma once

#include <memory>

#include "DDC_SolutionStrategy.hpp"
#include "DDC_TimeIntegrator.hpp"

namespace ddc {

/// The dynamic part of a run (doc/user-guide.md, "Dynamics").
class Dynamics {
 public:
  /// \param integrator the time integrator (Newmark, HHT-α, generalised-α)
  /// \param initialVelocity velocities at t = 0 (owned map of `model`)
  /// `strategy` assembles with inertia() from now on.
  Dynamics(std::unique_ptr<NewmarkIntegrator> integrator, Teuchos::RCP<Vector> initialVelocity, const Model& model,
           SolutionStrategy& strategy);
  /// Start at t = 0 from `u0` (the acceleration balances the body force).
  void start(const Model& model, const Vector& u0);
  /// The acceleration a(u) and velocity v(u) of the current step at the
  /// iterate `u`, and the integrator's factors, into inertia().
  void updateIterate(const Vector& u);
  /// Begin the step from `from` of size `size`, from the converged internal
  /// force `fint` (the α-methods' previous-step terms).
  void beginStep(const Model& model, double from, double size, const Vector& fint);
  NewmarkIntegrator& integrator() { return *integrator_; }
  const NewmarkIntegrator& integrator() const { return *integrator_; }
  /// The inertia term every assembly of the strategy uses.
  const Inertia* inertia() const { return &inertia_; }

 private:
  std::unique_ptr<NewmarkIntegrator> integrator_;
  Teuchos::RCP<Vector> initialVelocity_, acceleration_, velocity_;
  Inertia inertia_;
};

}  // namespace ddc
