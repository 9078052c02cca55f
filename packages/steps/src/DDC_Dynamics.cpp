#include "DDC_Dynamics.hpp"

namespace ddc {

Dynamics::Dynamics(std::unique_ptr<NewmarkIntegrator> integrator, Teuchos::RCP<Vector> initialVelocity,
                   const Model& model, SolutionStrategy& strategy)
    : integrator_(std::move(integrator)), initialVelocity_(std::move(initialVelocity)) {
  acceleration_ = model.createVector();
  velocity_ = model.createVector();
  inertia_.acceleration = acceleration_.get();
  strategy.setInertia(&inertia_);
}

void Dynamics::start(const Model& model, const Vector& u0) {
  integrator_->initialise(model, u0, *initialVelocity_, model.bodyForce());
}

void Dynamics::updateIterate(const Vector& u) {
  integrator_->acceleration(u, *acceleration_);
  if (integrator_->damped()) integrator_->velocity(u, *velocity_);
  inertia_ = integrator_->inertia(*acceleration_, integrator_->damped() ? velocity_.get() : nullptr);
}

void Dynamics::beginStep(const Model& model, double from, double size, const Vector& fint) {
  // f_ext(t_n) = λ_n f_ext (and the constant body force) for the α-methods'
  // previous-step terms.
  auto externalNow = model.createVector();
  externalNow->update(from, model.externalForce(), 0.0);
  if (model.bodyForce()) externalNow->update(1.0, *model.bodyForce(), 1.0);
  integrator_->beginStep(model, size, fint, *externalNow);
}

}  // namespace ddc
