// Depth (c) of doc/embedding.md in 3-D: a host with its own mesh of two Hex8
// blocks uses ddc::ContactComponent alone (no ddc::Analysis, no FETI-DP) for
// the pairing, the gaps, the active set and the constraint rows of the
// decomposed node-to-surface element.
//
// The host's mesh: a lower block [0, 2] x [0, 2] x [0, 1] of 4 x 4 x 2 Hex8
// and an upper block [0.5, 1.5] x [0.5, 1.5] x [1 + g0, 1.5 + g0] of
// 3 x 3 x 1 Hex8 (non-matching meshes), g0 = 0.05 apart. Its nodes are
// numbered lower block first; node n's DOFs are 3n, 3n + 1, 3n + 2, and
// ranks own contiguous ranges of nodes. Slave: the upper block's bottom face;
// master: the lower block's top face.
//
// It checks what a host relies on: every slave node pairs with the gap g0
// and the normal +z; after the upper block moves down by 0.08 every slot is
// active and its gap, summed from the slave and the master parts that
// assemble() hands out (possibly on two ranks), is g0 - 0.08. Run on any
// number of ranks: mpirun -np 2 host_contact_3d
#include <DDC_ContactComponent.hpp>
#include <DDC_Element.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Core.hpp>
#include <cmath>
#include <iostream>
#include <map>
#include <vector>

namespace {

/// One structured Hex8 block of the host's mesh.
struct Block {
  int nx, ny, nz;         // elements per direction
  double x0, y0, z0, hx, hy, hz;
  int firstNode;
  int node(int i, int j, int k) const { return firstNode + i + (nx + 1) * (j + (ny + 1) * k); }
  int numNodes() const { return (nx + 1) * (ny + 1) * (nz + 1); }
  Eigen::Vector3d X(int i, int j, int k) const { return {x0 + i * hx, y0 + j * hy, z0 + k * hz}; }
};

constexpr double kGap0 = 0.05;
constexpr double kPush = 0.08;
constexpr double kTolerance = 1e-12;  // round-off of coordinates of size 1

}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const int me = comm->getRank(), P = comm->getSize();
  int failures = 0;
  try {
    const Block lower{4, 4, 2, 0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 0};
    const Block upper{3, 3, 1, 0.5, 0.5, 1.0 + kGap0, 1.0 / 3, 1.0 / 3, 0.5, lower.numNodes()};
    const int numNodes = lower.numNodes() + upper.numNodes();
    auto owner = [&](int n) { return static_cast<int>(static_cast<long>(n) * P / numNodes); };

    // The host's DOF map: the DOFs of the nodes this rank owns.
    std::vector<ddc::GO> myDofs;
    for (int n = 0; n < numNodes; ++n)
      if (owner(n) == me)
        for (int c = 0; c < 3; ++c) myDofs.push_back(3 * n + c);
    auto map = Teuchos::rcp(new ddc::Map(3 * numNodes, Teuchos::ArrayView<const ddc::GO>(myDofs), 0, comm));

    // The component: decomposed counterparts, no Line2 pairs, so no segment
    // elements; the facet elements are the built-in ones.
    ddc::ContactComponentOptions options;
    options.decomposed = true;
    options.searchRadius = 0.5;           // absolute, about an element
    options.penetrationTolerance = 1e-9;  // absolute
    ddc::ContactComponent contact(comm, options);

    // Surface nodes, each registered by the rank that owns its DOFs.
    std::vector<ddc::ContactNode> nodes;
    std::vector<ddc::ContactNodeDofs> nodeDofs;
    auto addNode = [&](const Block& b, int i, int j, int k) {
      const int n = b.node(i, j, k);
      if (owner(n) != me) return;
      nodes.push_back({n, b.X(i, j, k)});
      nodeDofs.push_back({n, {{3 * n, 3 * n + 1, 3 * n + 2}}, {{false, false, false}}});
    };
    for (int j = 0; j <= lower.ny; ++j)
      for (int i = 0; i <= lower.nx; ++i) addNode(lower, i, j, lower.nz);
    for (int j = 0; j <= upper.ny; ++j)
      for (int i = 0; i <= upper.nx; ++i) addNode(upper, i, j, 0);
    contact.registerNodes(nodes);

    // The pair: every rank registers the same pair; rank 0 gives the facets
    // and the slave nodes (any split works: the shares are merged).
    ddc::ContactPairSurfaces pair;
    pair.name = "blocks";
    pair.slaveName = "upper/bottom";
    pair.masterName = "lower/top";
    pair.slaveFacetType = pair.masterFacetType = ddc::CellType::Quad4;
    if (me == 0) {
      long id = 0;
      // Master: the lower block's top face, counter-clockwise seen from +z
      // (outward); behind each facet an element of depth hz.
      for (int j = 0; j < lower.ny; ++j)
        for (int i = 0; i < lower.nx; ++i) {
          const int k = lower.nz;
          pair.masterFacets.push_back({id++,
                                       {lower.node(i, j, k), lower.node(i + 1, j, k), lower.node(i + 1, j + 1, k),
                                        lower.node(i, j + 1, k)},
                                       /*element=*/i + lower.nx * j, /*subdomain=*/0, /*depth=*/lower.hz});
        }
      // Slave: the upper block's bottom face, counter-clockwise seen from -z.
      id = 0;
      for (int j = 0; j < upper.ny; ++j)
        for (int i = 0; i < upper.nx; ++i)
          pair.slaveFacets.push_back({id++,
                                      {upper.node(i, j, 0), upper.node(i, j + 1, 0), upper.node(i + 1, j + 1, 0),
                                       upper.node(i + 1, j, 0)},
                                      /*element=*/1000 + i + upper.nx * j, /*subdomain=*/1, /*depth=*/0.0});
      for (int j = 0; j <= upper.ny; ++j)
        for (int i = 0; i <= upper.nx; ++i) pair.slaveNodes.push_back(upper.node(i, j, 0));
    }
    contact.registerPair(pair);
    contact.commit();
    contact.setDofs(map, nodeDofs);

    // The first pairing: nothing is paired before it.
    ddc::Vector u(map);
    contact.updatePairing(u, /*global=*/true, /*freeze=*/true);
    for (const auto& w : contact.takeWarnings())
      if (me == 0) std::cerr << "warning: " << w << "\n";
    for (size_t k = 0; k < contact.slots().size(); ++k) {
      const ddc::ContactSlot& s = contact.slots()[k];
      if (!s.paired() || std::abs(s.gap - kGap0) > kTolerance || (s.normal - Eigen::Vector3d(0, 0, 1)).norm() > kTolerance)
        ++failures, std::cerr << "not paired as expected: " << contact.describeSlot(static_cast<int>(k)) << "\n";
    }

    // Push the upper block down: every slot penetrates and activates.
    for (int n = upper.firstNode; n < numNodes; ++n)
      if (owner(n) == me) u.replaceGlobalValue(3 * n + 2, -kPush);
    ddc::Vector lambda(contact.multiplierMap());
    contact.updateActiveSet(u, &lambda);

    // The gap of each slot from the multiplier rows of its two counterparts:
    // each part arrives where it is evaluated; the host sums them.
    const size_t numSlots = contact.slots().size();
    std::map<ddc::GO, size_t> slotOf;
    for (size_t k = 0; k < numSlots; ++k) slotOf[contact.multiplierId(static_cast<int>(k))] = k;
    std::vector<double> mine(numSlots, 0.0), gaps(numSlots, 0.0);
    contact.assemble(u, &lambda, ddc::kResidual, [&](const std::vector<ddc::GO>& dofs, ddc::ElementResult& r) {
      mine[slotOf.at(dofs.back())] += r.residual[static_cast<Eigen::Index>(dofs.size()) - 1];
    });
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, static_cast<int>(numSlots), mine.data(), gaps.data());
    for (size_t k = 0; k < numSlots; ++k)
      if (!contact.slots()[k].active || std::abs(gaps[k] - (kGap0 - kPush)) > kTolerance)
        ++failures, std::cerr << contact.describeSlot(static_cast<int>(k)) << ": gap " << gaps[k] << ", expected "
                              << kGap0 - kPush << "\n";
    if (me == 0)
      std::cout << "host contact 3d: " << numSlots << " slots, " << contact.numActive() << " active, gap "
                << (numSlots ? gaps[0] : 0.0) << " on " << P << " ranks\n";
  } catch (const std::exception& e) {
    std::cerr << "host contact 3d: " << e.what() << "\n";
    ++failures;
  }
  int all = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, failures, Teuchos::outArg(all));
  if (me == 0) std::cout << (all ? "host contact 3d: FAILED" : "host contact 3d: OK") << std::endl;
  return all ? 1 : 0;
}
