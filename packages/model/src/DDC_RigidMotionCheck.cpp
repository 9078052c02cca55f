#include "DDC_RigidMotionCheck.hpp"

#include "DDC_Error.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace ddc {

namespace {

/// Entries of a free-motion basis vector below this are round-off (the
/// vectors are in reduced row echelon form: leading entries 1).
constexpr double kNegligible = 1e-8;

/// "x", "y", "z" for an axis-aligned unit vector, else "(a, b[, c])".
std::string directionText(Eigen::Vector3d a, int dim) {
  a /= a.norm();
  int nonzero = 0, axis = 0;
  for (int i = 0; i < dim; ++i)
    if (std::abs(a[i]) > 1e-6) ++nonzero, axis = i;
    else a[i] = 0.0;
  if (nonzero == 1) return std::string(1, "xyz"[axis]);
  char buf[96];
  if (dim == 2)
    std::snprintf(buf, sizeof buf, "(%.3g, %.3g)", a[0], a[1]);
  else
    std::snprintf(buf, sizeof buf, "(%.3g, %.3g, %.3g)", a[0], a[1], a[2]);
  return buf;
}

std::string pointText(Eigen::Vector3d p, double scale, int dim) {
  for (int i = 0; i < 3; ++i)
    if (std::abs(p[i]) < 1e-9 * scale) p[i] = 0.0;
  char buf[96];
  if (dim == 2)
    std::snprintf(buf, sizeof buf, "(%.4g, %.4g)", p[0], p[1]);
  else
    std::snprintf(buf, sizeof buf, "(%.4g, %.4g, %.4g)", p[0], p[1], p[2]);
  return buf;
}

}  // namespace

RigidMotionCheck::RigidMotionCheck(const Mesh& mesh, int numSlots, const Teuchos::Comm<int>* comm,
                                   const std::function<bool(int)>& counted)
    : dim_(mesh.dim()), modesPerBody_(mesh.dim() == 2 ? 3 : 6), numBodies_(mesh.numBodies()), numSlots_(numSlots) {
  DDC_CHECK(!mesh.isPart() || (comm && counted), "RigidMotionCheck: a part of a mesh needs its ranks");
  nodeBody_.assign(mesh.numNodes(), -1);
  // Per body: the sum of its nodes' positions and their number, then the
  // largest distance from the centroid; over the ranks for a part.
  std::vector<double> sums(4 * size_t(numBodies_), 0.0), radii(numBodies_, 0.0);
  for (int b = 0; b < numBodies_; ++b) {
    const Body& body = mesh.body(b);
    bodyNames_.push_back(body.name);
    for (int n = body.firstNode; n < body.firstNode + body.numNodes; ++n) {
      nodeBody_[n] = b;
      if (mesh.isPart() && !counted(n)) continue;
      for (int c = 0; c < 3; ++c) sums[4 * size_t(b) + c] += mesh.coord(n)[c];
      sums[4 * size_t(b) + 3] += 1.0;
    }
  }
  if (mesh.isPart()) {
    std::vector<double> local = sums;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, static_cast<int>(sums.size()), local.data(), sums.data());
  }
  for (int b = 0; b < numBodies_; ++b) {
    const Body& body = mesh.body(b);
    const double count = sums[4 * size_t(b) + 3];
    Eigen::Vector3d c(sums[4 * size_t(b)], sums[4 * size_t(b) + 1], sums[4 * size_t(b) + 2]);
    if (count > 0) c /= count;
    for (int n = body.firstNode; n < body.firstNode + body.numNodes; ++n)
      radii[b] = std::max(radii[b], (Eigen::Vector3d(mesh.coord(n).data()) - c).norm());
    centre_.push_back(c);
  }
  if (mesh.isPart()) {
    std::vector<double> local = radii;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, numBodies_, local.data(), radii.data());
  }
  for (int b = 0; b < numBodies_; ++b) radius_.push_back(radii[b] > 0.0 ? radii[b] : 1.0);
  reset();
}

void RigidMotionCheck::reset() {
  prescribed_ = Eigen::MatrixXd::Zero(numModes(), numModes());
  rows_.assign(static_cast<size_t>(numSlots_) * (numModes() + 1), 0.0);
}

int RigidMotionCheck::modeValues(int b, int c, const std::array<double, 3>& x, double* values) const {
  const Eigen::Vector3d r = (Eigen::Vector3d(x.data()) - centre_[b]) / radius_[b];
  for (int j = 0; j < modesPerBody_; ++j) values[j] = 0.0;
  values[c] = 1.0;  // translation along c
  if (dim_ == 2) {
    values[2] = c == 0 ? -r[1] : r[0];  // rotation about z: e_z x r
  } else {
    // rotation about axis k: (e_k x r)_c
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[k] = 1.0;
      values[3 + k] = e.cross(r)[c];
    }
  }
  return b;
}

void RigidMotionCheck::addPrescribed(int n, int c, const std::array<double, 3>& x) {
  double v[6];
  const int b = modeValues(nodeBody_[n], c, x, v);
  const int o = b * modesPerBody_;
  for (int i = 0; i < modesPerBody_; ++i)
    for (int j = 0; j < modesPerBody_; ++j) prescribed_(o + i, o + j) += v[i] * v[j];
}

void RigidMotionCheck::addRowEntry(int slot, int n, int c, const std::array<double, 3>& x, double coefficient) {
  addBodyRowEntry(slot, nodeBody_[n], c, x, coefficient);
}

void RigidMotionCheck::addBodyRowEntry(int slot, int body, int c, const std::array<double, 3>& x,
                                       double coefficient) {
  double v[6];
  const int b = modeValues(body, c, x, v);
  double* row = rows_.data() + static_cast<size_t>(slot) * (numModes() + 1);
  for (int j = 0; j < modesPerBody_; ++j) row[b * modesPerBody_ + j] += coefficient * v[j];
  row[numModes()] += coefficient * coefficient;
}

Eigen::MatrixXd RigidMotionCheck::freeBasis(const Teuchos::Comm<int>& comm) const {
  const int m = numModes();
  Eigen::MatrixXd G(m, m);
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, m * m, prescribed_.data(), G.data());
  if (numSlots_ > 0) {
    std::vector<double> rows(rows_.size());
    Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, static_cast<int>(rows_.size()), rows_.data(), rows.data());
    for (int k = 0; k < numSlots_; ++k) {
      const Eigen::Map<const Eigen::VectorXd> v(rows.data() + static_cast<size_t>(k) * (m + 1), m);
      const double norm2 = rows[static_cast<size_t>(k) * (m + 1) + m];
      if (norm2 > 0.0) G += v * v.transpose() / norm2;
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(G);
  const double largest = std::max(eig.eigenvalues().maxCoeff(), 1.0);
  std::vector<int> free;
  for (int i = 0; i < m; ++i)
    if (eig.eigenvalues()[i] <= kRestraintTolerance * largest) free.push_back(i);
  // Reduced row echelon form of the free directions (as rows), pivoting in
  // column order: translations before rotations, body by body, so that an
  // axis-aligned free motion comes out as one axis.
  Eigen::MatrixXd F(free.size(), m);
  for (size_t i = 0; i < free.size(); ++i) F.row(i) = eig.eigenvectors().col(free[i]).transpose();
  int r = 0;
  for (int j = 0; j < m && r < F.rows(); ++j) {
    Eigen::Index p;
    const double best = F.col(j).tail(F.rows() - r).cwiseAbs().maxCoeff(&p);
    if (best <= kNegligible) continue;
    F.row(r).swap(F.row(r + p));
    F.row(r) /= F(r, j);
    for (int i = 0; i < F.rows(); ++i)
      if (i != r) F.row(i) -= F(i, j) * F.row(r);
    ++r;
  }
  F = F.unaryExpr([](double v) { return std::abs(v) <= kNegligible ? 0.0 : v; });
  return F.transpose();
}

std::string RigidMotionCheck::freeMotions(const Teuchos::Comm<int>& comm) const {
  const Eigen::MatrixXd F = freeBasis(comm);
  std::ostringstream os;
  for (int i = 0; i < F.cols(); ++i) {
    if (i > 0) os << "; ";
    bool first = true;
    for (int b = 0; b < numBodies_; ++b) {
      const auto v = F.col(i).segment(b * modesPerBody_, modesPerBody_);
      if (v.cwiseAbs().maxCoeff() == 0.0) continue;
      os << (first ? "" : " together with ") << "body '" << bodyNames_[b] << "' ";
      first = false;
      Eigen::Vector3d t = Eigen::Vector3d::Zero(), w = Eigen::Vector3d::Zero();
      for (int c = 0; c < dim_; ++c) t[c] = v[c];
      if (dim_ == 2)
        w[2] = v[2];
      else
        w = v.tail(3);
      if (w.norm() == 0.0) {
        os << "translation along " << directionText(t, dim_);
        continue;
      }
      // Motion t + ω × (x − c) with ω = w / ρ: a rotation about the axis
      // along ω through p = c + ω × t / |ω|² (plus a slide along the axis).
      const Eigen::Vector3d omega = w / radius_[b];
      const Eigen::Vector3d p = centre_[b] + omega.cross(t) / omega.squaredNorm();
      os << "rotation about " << (dim_ == 2 ? "the point " : "the " + directionText(w, 3) + " axis through ")
         << pointText(p, radius_[b], dim_);
      if (std::abs(omega.dot(t)) > 1e-6 * omega.norm() * (t.norm() + radius_[b] * omega.norm()))
        os << " with a slide along that axis";
    }
  }
  return os.str();
}

}  // namespace ddc
