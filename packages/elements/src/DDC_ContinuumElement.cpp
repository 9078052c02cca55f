#include "DDC_ContinuumElement.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_ShapeFunctions.hpp"
#include "DDC_TensorAlgebra.hpp"

namespace ddc {

namespace {

/// Total-Lagrangian continuum element of dimension kDim with kN nodes and kQ
/// quadrature points (the cell's shape functions and rule come from
/// DDC_ShapeFunctions). All per-point arrays are fixed size so the compiler
/// unrolls the small dense algebra; the reference gradients at the
/// quadrature points and corners are tabulated once per instance (one
/// instance serves a whole body).
template <int kDim, int kN, int kQ>
class ContinuumSolid final : public ContinuumElement {
 public:
  static constexpr int kDofs = kDim * kN;
  static constexpr int kVoigt = Voigt<kDim>::kSize;
  using Tensor = Eigen::Matrix<double, kDim, kDim>;
  using NodeMat = Eigen::Matrix<double, kN, kDim>;
  using BMat = Eigen::Matrix<double, kVoigt, kDofs>;
  using VecD = Eigen::Matrix<double, kDofs, 1>;
  using MatD = Eigen::Matrix<double, kDofs, kDofs>;

  ContinuumSolid(CellType cell, std::shared_ptr<const Material> material)
      : ContinuumElement(std::move(material), cell), name_(cellTypeName(cell)) {
    if (!material_) throw std::invalid_argument(std::string(name_) + ": material must not be null");
    const ReferenceCell& ref = referenceCell(cell);
    const QuadratureRule& rule = quadratureRule(cell);
    DDC_CHECK(ref.dim == kDim && ref.numNodes == kN && static_cast<int>(rule.points.size()) == kQ,
               name_ << ": element instantiated with the wrong sizes");
    Eigen::MatrixXd dN;
    for (int q = 0; q < kQ; ++q) {
      shapeFunctions(cell, rule.points[q], nullptr, &dN);
      dNq_[q] = dN;
      wq_[q] = rule.weights[q];
    }
    dNc_.resize(ref.numCorners);
    for (int c = 0; c < ref.numCorners; ++c) {
      shapeFunctions(cell, ref.nodes[c], nullptr, &dN);
      dNc_[c] = dN;
    }
  }

  int numNodes() const override { return kN; }
  int dim() const override { return kDim; }

  void compute(const NodalArray& X, const NodalArray& u, unsigned what, ElementResult& out) const override {
    checkSizes(X, u);
    const NodeMat Xf = X;
    const NodeMat uf = u;
    const bool wantR = (what & kResidual) != 0;
    const bool wantK = (what & kTangent) != 0;
    const bool linear = material_->isGeometricallyLinear();

    double energy = 0.0;
    VecD f = VecD::Zero();
    MatD K;
    if (wantK) K.setZero();
    VoigtVector<kDim> S;
    VoigtMatrix<kDim> D;
    NodeMat G;
    BMat B;
    for (int q = 0; q < kQ; ++q) {
      const double dV = referenceGradients(Xf, q, G);
      const Tensor F = Tensor::Identity() + uf.transpose() * G;
      if (!linear) requireAdmissible(F, q);
      energy += dV * material_->evaluate(F, (wantR || wantK) ? &S : nullptr, wantK ? &D : nullptr);
      if (!wantR && !wantK) continue;
      // The small-strain B-matrix is the nonlinear one with F = I.
      fillB(linear ? Tensor::Identity() : F, G, B);
      f.noalias() += (dV * B.transpose()) * S;
      if (!wantK) continue;
      // Material part B^T D B. The lazy (coefficient-wise) product of the
      // n x 3 and 3 x n factors measured ~30 % faster than Eigen's GEMM path
      // for Quad4/Quad9; for the n x 6 factors of the 3-D cells GEMM is the
      // faster one (Hex27: ~0.65 -> ~0.3 ms per evaluation with tangent).
      const Eigen::Matrix<double, kDofs, kVoigt> BtD = B.transpose() * (dV * D);
      if constexpr (kDim == 2)
        K.noalias() += BtD.lazyProduct(B);
      else
        K.noalias() += BtD * B;
      if (linear) continue;
      // Geometric part: (Grad N_a . S Grad N_b) I, from the variation of
      // B with F (Bonet & Wood, ch. 9, initial-stress stiffness).
      const Tensor Sm = symmetricFromVoigt<kDim>(S);
      const Eigen::Matrix<double, kN, kN> g = (dV * G) * Sm * G.transpose();
      for (int b = 0; b < kN; ++b)
        for (int a = 0; a < kN; ++a)
          for (int c = 0; c < kDim; ++c) K(kDim * a + c, kDim * b + c) += g(a, b);
    }
    out.energy = energy;
    if (wantR) out.residual = f;
    if (wantK) out.tangent = K;
  }

  void postprocess(const NodalArray& X, const NodalArray& u, ElementPostResult& out) const override {
    checkSizes(X, u);
    const NodeMat Xf = X;
    const NodeMat uf = u;
    const bool linear = material_->isGeometricallyLinear();
    double volume = 0.0, energy = 0.0, minDetF = std::numeric_limits<double>::infinity();
    double sigma[6] = {0, 0, 0, 0, 0, 0};
    VoigtVector<kDim> S;
    NodeMat G;
    for (int q = 0; q < kQ; ++q) {
      const double dV = referenceGradients(Xf, q, G);
      const Tensor F = Tensor::Identity() + uf.transpose() * G;
      const double J = F.determinant();
      minDetF = std::min(minDetF, J);
      if (!linear) requireAdmissible(F, q);
      energy += dV * material_->evaluate(F, &S, nullptr);
      volume += dV;
      // Cauchy stress in the 6-slot Voigt order of ElementPostResult.
      double s[6] = {0, 0, 0, 0, 0, 0};
      if (linear) {
        // The small-strain law already returns sigma(eps).
        for (int a = 0; a < kVoigt; ++a) s[postSlot(a)] = S(a);
        if (kDim == 2) s[2] = material_->stressZZ(F.template topLeftCorner<2, 2>());
      } else {
        // Push-forward sigma = J^-1 F S F^T; plane strain sigma_zz = J^-1 S33 (F33 = 1).
        const Tensor sm = F * symmetricFromVoigt<kDim>(S) * F.transpose() / J;
        for (int a = 0; a < kVoigt; ++a) s[postSlot(a)] = sm(Voigt<kDim>::kRow[a], Voigt<kDim>::kCol[a]);
        if (kDim == 2) s[2] = material_->stressZZ(F.template topLeftCorner<2, 2>()) / J;
      }
      // Reference-volume weighted average over the quadrature points (equal
      // weights for an affine element).
      for (int k = 0; k < 6; ++k) sigma[k] += dV * s[k];
    }
    for (int k = 0; k < 6; ++k) out.cauchy[k] = sigma[k] / volume;
    out.energyDensity = energy / volume;
    out.minDetJ = minDetF;
  }

  double minReferenceJacobian(const NodalArray& X) const override {
    if (X.rows() != kN || X.cols() != kDim) wrongSize("X", X);
    const NodeMat Xf = X;
    double m = std::numeric_limits<double>::infinity();
    for (int q = 0; q < kQ; ++q) m = std::min(m, (Xf.transpose() * dNq_[q]).determinant());
    for (const auto& dNc : dNc_) m = std::min(m, (Xf.transpose() * dNc).determinant());
    return m;
  }

 private:
  /// Slot in ElementPostResult::cauchy (3-D Voigt order) of Voigt component a.
  static constexpr int postSlot(int a) { return kDim == 3 || a < 2 ? a : 5; }

  /// Reference gradients G = dN/dX (n x kDim) at quadrature point q; returns
  /// the reference volume weight w_q det(dX/dxi).
  /// \throws InadmissibleDeformation for an inverted or degenerate element.
  double referenceGradients(const NodeMat& Xf, int q, NodeMat& G) const {
    // J0_ik = dX_i/dxi_k; dN/dX = dN/dxi J0^-1.
    const Tensor J0 = Xf.transpose() * dNq_[q];
    const double detJ0 = J0.determinant();
    if (!(detJ0 > 0))
      DDC_THROW(InadmissibleDeformation, name_ << ": inverted or degenerate reference element, det(dX/dxi) = "
                                               << detJ0 << " at quadrature point " << q);
    G.noalias() = dNq_[q] * (adjugate(J0) / detJ0);
    return wq_[q] * detJ0;
  }

  void requireAdmissible(const Tensor& F, int q) const {
    const double J = F.determinant();
    if (!(J > 0)) DDC_THROW(InadmissibleDeformation, name_ << ": det F = " << J << " <= 0 at quadrature point " << q);
  }

  /// Nonlinear B-matrix: row a (Voigt) holds dE_ij (normal rows) or 2 dE_ij
  /// (shear rows), ij = (kRow[a], kCol[a]), per nodal DOF, from
  /// dE = sym(F^T dF), dF = sum_b du_b (x) G_b.
  static void fillB(const Tensor& F, const NodeMat& G, BMat& B) {
    for (int b = 0; b < kN; ++b)
      for (int a = 0; a < kVoigt; ++a) {
        const int i = Voigt<kDim>::kRow[a], j = Voigt<kDim>::kCol[a];
        for (int m = 0; m < kDim; ++m)
          B(a, kDim * b + m) = a < kDim ? F(m, i) * G(b, i) : F(m, i) * G(b, j) + F(m, j) * G(b, i);
      }
  }

  void checkSizes(const NodalArray& X, const NodalArray& u) const {
    if (X.rows() != kN || X.cols() != kDim) wrongSize("X", X);
    if (u.rows() != kN || u.cols() != kDim) wrongSize("u", u);
  }

  [[noreturn]] void wrongSize(const char* what, const NodalArray& A) const {
    // A caller bug (the mesh cell type selects the element), not user input.
    throw std::invalid_argument(std::string(name_) + ": " + what + " is " + std::to_string(A.rows()) + " x " +
                                std::to_string(A.cols()) + ", expected " + std::to_string(kN) + " x " +
                                std::to_string(kDim));
  }

  const char* name_;
  std::array<NodeMat, kQ> dNq_;  ///< dN/dxi at the quadrature points
  std::array<double, kQ> wq_;    ///< quadrature weights
  std::vector<NodeMat> dNc_;     ///< dN/dxi at the corners
};

}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> ContinuumElement::getValidParameters() {
  static const Teuchos::RCP<const Teuchos::ParameterList> valid = [] {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("Element"));
    Teuchos::ParameterList& m = pl->sublist(
        "Material", false, "Hyperelastic material of the body (3-D; plane strain, per unit thickness, in 2-D).");
    m.setParameters(*Material::getValidParameters());
    return Teuchos::RCP<const Teuchos::ParameterList>(pl);
  }();
  return valid;
}

void ContinuumElement::mass(const NodalArray& X, MassLumping lumping, Eigen::MatrixXd& M) const {
  if (!hasMass())
    throw std::logic_error(std::string(cellTypeName(cell_)) + "::mass: the material has no density (Density = 0)");
  const int n = numNodes(), d = dim();
  if (X.rows() != n || X.cols() != d)
    DDC_THROW(std::invalid_argument, cellTypeName(cell_) << "::mass: X is " << X.rows() << " x " << X.cols()
                                                         << ", expected " << n << " x " << d);
  const double rho = material_->density();
  const QuadratureRule& rule = massQuadratureRule(cell_);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);  // the scalar mass ∫ ρ N_a N_b dV
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (size_t q = 0; q < rule.points.size(); ++q) {
    shapeFunctions(cell_, rule.points[q], &N, &dN);
    const double detJ0 = (X.transpose() * dN).determinant();
    if (!(detJ0 > 0))
      DDC_THROW(InadmissibleDeformation, cellTypeName(cell_) << "::mass: inverted or degenerate reference element, "
                                                                "det(dX/dxi) = " << detJ0);
    m.noalias() += (rho * rule.weights[q] * detJ0) * N * N.transpose();
  }
  Eigen::VectorXd diagonal;
  switch (lumping) {
    case MassLumping::Consistent:
      break;
    case MassLumping::RowSum:
      diagonal = m.rowwise().sum();
      break;
    case MassLumping::HRZ:
      diagonal = m.diagonal() * (m.sum() / m.diagonal().sum());
      break;
  }
  M.setZero(n * d, n * d);
  for (int a = 0; a < n; ++a)
    for (int c = 0; c < d; ++c) {
      if (lumping != MassLumping::Consistent) {
        M(d * a + c, d * a + c) = diagonal[a];
        continue;
      }
      for (int b = 0; b < n; ++b) M(d * a + c, d * b + c) = m(a, b);
    }
}

std::shared_ptr<ContinuumElement> makeContinuumElement(CellType cell, std::shared_ptr<const Material> material) {
  switch (cell) {
    case CellType::Quad4:
      return std::make_shared<ContinuumSolid<2, 4, 4>>(cell, std::move(material));
    case CellType::Quad9:
      return std::make_shared<ContinuumSolid<2, 9, 9>>(cell, std::move(material));
    case CellType::Hex8:
      return std::make_shared<ContinuumSolid<3, 8, 8>>(cell, std::move(material));
    case CellType::Hex20:
      return std::make_shared<ContinuumSolid<3, 20, 27>>(cell, std::move(material));
    case CellType::Hex27:
      return std::make_shared<ContinuumSolid<3, 27, 27>>(cell, std::move(material));
    case CellType::Tet4:
      return std::make_shared<ContinuumSolid<3, 4, 1>>(cell, std::move(material));
    case CellType::Tet10:
      return std::make_shared<ContinuumSolid<3, 10, 4>>(cell, std::move(material));
    default:
      throw std::invalid_argument(std::string("makeContinuumElement: ") + cellTypeName(cell) +
                                  " is not an element cell type");
  }
}

}  // namespace ddc
