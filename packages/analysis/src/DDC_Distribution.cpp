#include "DDC_Distribution.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <sstream>

#include "DDC_ContactComponent.hpp"
#include "DDC_Memory.hpp"
#include "DDC_Model.hpp"

namespace ddc {

namespace {

/// "8251 of 131072 <what> (6.3 %)"
std::string share(long long part, long long whole, const char* what) {
  std::ostringstream os;
  os << part << " of " << whole << " " << what;
  if (whole > 0) {
    os.setf(std::ios::fixed);
    os.precision(1);
    os << " (" << 100.0 * double(part) / double(whole) << " %)";
  }
  return os.str();
}

}  // namespace

RankShare rankShare(const Model& model, long long coarseRows) {
  RankShare s;
  s.elements = static_cast<long long>(model.localElements().size());
  const Map& owned = *model.ownedMap();
  for (int n = 0; n < model.mesh().numNodes(); ++n) s.nodes += owned.isNodeGlobalElement(model.dof(n, 0)) ? 1 : 0;
  if (model.hasContact()) s.slots = static_cast<long long>(model.contact()->ownedSlots().size());
  s.coarseRows = coarseRows;
  s.heldElements = model.mesh().numElements();
  s.heldNodes = model.mesh().numNodes();
  return s;
}

std::string distributionLine(const Teuchos::Comm<int>& comm, const Model& model, const RankShare& mine,
                             double estimatedBytesPerRank, MeshOrigin origin) {
  const long long local[6] = {mine.elements, mine.nodes, mine.slots, mine.coarseRows, mine.heldElements,
                              mine.heldNodes};
  long long most[6] = {0, 0, 0, 0, 0, 0}, total[6] = {0, 0, 0, 0, 0, 0};
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 6, local, most);
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 6, local, total);
  const long long elements = model.mesh().numGlobalElements(), nodes = model.mesh().numGlobalNodes();
  const long long slots = model.hasContact() ? static_cast<long long>(model.contact()->slots().size()) : 0;
  std::ostringstream os;
  os << "distribution: the busiest rank assembles " << share(most[0], elements, "elements") << ", owns "
     << share(most[1], nodes, "nodes");
  if (slots > 0) os << ", " << share(most[2], slots, "contact slots");
  if (total[3] > 0) os << ", " << share(most[3], total[3], "coarse rows");
  if (model.mesh().isPart())
    os << "; the busiest rank holds " << share(most[4], elements, "elements") << " and "
       << share(most[5], nodes, "nodes") << " of the mesh (its elements' nodes, those shared with other ranks "
       << "included)"
       << (origin == MeshOrigin::Ranges ? "; no rank held the whole mesh (built in ranges of elements)"
                                        : "; each rank built the whole mesh and kept its part")
       << (slots > 0 ? "; every rank holds all " + std::to_string(slots) + " contact slots" : "");
  else
    os << "; every rank holds the whole mesh (" << elements << " elements, " << nodes << " nodes)"
       << (slots > 0 ? " and all " + std::to_string(slots) + " contact slots" : "");
  os << "; estimated " << formatBytes(estimatedBytesPerRank) << " per rank";
  return os.str();
}

}  // namespace ddc
