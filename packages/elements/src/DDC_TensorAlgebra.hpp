// Small fixed-size tensor helpers shared by the materials and the continuum
// elements: the adjugate of a 2x2 or 3x3 matrix (inverse = adj / det, the
// form both use so that det is computed, and checked, once) and the
// symmetric tensor of a Voigt vector.
#pragma once

#include <Eigen/Dense>

#include "DDC_Material.hpp"

namespace ddc {

/// Adjugate (transposed cofactor matrix): A adj(A) = det(A) I.
inline Eigen::Matrix2d adjugate(const Eigen::Matrix2d& A) {
  Eigen::Matrix2d adj;
  adj << A(1, 1), -A(0, 1), -A(1, 0), A(0, 0);
  return adj;
}

/// Adjugate of a 3x3 matrix: adj(A)_ij = cofactor_ji.
inline Eigen::Matrix3d adjugate(const Eigen::Matrix3d& A) {
  Eigen::Matrix3d adj;
  adj(0, 0) = A(1, 1) * A(2, 2) - A(1, 2) * A(2, 1);
  adj(0, 1) = A(0, 2) * A(2, 1) - A(0, 1) * A(2, 2);
  adj(0, 2) = A(0, 1) * A(1, 2) - A(0, 2) * A(1, 1);
  adj(1, 0) = A(1, 2) * A(2, 0) - A(1, 0) * A(2, 2);
  adj(1, 1) = A(0, 0) * A(2, 2) - A(0, 2) * A(2, 0);
  adj(1, 2) = A(0, 2) * A(1, 0) - A(0, 0) * A(1, 2);
  adj(2, 0) = A(1, 0) * A(2, 1) - A(1, 1) * A(2, 0);
  adj(2, 1) = A(0, 1) * A(2, 0) - A(0, 0) * A(2, 1);
  adj(2, 2) = A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0);
  return adj;
}

/// The symmetric dim x dim tensor of a Voigt stress vector.
template <int dim>
Eigen::Matrix<double, dim, dim> symmetricFromVoigt(const VoigtVector<dim>& v) {
  Eigen::Matrix<double, dim, dim> m;
  for (int a = 0; a < Voigt<dim>::kSize; ++a) {
    m(Voigt<dim>::kRow[a], Voigt<dim>::kCol[a]) = v(a);
    m(Voigt<dim>::kCol[a], Voigt<dim>::kRow[a]) = v(a);
  }
  return m;
}

}  // namespace ddc
