// Implicit time integration of M ü + f_int(u) = f_ext(t) (doc/user-guide.md,
// "Dynamics"): the Newmark family (Newmark 1959; Hughes, The Finite Element
// Method, ch. 9). Over a step t_n → t_{n+1} = t_n + h, with the predictors
//
//   ũ = u_n + h v_n + h² (½ − β) a_n,     ṽ = v_n + h (1 − γ) a_n,
//
// the acceleration and velocity are functions of the unknown u_{n+1}:
//
//   a(u) = (u − ũ) / (β h²),               v(u) = ṽ + γ h a(u),
//
// so Newton on r(u) = f_int(u) − f_ext(t_{n+1}) + M a(u) has the tangent
// K + c M with c = 1 / (β h²) (Model::assemble with an Inertia term). The
// step controller chooses h (BisectingSteps: the nominal time steps, halved
// on Newton failure), so h may change from step to step; the formulas hold
// for any h.
//
// Stability: unconditionally stable for linear problems when
// 2β ≥ γ ≥ ½ (Hughes §9.1); γ = ½ has no numerical damping, γ > ½ damps
// (first-order accurate). β = ¼, γ = ½ (the trapezoidal rule) conserves the
// energy of a linear free vibration exactly.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <string>

#include "DDC_Model.hpp"

namespace ddc {

/// The Newmark integrator's parameters and its state (u_n, v_n, a_n).
class NewmarkIntegrator {
 public:
  /// \param beta β > 0
  /// \param gamma γ ≥ ½, with 2β ≥ γ (unconditional stability)
  /// \throws InputError naming `path` and the parameter outside its range
  NewmarkIntegrator(double beta, double gamma, const std::string& path);

  /// Start from the displacements u0 with velocities v0 and zero
  /// acceleration (no load acts at t = 0: boundary values and tractions are
  /// zero there, see the user guide). Vectors on the model's owned map.
  void initialise(const Model& model, const Vector& u0, const Vector& v0);
  /// Begin the step t_n → t_n + h from the converged state: the predictors.
  void beginStep(double h);
  /// a(u) of the current step into `a`.
  void acceleration(const Vector& u, Vector& a) const;
  /// The factor c = 1/(β h²) of M in the tangent.
  double tangentFactor() const { return 1.0 / (beta_ * h_ * h_); }
  /// The step converged at u: u_n, v_n, a_n become those of t_{n+1}.
  void acceptStep(const Vector& u);
  /// The converged velocities v_n and accelerations a_n.
  const Vector& velocity() const { return *v_; }
  const Vector& accelerationNow() const { return *a_; }

  double beta() const { return beta_; }
  double gamma() const { return gamma_; }

 private:
  double beta_, gamma_, h_ = 0.0;
  Teuchos::RCP<Vector> u_, v_, a_;        ///< converged state at t_n
  Teuchos::RCP<Vector> uTilde_, vTilde_;  ///< predictors of the current step
};

}  // namespace ddc
