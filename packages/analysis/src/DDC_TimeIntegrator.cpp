#include "DDC_TimeIntegrator.hpp"

#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

NewmarkIntegrator::NewmarkIntegrator(double beta, double gamma, const std::string& path) : beta_(beta), gamma_(gamma) {
  DDC_INPUT_REQUIRE(gamma >= 0.5, "'" << joinPath(path, "Newmark Gamma") << "' = " << gamma
                                      << ": gamma < 1/2 amplifies every mode (unstable); use gamma >= 1/2 "
                                         "(1/2: no numerical damping)");
  DDC_INPUT_REQUIRE(2.0 * beta >= gamma,
                    "'" << joinPath(path, "Newmark Beta") << "' = " << beta << " with '"
                        << joinPath(path, "Newmark Gamma") << "' = " << gamma
                        << ": the implicit Newmark scheme is unconditionally stable only for 2 beta >= gamma >= "
                           "1/2 (e.g. beta = 1/4, gamma = 1/2, the trapezoidal rule)");
}

void NewmarkIntegrator::initialise(const Model& model, const Vector& u0, const Vector& v0) {
  u_ = model.createVector();
  v_ = model.createVector();
  a_ = model.createVector();
  uTilde_ = model.createVector();
  vTilde_ = model.createVector();
  u_->assign(u0);
  v_->assign(v0);
  a_->putScalar(0.0);
}

void NewmarkIntegrator::beginStep(double h) {
  h_ = h;
  // ũ = u_n + h v_n + h² (½ − β) a_n;  ṽ = v_n + h (1 − γ) a_n.
  uTilde_->update(1.0, *u_, h, *v_, 0.0);
  uTilde_->update(h * h * (0.5 - beta_), *a_, 1.0);
  vTilde_->update(1.0, *v_, h * (1.0 - gamma_), *a_, 0.0);
}

void NewmarkIntegrator::acceleration(const Vector& u, Vector& a) const {
  const double c = tangentFactor();
  a.update(c, u, -c, *uTilde_, 0.0);
}

void NewmarkIntegrator::acceptStep(const Vector& u) {
  acceleration(u, *a_);
  v_->update(1.0, *vTilde_, gamma_ * h_, *a_, 0.0);
  u_->assign(u);
}

}  // namespace ddc
