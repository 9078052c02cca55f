// Adapter from the Model's data to VTK pieces: one piece per subdomain.
#pragma once

#include "DDC_Model.hpp"
#include "DDC_VtkWriter.hpp"

namespace ddc {

/// Write the state `u` (owned layout) as VTK step `step`: one piece per
/// subdomain of this rank, reference coordinates, point data "displacement"
/// (3 components), cell data "cauchy_stress" (6: xx, yy, zz, xy, yz, xz),
/// "strain_energy_density", "body", "subdomain". Collective.
void writeVtkStep(VtkWriter& writer, const Model& model, const Vector& u, int step, double time);

}  // namespace ddc
