// Adapter from the Model's data to VTK pieces: one piece per subdomain.
#pragma once

#include <functional>

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

}  // namespace ddc
