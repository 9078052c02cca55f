// The "Contact" sublist: formulation, contact pairs (slave / master side
// sets), search and active-set options.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <string>
#include <vector>

#include "DDC_Mesh.hpp"

namespace ddc {

/// One contact pair: slave nodes of a side set against a master side set.
struct ContactPairDefinition {
  std::string name;       ///< sublist name, for messages
  std::string slaveSet;   ///< qualified side set "Body/set"
  std::string masterSet;  ///< qualified side set
};

/// Validated contact options with automatic values resolved.
struct ContactOptions {
  /// false: conventional nonlinear NTS (projection and normal follow the
  /// current configuration); true: decomposed NTS (frozen over each step).
  bool decomposed = false;
  /// Start every step with all paired slave nodes active (the paper), or
  /// with the active set of the previous step.
  bool initialInContact = true;
  double searchRadius = 0.0;          ///< absolute
  double penetrationTolerance = 0.0;  ///< absolute: activate when g_N < -tol
  std::vector<ContactPairDefinition> pairs;

  bool enabled() const { return !pairs.empty(); }

  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
  /// Validate "Contact" (in place) against the mesh: sets must exist, be
  /// Quad4 sides, and slave and master must differ; no two pairs may share a
  /// slave node and a master segment (duplicated pairs) or each have its
  /// slave surface on the other's master surface (mirrored pairs), compared
  /// by nodes and segments, not by names (doc/contact.md "Pairs that
  /// overlap"). Every rank holds the mesh, so every rank throws alike.
  /// \throws InputError naming the parameter path or both pairs.
  static ContactOptions fromParameters(Teuchos::ParameterList& list, const Mesh& mesh, const std::string& path);
};

}  // namespace ddc
