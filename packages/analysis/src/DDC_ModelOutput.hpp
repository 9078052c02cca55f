// Adapters from the Model's data to the model-free writers of the io
// package: VTK pieces (one per subdomain) and Exodus II step values.
#pragma once

#include <functional>

#include "DDC_ExodusWriter.hpp"
#include "DDC_Model.hpp"
#include "DDC_VtkWriter.hpp"

namespace ddc {

/// One element of this rank at an output state (forEachLocalElementOutput()).
struct ElementOutput {
  int element;
  const int* nodes;  ///< its mesh nodes (mesh order)
  int numNodes;
  const Eigen::MatrixXd& ue;       ///< displacements, numNodes x dim
  const ElementPostResult& post;   ///< stresses and energy density (zeros if the element refused the state)
};

/// Call `f` for every element of this rank (Model::localElements()) with its
/// displacements at `uOverlap` (Model::toOverlap()) and its postprocess():
/// the element loop of the VTK and Exodus II outputs.
void forEachLocalElementOutput(const Model& model, const Vector& uOverlap,
                               const std::function<void(const ElementOutput&)>& f);

/// Write the state `u` (owned layout) as VTK step `step`: one piece per
/// subdomain of this rank, reference coordinates, point data "displacement"
/// (3 components), cell data "cauchy_stress" (6: xx, yy, zz, xy, yz, xz),
/// "strain_energy_density", "body", "subdomain"; in a dynamic analysis also
/// point data "velocity" and "acceleration" (3 components each) when given.
/// Collective.
void writeVtkStep(VtkWriter& writer, const Model& model, const Vector& u, int step, double time,
                  const Vector* velocity = nullptr, const Vector* acceleration = nullptr);

/// The Exodus II variables of a run of `model`: nodal displ_x, displ_y
/// (, displ_z), in dynamics vel_* and acc_*, with contact contact_gap,
/// contact_pressure, contact_multiplier (0 away from slave nodes); element
/// stress_xx, stress_yy, stress_zz, stress_xy, stress_yz, stress_xz (Cauchy),
/// von_mises, strain_energy_density; the global variables `globals`.
ExodusVariables exodusVariables(const Model& model, bool dynamics, std::vector<std::string> globals);

/// Write the state `u` (owned layout; in dynamics with `velocity` and
/// `acceleration`) and the global values as the next step of `writer`
/// (made with exodusVariables()). Collective.
void writeExodusStep(ExodusWriter& writer, const Model& model, double time, const Vector& u,
                     const Vector* velocity, const Vector* acceleration, const std::vector<double>& globals);

}  // namespace ddc
