// The "Contact" sublist: formulation, contact pairs (slave / master side
// sets), search and active-set options.
//
// Contact surfaces are side sets of any element type: sides of 2-D bodies
// (Line2 segments of Quad4, Line3 of Quad9) and faces of 3-D bodies (Tri3,
// Tri6, Quad4, Quad8, Quad9 faces of Tet4, Tet10, Hex8, Hex20, Hex27); see
// DDC_ContactSurface.hpp. The automatic length scale h (Search Radius 0,
// Penetration Tolerance) is the mean size of the master facets of all pairs:
//   2-D   the length |x_end − x_start| of a segment (for a Line3 segment the
//         chord, not the arc; for Line2 the segment length as before);
//   3-D   the square root of the face's area, taken as the area of the
//         polygon through its corners (½|(x_1 − x_0) × (x_2 − x_0)| for a
//         triangle, ½|(x_2 − x_0) × (x_3 − x_1)| for a quadrilateral).
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
  /// Coulomb friction coefficient μ ≥ 0 ("Friction Coefficient"; 0:
  /// frictionless).
  double friction = 0.0;
};

/// Validated contact options with automatic values resolved.
struct ContactOptions {
  /// false: conventional nonlinear NTS (projection and normal follow the
  /// current configuration); true: decomposed NTS (frozen over each step).
  bool decomposed = false;
  /// Start every step with all paired slave nodes active (the paper), or
  /// with the active set of the previous step. "Automatic" gives true here;
  /// a dynamic Analysis sets it false.
  bool initialInContact = true;
  /// With initialInContact: only when no slave node is active (the first
  /// step, or once the bodies have separated); otherwise the step starts
  /// from the previous step's active set. "Automatic" in a quasi-static run
  /// with friction (doc/user-guide.md, "The active set at the start of a
  /// step").
  bool inContactOnlyWhenNoneActive = false;
  double searchRadius = 0.0;          ///< absolute (automatic: h, the file comment)
  double length = 1.0;                ///< h, the mean master facet size (the file comment)
  double penetrationTolerance = 0.0;  ///< absolute: activate when g_N < -tol (the parameter times h)
  /// Conventional formulation: when the pairing cycles inside an increment,
  /// keep it for the rest of the increment (true) or fail the increment
  /// (false: bisection). "Pairing Cycles", doc/contact.md.
  bool freezeCyclingPairing = true;
  std::vector<ContactPairDefinition> pairs;

  bool enabled() const { return !pairs.empty(); }
  /// Whether some pair has friction (μ > 0).
  bool frictional() const {
    for (const auto& p : pairs)
      if (p.friction > 0.0) return true;
    return false;
  }

  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
  /// Validate "Contact" (in place) against the mesh: sets must exist and be
  /// side sets (a node set has no facets) of facets of an element type
  /// (contactFacetType()), and slave and master must differ; no two pairs may
  /// share a slave node and a master facet (duplicated pairs) or each have its
  /// slave surface on the other's master surface (mirrored pairs), compared
  /// by nodes and by facets' sorted corner nodes, not by names (doc/contact.md
  /// "Pairs that overlap"). Formulation "Node-To-Surface" / "Decomposed
  /// Node-To-Surface" are synonyms of "Node-To-Segment" / "Decomposed
  /// Node-To-Segment". With a whole mesh on every rank every rank throws
  /// alike; with a part of a mesh (Mesh::isPart()) the checks and the
  /// length scale are the whole mesh's, from the parts of the ranks of
  /// `comm` (collective then; unused for a whole mesh).
  /// \throws InputError naming the parameter path or both pairs.
  static ContactOptions fromParameters(Teuchos::ParameterList& list, const Mesh& mesh, const std::string& path,
                                       MPI_Comm comm = MPI_COMM_SELF);
};

}  // namespace ddc
