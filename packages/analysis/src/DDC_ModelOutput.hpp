// Adapter from the Model's data to VTK pieces: one piece per subdomain.
#pragma once

#include "DDC_Model.hpp"
#include "DDC_VtkWriter.hpp"

namespace ddc {

/// Write the state `u` (owned layout) as VTK step `step`: one piece per
/// subdomain of this rank, reference coordinates, point data "displacement"
/// (3 components), cell data "cauchy_stress" (6: xx, yy, zz, xy, yz, xz),
/// "strain_energy_density", "body", "subdomain"; in a dynamic analysis also
/// point data "velocity" and "acceleration" (3 components each) when given.
/// Collective.
void writeVtkStep(VtkWriter& writer, const Model& model, const Vector& u, int step, double time,
                  const Vector* velocity = nullptr, const Vector* acceleration = nullptr);

}  // namespace ddc
