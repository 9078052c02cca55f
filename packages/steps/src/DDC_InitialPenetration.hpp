// A dynamic run whose contact pairs start overlapped: a slave node paired
// within the search radius but behind its master surface. Contact pushes
// the bodies apart in the first step, and the strain energy of that push
// becomes kinetic energy no load supplied (doc/user-guide.md, "Contact in
// dynamics"). The step loop warns at the start (the deepest node) and after
// the first step (the energy it added beyond the external work).
#pragma once

#include <string>

#include "DDC_Model.hpp"

namespace ddc {

/// The deepest initial penetration of a model's contact pairs.
struct InitialPenetration {
  double depth = 0.0;  ///< > 0: the deepest slave node lies this far behind its master surface
  int node = -1;       ///< that slave node
  std::string pair;    ///< its pair's name
};

/// The penetration of the current pairing (the reference configuration at
/// the start of a run) beyond Contact/Penetration Tolerance; depth 0 if
/// none. Collective: every rank gets the same answer.
InitialPenetration initialPenetration(const Model& model);

/// "warning: ..." naming the depth, node and pair.
std::string initialPenetrationWarning(const InitialPenetration& p);

/// "warning: ..." on the energy the first step gained: `before` the total
/// energy at the start, `after` at the first step's end, `work` the
/// external work of that step, `dissipated` the frictional dissipation of
/// that step (doc/contact.md, "Friction"; named in the message when > 0).
std::string injectedEnergyWarning(const InitialPenetration& p, double before, double after, double work,
                                  double dissipated = 0.0);

}  // namespace ddc
