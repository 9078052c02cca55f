#include "DDC_InitialPenetration.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <iomanip>
#include <limits>
#include <sstream>

#include "DDC_ContactComponent.hpp"

namespace ddc {

InitialPenetration initialPenetration(const Model& model) {
  InitialPenetration r;
  const double tol = model.contactOptions().penetrationTolerance;
  double deepest = 0.0;
  int node = std::numeric_limits<int>::max(), pair = -1;
  // A slot's gap is current on its owner (the pairing's results go only
  // where a slot is evaluated).
  for (int k : model.ownedSlots()) {
    const ContactSlot& s = model.contactSlots()[size_t(k)];
    if (!s.paired() || !(s.gap < -tol)) continue;
    if (-s.gap < deepest || (-s.gap == deepest && s.slaveNode >= node)) continue;
    deepest = -s.gap;
    node = s.slaveNode;
    pair = s.pair;
  }
  // The deepest over the ranks; of equally deep nodes the lowest id.
  const auto& comm = *model.comm();
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, deepest, Teuchos::outArg(r.depth));
  if (!(r.depth > 0.0)) return InitialPenetration{};
  const int mine = deepest == r.depth ? node : std::numeric_limits<int>::max();
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MIN, mine, Teuchos::outArg(r.node));
  const int myPair = (deepest == r.depth && node == r.node) ? pair : std::numeric_limits<int>::max();
  int p = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MIN, myPair, Teuchos::outArg(p));
  r.pair = model.contact()->pairName(p);
  return r;
}

std::string initialPenetrationWarning(const InitialPenetration& p) {
  std::ostringstream os;
  os << "warning: the bodies start overlapped: slave node " << p.node << " of contact pair '" << p.pair
     << "' lies " << p.depth << " behind its master surface (the deepest "
        "slave node beyond Contact/Penetration Tolerance); contact pushes them apart in the first step, "
        "adding energy no load supplies (doc/user-guide.md, \"Contact in dynamics\": start the bodies touching "
        "or apart)";
  return os.str();
}

std::string injectedEnergyWarning(const InitialPenetration& p, double before, double after, double work,
                                  double dissipated) {
  // Friction took `dissipated` out of the energy the step had to keep.
  const double gained = after + dissipated - before - work;
  std::ostringstream os;
  os << "warning: step 1: the initial penetration (" << p.depth << " at slave node " << p.node << " of contact pair '"
     << p.pair << "') changed the total energy from " << before << " to " << after << " with external work "
     << work;
  if (dissipated > 0.0) os << " and frictional dissipation " << dissipated;
  os << ": " << gained << " beyond it";
  if (before > 0.0) os << " (" << (gained >= 0 ? "+" : "") << std::setprecision(3) << 100.0 * gained / before << " %)";
  return os.str();
}

}  // namespace ddc
