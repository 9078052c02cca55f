#include "DDC_TimeIntegrator.hpp"

#include <stdexcept>

#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

NewmarkParameters NewmarkParameters::newmark(double beta, double gamma, const std::string& path) {
  DDC_INPUT_REQUIRE(gamma >= 0.5, "'" << joinPath(path, "Newmark Gamma") << "' = " << gamma
                                      << ": gamma < 1/2 amplifies every mode (unstable); use gamma >= 1/2 "
                                         "(1/2: no numerical damping)");
  DDC_INPUT_REQUIRE(2.0 * beta >= gamma,
                    "'" << joinPath(path, "Newmark Beta") << "' = " << beta << " with '"
                        << joinPath(path, "Newmark Gamma") << "' = " << gamma
                        << ": the implicit Newmark scheme is unconditionally stable only for 2 beta >= gamma >= "
                           "1/2 (e.g. beta = 1/4, gamma = 1/2, the trapezoidal rule)");
  NewmarkParameters p;
  p.beta = beta;
  p.gamma = gamma;
  return p;
}

NewmarkParameters NewmarkParameters::hht(double alpha, const std::string& path) {
  DDC_INPUT_REQUIRE(alpha >= -1.0 / 3.0 && alpha <= 0.0,
                    "'" << joinPath(path, "HHT Alpha") << "' = " << alpha
                        << ": HHT-alpha is unconditionally stable and second-order accurate for alpha in [-1/3, 0]");
  NewmarkParameters p;
  p.alphaM = 0.0;
  p.alphaF = -alpha;
  p.gamma = 0.5 - alpha;
  p.beta = 0.25 * (1.0 - alpha) * (1.0 - alpha);
  return p;
}

NewmarkParameters NewmarkParameters::generalisedAlpha(double rho, const std::string& path) {
  DDC_INPUT_REQUIRE(rho >= 0.0 && rho <= 1.0, "'" << joinPath(path, "Spectral Radius") << "' = " << rho
                                                  << ": the spectral radius at infinite frequency is in [0, 1] "
                                                     "(1: no numerical damping, 0: the most)");
  NewmarkParameters p;
  p.alphaM = (2.0 * rho - 1.0) / (rho + 1.0);
  p.alphaF = rho / (rho + 1.0);
  p.gamma = 0.5 - p.alphaM + p.alphaF;
  p.beta = 0.25 * (1.0 - p.alphaM + p.alphaF) * (1.0 - p.alphaM + p.alphaF);
  return p;
}

void NewmarkIntegrator::initialise(const Model& model, const Vector& u0, const Vector& v0, const Vector* force0) {
  u_ = model.createVector();
  v_ = model.createVector();
  a_ = model.createVector();
  uTilde_ = model.createVector();
  vTilde_ = model.createVector();
  g_ = model.createVector();
  u_->assign(u0);
  v_->assign(v0);
  a_->putScalar(0.0);
  stateForcesCurrent_ = false;
  cgIterations_ = 0;
  // The force a0 balances: force0, less the damping of the initial velocity.
  auto b = model.createVector();
  if (force0) b->assign(*force0);
  if (damped() && v0.normInf() > 0.0) {
    auto Cv = model.createVector();
    applyDamping(model, u0, v0, *Cv);
    b->update(-1.0, *Cv, 1.0);
  }
  if (b->normInf() == 0.0) return;
  // M a0 = force0 on the free DOFs with mass: preconditioned CG with the
  // diagonal of M, the other DOFs masked out (M is positive definite on the
  // rest; on massless DOFs — a redistributed contact surface — the rows of
  // M vanish and a0 is left 0 there).
  auto d = model.createVector();
  model.massDiagonal(*d);
  const size_t n = d->getLocalLength();
  const GO first = model.ownedMap()->getMinGlobalIndex();
  std::vector<double> inv(n, 0.0);
  {
    auto dd = d->getData();
    for (size_t l = 0; l < n; ++l)
      if (dd[l] > 0.0 && !model.isConstrained(first + GO(l))) inv[l] = 1.0 / dd[l];
  }
  auto mask = [&](Vector& x) {
    auto xd = x.getDataNonConst();
    for (size_t l = 0; l < n; ++l)
      if (inv[l] == 0.0) xd[l] = 0.0;
  };
  auto r = model.createVector(), z = model.createVector(), p = model.createVector(), q = model.createVector();
  r->assign(*b);
  mask(*r);
  const double bnorm = r->norm2();
  if (bnorm == 0.0) return;
  auto precondition = [&] {
    auto rd = r->getData();
    auto zd = z->getDataNonConst();
    for (size_t l = 0; l < n; ++l) zd[l] = inv[l] * rd[l];
  };
  precondition();
  p->assign(*z);
  double rz = r->dot(*z);
  constexpr double kTolerance = 1e-12;
  constexpr int kMaxIterations = 1000;
  for (cgIterations_ = 1; cgIterations_ <= kMaxIterations; ++cgIterations_) {
    model.applyMass(*p, *q);
    mask(*q);
    const double alpha = rz / p->dot(*q);
    a_->update(alpha, *p, 1.0);
    r->update(-alpha, *q, 1.0);
    if (r->norm2() <= kTolerance * bnorm) return;
    precondition();
    const double rz1 = r->dot(*z);
    p->update(1.0, *z, rz1 / rz);
    rz = rz1;
  }
  DDC_THROW(SolverError, "the initial acceleration (M a0 = f_ext(0) - f_int(u0)) did not converge in "
                             << kMaxIterations << " CG iterations");
}

void NewmarkIntegrator::beginStep(const Model& model, double h, const Vector& fintNow, const Vector& externalNow) {
  h_ = h;
  const double beta = p_.beta, gamma = p_.gamma;
  // ũ = u_n + h v_n + h² (½ − β) a_n;  ṽ = v_n + h (1 − γ) a_n.
  uTilde_->update(1.0, *u_, h, *v_, 0.0);
  uTilde_->update(h * h * (0.5 - beta), *a_, 1.0);
  vTilde_->update(1.0, *v_, h * (1.0 - gamma), *a_, 0.0);
  // g = [α_f (f_int(u_n) − f_ext(t_n)) + α_m M a_n] / (1 − α_f).
  g_->putScalar(0.0);
  const double s = 1.0 / (1.0 - p_.alphaF);
  if (p_.alphaF != 0.0) g_->update(p_.alphaF * s, fintNow, -p_.alphaF * s, externalNow, 0.0);
  if (p_.alphaM != 0.0 || (p_.alphaF != 0.0 && damped())) stateForces(model);
  if (p_.alphaM != 0.0) g_->update(p_.alphaM * s, *Ma_, 1.0);
  // ... + α_f C v_n / (1 − α_f).
  if (p_.alphaF != 0.0 && damped()) g_->update(p_.alphaF * s, *Cv_, 1.0);
}

void NewmarkIntegrator::stateForces(const Model& model) const {
  if (stateForcesCurrent_) return;
  if (Ma_.is_null()) Ma_ = model.createVector();
  model.applyMass(*a_, *Ma_);
  if (damped()) {
    if (Cv_.is_null()) Cv_ = model.createVector();
    applyDamping(model, *u_, *v_, *Cv_);
  }
  stateForcesCurrent_ = true;
}

void NewmarkIntegrator::applyDamping(const Model& model, const Vector& u, const Vector& v, Vector& Cv) const {
  model.applyMass(v, Cv);
  Cv.scale(dampAlpha_);
  if (dampBeta_ != 0.0) {
    auto Kv = model.createVector();
    model.applyElementTangent(u, v, *Kv);
    Cv.update(dampBeta_, *Kv, 1.0);
  }
}

void NewmarkIntegrator::inertiaForce(const Model& model, Vector& f) const {
  stateForces(model);
  f.assign(*Ma_);
  if (damped()) f.update(1.0, *Cv_, 1.0);
}

void NewmarkIntegrator::velocity(const Vector& u, Vector& v) const {
  const double c = p_.gamma / (p_.beta * h_);
  v.update(c, u, -c, *uTilde_, 0.0);
  v.update(1.0, *vTilde_, 1.0);
}

void NewmarkIntegrator::acceleration(const Vector& u, Vector& a) const {
  const double c = 1.0 / (p_.beta * h_ * h_);
  a.update(c, u, -c, *uTilde_, 0.0);
}

Inertia NewmarkIntegrator::inertia(const Vector& a, const Vector* v) const {
  Inertia in;
  in.acceleration = &a;
  in.residualFactor = weight();
  in.tangentFactor = weight() / (p_.beta * h_ * h_);
  const bool previous = p_.alphaF != 0.0 || p_.alphaM != 0.0;
  in.force = previous ? g_.get() : nullptr;
  if (damped() && v) {
    in.velocity = v;
    in.massDamping = dampAlpha_;
    in.stiffnessDamping = dampBeta_;
    in.velocityFactor = p_.gamma / (p_.beta * h_);
  }
  return in;
}

void NewmarkIntegrator::restoreState(const Vector& u, const Vector& v, const Vector& a) {
  if (u_.is_null()) throw std::logic_error("NewmarkIntegrator::restoreState before initialise()");
  u_->assign(u);
  v_->assign(v);
  a_->assign(a);
  stateForcesCurrent_ = false;
}

void NewmarkIntegrator::acceptStep(const Vector& u) {
  acceleration(u, *a_);
  v_->update(1.0, *vTilde_, p_.gamma * h_, *a_, 0.0);
  u_->assign(u);
  stateForcesCurrent_ = false;
}

}  // namespace ddc
