// The analysis' parameter schema (Analysis::getValidParameters()): the
// pieces other units of the analysis validate against.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <string>
#include <vector>

#include "DDC_ElementFactory.hpp"

namespace ddc {

/// The values of Mesh/Bodies/<body>/Generator: the built-in generators, Gmsh, Exodus.
extern const std::vector<std::string> kMeshGenerators;

/// "Mesh/Bodies/<Body Name>": Generator, one sublist per generator, and the
/// Element sublist (Type plus the union of the element types' parameters in
/// `factory`).
Teuchos::RCP<Teuchos::ParameterList> bodyValidParameters(const ElementFactory& factory);

/// "Dynamics": the integrator, the time steps, the Newmark parameters, the
/// mass matrix and the initial velocities (doc/user-guide.md, "Dynamics").
Teuchos::RCP<const Teuchos::ParameterList> dynamicsValidParameters();

}  // namespace ddc
