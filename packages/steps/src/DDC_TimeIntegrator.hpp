// Implicit time integration of M ü + f_int(u) = f_ext(t) (doc/user-guide.md,
// "Dynamics"): the Newmark family with the α-methods — Newmark (1959),
// HHT-α (Hilber, Hughes & Taylor 1977) and generalised-α (Chung & Hulbert
// 1993); Hughes, The Finite Element Method, ch. 9.
//
// Over a step t_n → t_{n+1} = t_n + h, with the predictors
//
//   ũ = u_n + h v_n + h² (½ − β) a_n,     ṽ = v_n + h (1 − γ) a_n,
//
// the acceleration and velocity are functions of the unknown u_{n+1}:
//
//   a(u) = (u − ũ) / (β h²),               v(u) = ṽ + γ h a(u).
//
// The α-methods balance forces at intermediate points,
//
//   (1 − α_m) M a_{n+1} + α_m M a_n + (1 − α_f) f_int(u_{n+1}) + α_f f_int(u_n)
//     = (1 − α_f) f_ext(t_{n+1}) + α_f f_ext(t_n)
//
// (the "generalised trapezoidal" form of the internal force, which keeps
// f_int an element quantity for any material). Divided by (1 − α_f), Newton
// solves r(u) = f_int(u) − f_ext(t_{n+1}) + w M a(u) + g = 0 with
//
//   w = (1 − α_m)/(1 − α_f),   c = w / (β h²)  (the tangent is K + c M),
//   g = [α_f (f_int(u_n) − f_ext(t_n)) + α_m M a_n] / (1 − α_f),
//
// which is Model::assemble with Inertia{a, c, w, g}. Newmark is α_m = α_f = 0.
//
// Rayleigh damping C = α_R M + β_R K adds C v(u) + α_f/(1 − α_f) C v_n to r,
// and (γ/(β h)) C to the tangent (v(u) = ṽ + γ h a(u)).
//
// Parameters and stability (linear problems, unconditional):
//  - Newmark: 2β ≥ γ ≥ ½; β = ¼, γ = ½ (trapezoidal) conserves the energy of
//    a linear free vibration; γ > ½ damps at first-order accuracy.
//  - HHT-α: α ∈ [−⅓, 0], α_m = 0, α_f = −α, γ = ½ − α, β = (1 − α)²/4;
//    second order; α = 0 is the trapezoidal rule.
//  - generalised-α from the spectral radius at infinite frequency
//    ρ∞ ∈ [0, 1]: α_m = (2ρ∞ − 1)/(ρ∞ + 1), α_f = ρ∞/(ρ∞ + 1),
//    γ = ½ − α_m + α_f, β = (1 − α_m + α_f)²/4; second order, with minimal
//    low-frequency damping for the high-frequency damping chosen.
// The step controller chooses h (halved on Newton failure), so h may change
// from step to step; the formulas hold for any h.
#pragma once

#include <string>

#include "DDC_Model.hpp"

namespace ddc {

/// The parameters of a member of the family (see the top of this file).
struct NewmarkParameters {
  double beta = 0.25, gamma = 0.5;
  double alphaM = 0.0, alphaF = 0.0;
  /// Newmark; \throws InputError naming `path` unless 2β ≥ γ ≥ ½.
  static NewmarkParameters newmark(double beta, double gamma, const std::string& path);
  /// HHT-α; \throws InputError naming `path` unless α ∈ [−⅓, 0].
  static NewmarkParameters hht(double alpha, const std::string& path);
  /// Generalised-α; \throws InputError naming `path` unless ρ∞ ∈ [0, 1].
  static NewmarkParameters generalisedAlpha(double rhoInfinity, const std::string& path);
};

/// The integrator's state (u_n, v_n, a_n, f_int(u_n)) and its step algebra.
class NewmarkIntegrator {
 public:
  explicit NewmarkIntegrator(const NewmarkParameters& p) : p_(p) {}

  /// Rayleigh damping C = alpha M + beta K (K the element tangents at the
  /// current state): M a + C v + f_int = f_ext, with C v balanced like f_int
  /// by the α-methods ((1 − α_f) C v_{n+1} + α_f C v_n). Before initialise().
  void setRayleighDamping(double alpha, double beta) { dampAlpha_ = alpha, dampBeta_ = beta; }
  bool damped() const { return dampAlpha_ != 0.0 || dampBeta_ != 0.0; }

  /// Start from the displacements u0 with velocities v0 and the
  /// acceleration that balances `force0` = f_ext(0) − f_int(u0) (e.g.
  /// gravity; boundary values and tractions are zero at t = 0, see the user
  /// guide): M a0 = force0 on the free DOFs with mass, solved by
  /// Jacobi-preconditioned CG (accelerationSolveIterations()); a0 = 0 on
  /// prescribed and massless DOFs, and everywhere without `force0`.
  /// Vectors on the model's owned map.
  /// \throws SolverError if CG does not reach 1e-12 relative in 1000
  ///         iterations (M is positive definite on those DOFs: it does)
  void initialise(const Model& model, const Vector& u0, const Vector& v0, const Vector* force0 = nullptr);
  /// Continue from a converged state saved by a checkpoint (displacements,
  /// velocity() and accelerationNow() of that state), after initialise().
  void restoreState(const Vector& u, const Vector& v, const Vector& a);
  /// CG iterations of the initial-acceleration solve (0 without force0).
  int accelerationSolveIterations() const { return cgIterations_; }
  /// Begin the step t_n → t_n + h from the converged state: the predictors
  /// and, for the α-methods, the force g of the previous step's terms, from
  /// f_int(u_n) (`fintNow`, all DOFs) and the external force f_ext(t_n) =
  /// λ_n f_ext (`externalNow`).
  void beginStep(const Model& model, double h, const Vector& fintNow, const Vector& externalNow);
  /// a(u) of the current step into `a`.
  void acceleration(const Vector& u, Vector& a) const;
  /// v(u) = ṽ + γ h a(u) of the current step into `v`.
  void velocity(const Vector& u, Vector& v) const;
  /// The inertia term of the current step at the acceleration vector `a`
  /// and, with damping, the velocity vector `v` (which the caller fills with
  /// acceleration() and velocity() at each iterate).
  Inertia inertia(const Vector& a, const Vector* v = nullptr) const;
  /// The step converged at u: u_n, v_n, a_n become those of t_{n+1}.
  void acceptStep(const Vector& u);
  /// M a_n + C v_n of the converged state (C v_n only with damping): with
  /// f_int, the force the prescribed DOFs exert (their reactions). Owned map.
  void inertiaForce(const Model& model, Vector& f) const;
  /// The converged velocities v_n.
  const Vector& velocity() const { return *v_; }
  /// The converged accelerations a_n.
  const Vector& accelerationNow() const { return *a_; }
  const NewmarkParameters& parameters() const { return p_; }

 private:
  double weight() const { return (1.0 - p_.alphaM) / (1.0 - p_.alphaF); }
  NewmarkParameters p_;
  double h_ = 0.0;
  Teuchos::RCP<Vector> u_, v_, a_;        ///< converged state at t_n
  Teuchos::RCP<Vector> uTilde_, vTilde_;  ///< predictors of the current step
  Teuchos::RCP<Vector> g_;                ///< α-methods: the previous step's force terms
  int cgIterations_ = 0;
  double dampAlpha_ = 0.0, dampBeta_ = 0.0;  ///< setRayleighDamping()
  /// C v = alpha M v + beta K(u) v into Cv.
  void applyDamping(const Model& model, const Vector& u, const Vector& v, Vector& Cv) const;
  /// M a_n and (with damping) C v_n of the converged state, computed once
  /// per state (an element pass with beta > 0): beginStep() and
  /// inertiaForce() both need them, and a bisected step begins again.
  void stateForces(const Model& model) const;
  mutable Teuchos::RCP<Vector> Ma_, Cv_;
  mutable bool stateForcesCurrent_ = false;
};

}  // namespace ddc
