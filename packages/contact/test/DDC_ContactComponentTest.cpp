// The contact component driven by a host with its own node and DOF
// numbering, no mesh and no analysis (doc/embedding.md, "(c) The
// contact component"): registration, pairing, rows, gaps and the active set of the
// decomposed element, contributions of the conventional one, and the errors
// of a registration that does not match the host's DOF ownership. On 2 ranks
// the master surface and the slave surface belong to different ranks, so
// every value that pairs them has crossed ranks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Teuchos_DefaultComm.hpp>
#include <Tpetra_Core.hpp>
#include <cmath>
#include <memory>

#include "DDC_ContactComponent.hpp"
#include "DDC_Error.hpp"
#include "DDC_Friction.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using ddc::ContactComponent;
using ddc::GO;
using ddc::InputError;
using ddc::test::kRoundoff;
using ::testing::HasSubstr;

// The host: a flat master surface y = 0 (nodes 0, 1, 2 at x = 0, 1, 2; the
// master body below) and a slave surface y = kGap0 above it (nodes 10, 11 at
// x = 0.5, 1.5; the slave body above). Host DOFs: node n's u_x, u_y are
// 2·i, 2·i + 1 with i its position in {0, 1, 2, 10, 11}. The master nodes
// belong to rank 0, the slave nodes to the last rank.
constexpr double kGap0 = 0.1;
const int kNodes[5] = {0, 1, 2, 10, 11};
const double kX[5][2] = {{0, 0}, {1, 0}, {2, 0}, {0.5, kGap0}, {1.5, kGap0}};

struct Host {
  Teuchos::RCP<const Teuchos::Comm<int>> comm = Tpetra::getDefaultComm();
  int me = comm->getRank(), last = comm->getSize() - 1;
  bool ownsMaster() const { return me == 0; }
  bool ownsSlave() const { return me == last; }
  bool owns(int i) const { return i < 3 ? ownsMaster() : ownsSlave(); }
  Teuchos::RCP<const ddc::Map> map() const {
    std::vector<GO> gids;
    for (int i = 0; i < 5; ++i)
      if (owns(i)) gids.insert(gids.end(), {GO(2 * i), GO(2 * i + 1)});
    return Teuchos::rcp(new ddc::Map(10, Teuchos::ArrayView<const GO>(gids), 0, comm));
  }
};

/// Register the host's surfaces; `tweak` may change this rank's share first.
std::unique_ptr<ContactComponent> registered(const Host& h, bool decomposed,
                                             const std::function<void(std::vector<ddc::ContactNode>&,
                                                                      ddc::ContactPairSurfaces&)>& tweak = {}) {
  ddc::ContactComponentOptions o;
  o.decomposed = decomposed;
  o.searchRadius = 0.5;
  o.penetrationTolerance = 1e-12;
  auto c = std::make_unique<ContactComponent>(h.comm, o);
  std::vector<ddc::ContactNode> nodes;
  for (int i = 0; i < 5; ++i)
    if (h.owns(i)) nodes.push_back({kNodes[i], Eigen::Vector2d(kX[i][0], kX[i][1])});
  ddc::ContactPairSurfaces pair;
  pair.name = "P";
  pair.slaveName = "upper/bottom";
  pair.masterName = "lower/top";
  if (h.ownsMaster()) {
    // Master body below: travelling right to left keeps it on the left.
    pair.masterFacets.push_back({0, {{2, 1}}, 100, 0, 1.0});
    pair.masterFacets.push_back({1, {{1, 0}}, 101, 0, 1.0});
  }
  if (h.ownsSlave()) {
    pair.slaveFacets.push_back({0, {{10, 11}}, 200, 1, 0.0});
    pair.slaveNodes = {10, 11};
  }
  if (tweak) tweak(nodes, pair);
  c->registerNodes(nodes);
  c->registerPair(pair);
  c->commit();
  return c;
}

std::vector<ddc::ContactNodeDofs> dofsOf(const Host& h) {
  std::vector<ddc::ContactNodeDofs> d;
  for (int i = 0; i < 5; ++i)
    if (h.owns(i)) d.push_back({kNodes[i], {{GO(2 * i), GO(2 * i + 1)}}, {{false, false}}});
  return d;
}

/// u with the slave surface moved down by `down` (y of nodes 10, 11).
Teuchos::RCP<ddc::Vector> state(const Host& h, const Teuchos::RCP<const ddc::Map>& map, double down) {
  auto u = Teuchos::rcp(new ddc::Vector(map));
  for (int i = 3; i < 5; ++i)
    if (h.owns(i)) u->replaceGlobalValue(GO(2 * i + 1), -down);
  return u;
}

TEST(ContactComponent, DecomposedRowsGapsAndActiveSetAcrossRanks) {
  Host h;
  auto c = registered(h, true);
  auto map = h.map();
  c->setDofs(map, dofsOf(h));  // multipliers not in the host's vector
  ASSERT_EQ(c->slots().size(), 2u);
  EXPECT_EQ(c->ownedSlots().size(), h.ownsSlave() ? 2u : 0u);
  auto u = state(h, map, 0.0);
  const long exchanges0 = c->exchanges();
  c->updatePairing(*u, /*global=*/true, /*freeze=*/true);
  EXPECT_EQ(c->exchanges(), exchanges0 + 1) << "one exchange per step-end pairing";
  for (int k = 0; k < 2; ++k) {
    const auto& s = c->slots()[k];
    ASSERT_TRUE(s.paired()) << c->describeSlot(k);
    EXPECT_NEAR(s.gap, kGap0, kRoundoff);
    EXPECT_NEAR(s.frozen.xi[0], 0.0, kRoundoff) << "the midpoint of the segment (reference coordinate in [-1, 1])";
    EXPECT_EQ(s.masterElement, s.slaveNode == 10 ? 101 : 100);
  }
  // Rows in host DOF ids: n^p = (0, 1) on the slave's u_y, −½ n^p on each
  // master node's u_y; the master entries carry the master facet's subdomain.
  const auto rows = c->contactRows();
  double slaveSum = 0, masterSum = 0;
  for (const auto& e : rows) {
    EXPECT_EQ(e.dof % 2, 1) << "only u_y: the normal is vertical";
    const bool master = e.role == ddc::SurfaceContactRole::Master;
    (master ? masterSum : slaveSum) += e.coefficient;
    if (master) EXPECT_EQ(e.subdomain, 0);
  }
  double sums[2] = {slaveSum, masterSum}, total[2];
  Teuchos::reduceAll(*h.comm, Teuchos::REDUCE_SUM, 2, sums, total);
  EXPECT_NEAR(total[0], 2.0, kRoundoff) << "two slave rows with coefficient 1";
  EXPECT_NEAR(total[1], -2.0, kRoundoff) << "two master rows with −½ −½";

  // Push the slave surface through: both pairs activate (frozen gap < 0).
  ddc::Vector lambda(c->multiplierMap());
  auto pushed = state(h, map, 0.15);
  auto changed = c->updateActiveSet(*pushed, &lambda);
  EXPECT_EQ(changed.size(), 2u);
  for (const auto& s : c->slots()) {
    EXPECT_TRUE(s.active);
    EXPECT_NEAR(s.gap, kGap0 - 0.15, kRoundoff) << "the frozen gap, summed on the multiplier map";
  }
  // Tension releases them.
  lambda.putScalar(1.0);
  changed = c->updateActiveSet(*pushed, &lambda);
  EXPECT_EQ(changed.size(), 2u);
  for (const auto& s : c->slots()) EXPECT_FALSE(s.active);
}

TEST(ContactComponent, ANewtonIterationsActiveSetMovesOnlyTheEvaluatedSlotsValues) {
  // The slots are owned by the last rank and their master counterparts
  // evaluated on rank 0; on 3 ranks, rank 1 evaluates nothing. An update
  // without everySlot (a Newton iteration's) gives every rank the changed
  // states but the values only to the ranks that evaluate the slots; an
  // update with it (a host's) then gives every rank every value, from the
  // slots' owners.
  Host h;
  auto c = registered(h, true);
  auto map = h.map();
  c->setDofs(map, dofsOf(h));
  c->updatePairing(*state(h, map, 0.0), /*global=*/true, /*freeze=*/true);
  const bool evaluates = h.ownsMaster() || h.ownsSlave();
  ddc::Vector lambda(c->multiplierMap());
  auto pushed = state(h, map, 0.15);
  const auto bytes0 = c->valueBytesReceived();
  auto changed = c->updateActiveSet(*pushed, &lambda, /*everySlot=*/false);
  EXPECT_EQ(changed, (std::vector<int>{0, 1})) << "the changes of the owner's slots, on every rank";
  const long lean = c->valueBytesReceived()[0] - bytes0[0];
  for (const auto& s : c->slots()) {
    EXPECT_TRUE(s.active) << "the active set is the same on every rank";
    EXPECT_EQ(s.friction, ddc::FrictionState::Slip) << "a frictionless contact slips";
    EXPECT_NEAR(s.gap, evaluates ? kGap0 - 0.15 : kGap0, kRoundoff)
        << "the summed gap reaches the evaluating ranks only; elsewhere the pairing's stays";
  }
  // With everySlot: every value to every rank; nothing changes.
  changed = c->updateActiveSet(*pushed, &lambda, /*everySlot=*/true);
  EXPECT_TRUE(changed.empty());
  const long every = c->valueBytesReceived()[1] - bytes0[1];
  EXPECT_EQ(c->valueBytesReceived()[0], bytes0[0] + lean) << "counted apart";
  EXPECT_EQ(c->valueUpdates(), (std::array<long, 2>{1, 1}));
  for (const auto& s : c->slots()) EXPECT_NEAR(s.gap, kGap0 - 0.15, kRoundoff) << "every rank holds every value now";
  if (!evaluates) {
    EXPECT_EQ(every, 2 * ddc::ContactComponent::sharedSlotBytes())
        << "a bystander receives the values of both slots from their owner, nothing else";
    EXPECT_LT(lean, every) << "and in a Newton iteration only the other ranks' changed states";
  }
  if (h.comm->getSize() == 1) EXPECT_EQ(lean + every, 0) << "one rank receives nothing";
  // Tension releases both slots, on every rank.
  lambda.putScalar(1.0);
  changed = c->updateActiveSet(*pushed, &lambda, /*everySlot=*/false);
  EXPECT_EQ(changed, (std::vector<int>{0, 1}));
  for (const auto& s : c->slots()) EXPECT_FALSE(s.active);
}

TEST(ContactComponent, AStepsSumsAndItsOutputReadTheOwnersValues) {
  // After updates without everySlot only the evaluating ranks hold the
  // multipliers (on 3 ranks rank 1 keeps λ = 0): the summary's force is
  // still the same on every rank (summed on the owners), and the values
  // come to any rank that asks the owners for them.
  Host h;
  auto c = registered(h, true);
  auto map = h.map();
  c->setDofs(map, dofsOf(h));
  c->updatePairing(*state(h, map, 0.0), /*global=*/true, /*freeze=*/true);
  ddc::Vector lambda(c->multiplierMap());
  auto pushed = state(h, map, 0.15);
  c->updateActiveSet(*pushed, &lambda, /*everySlot=*/false);  // both penetrate: active
  lambda.putScalar(-1.0);
  c->updateActiveSet(*pushed, &lambda, /*everySlot=*/false);  // compression: stored where evaluated
  const bool evaluates = h.ownsMaster() || h.ownsSlave();
  for (const auto& s : c->slots()) EXPECT_EQ(s.state.multiplier, evaluates ? -1.0 : 0.0);
  const ddc::ContactSummary sum = c->reduceSummary();
  EXPECT_EQ(sum.active, 2);
  EXPECT_EQ(c->numActive(), 2);
  const Eigen::Vector3d n = c->slots()[0].frozen.normal;  // the frozen normal, replicated
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(sum.force[d], 2.0 * n[d], kRoundoff) << "Σ −λ n of both slots, every rank";

  // Every rank asks for slot 1 only, rank 0 for both.
  std::vector<ddc::ContactSlot> slots = c->slots();
  const std::vector<int> wanted = h.me == 0 ? std::vector<int>{0, 1} : std::vector<int>{1};
  c->shareSlotValues(slots, wanted);
  for (int k : {0, 1}) {
    const bool asked = std::count(wanted.begin(), wanted.end(), k) > 0;
    EXPECT_EQ(slots[k].state.multiplier, asked || evaluates ? -1.0 : 0.0) << "slot " << k;
    EXPECT_NEAR(slots[k].gap, asked || evaluates ? kGap0 - 0.15 : kGap0, kRoundoff) << "slot " << k;
    EXPECT_EQ(slots[k].normal, c->slots()[k].frozen.normal) << "slot " << k;
  }
  EXPECT_EQ(c->slots()[1].state.multiplier, evaluates ? -1.0 : 0.0) << "the component's own slots are not touched";
  // A wrong slot or list stops every rank.
  EXPECT_THROW(c->shareSlotValues(slots, h.me == 0 ? std::vector<int>{2} : std::vector<int>{}), std::invalid_argument);
  std::vector<ddc::ContactSlot> none;
  EXPECT_THROW(c->shareSlotValues(none, {}), std::invalid_argument);
  std::vector<ddc::ContactSlot> wrongHere = h.me == 0 ? none : slots;  // a wrong list on rank 0 only
  EXPECT_THROW(c->shareSlotValues(wrongHere, {}), std::invalid_argument) << "every rank, no rank waiting";
  EXPECT_THROW(c->frictionalWork(none), std::invalid_argument);
  EXPECT_EQ(c->frictionalWork(c->slots()), 0.0) << "no friction";
  // Once per run: every value on every rank.
  c->shareEverySlotsValues();
  for (const auto& s : c->slots()) EXPECT_EQ(s.state.multiplier, -1.0);
}

TEST(ContactComponent, AFullyPrescribedSlotThatPenetratesStopsEveryRank) {
  // Slave node 11 and its master facet (nodes 1, 2) fully prescribed: the
  // owner of its slot finds it, and every rank throws its message, in a
  // Newton iteration's update as in a step's end.
  for (const bool everySlot : {false, true}) {
    Host h;
    auto c = registered(h, true);
    auto map = h.map();
    auto dofs = dofsOf(h);
    for (auto& d : dofs)
      if (d.id == 1 || d.id == 2 || d.id == 11) d.prescribed = {{true, true, true}};
    c->setDofs(map, dofs);
    c->updatePairing(*state(h, map, 0.0), /*global=*/true, /*freeze=*/true);
    ddc::Vector lambda(c->multiplierMap());
    auto pushed = state(h, map, 0.15);
    ddc::test::expectThrowWith<InputError>([&] { c->updateActiveSet(*pushed, &lambda, everySlot); },
                                           {"slave node 11", "have all their displacements prescribed", "(gap -0.05"});
  }
}

TEST(ContactComponent, TheFrozenGeometryErrorOfAStepAgainstItsClosedForm) {
  // The step starts paired at u = 0 (n^p = (0, 1), xi^p = 0: the segment
  // midpoints). It ends with the slave surface moved by (s, -(kGap0 + d))
  // and master node 2 raised by delta: slave 10 is still over the flat
  // segment (1, 0), slave 11 over the tilted segment (2, 1). Both are
  // active with lambda = -1. The step-end pairing gives slave 10 the same
  // gap and normal (no error), slave 11 the gap and normal of the tilted
  // segment: gap work |g - g^p|, normal work |n - n^p| times the slip of
  // its contact point, in reference coordinates.
  Host h;
  auto c = registered(h, true);
  auto map = h.map();
  c->setDofs(map, dofsOf(h));
  c->updatePairing(*state(h, map, 0.0), true, true);
  const double s = 0.2, d = 0.01, delta = 0.1;
  auto u = state(h, map, kGap0 + d);
  for (int i = 3; i < 5; ++i)
    if (h.owns(i)) u->replaceGlobalValue(GO(2 * i), s);
  if (h.owns(2)) u->replaceGlobalValue(GO(2 * 2 + 1), delta);
  ddc::Vector lambda(c->multiplierMap());
  c->updateActiveSet(*u, &lambda);  // both penetrate: active
  lambda.putScalar(-1.0);
  c->updateActiveSet(*u, &lambda);  // compression: the multipliers are stored
  const std::vector<ddc::ContactSlot> converged = c->slots();
  for (const auto& sl : converged) ASSERT_TRUE(sl.active);
  c->updatePairing(*u, true, true);
  const ddc::FrozenGeometryError e = c->frozenGeometryError(converged);

  // Slave 11 at (1.5 + s, -d) against the segment from (1, 0) to (2, delta).
  const double L = std::sqrt(1 + delta * delta);
  const double gFrozen = -d - delta / 2;                 // n^p . (x_s - midpoint)
  const double g = (-delta * (0.5 + s) - d) / L;          // n . (x_s - (1, 0))
  const double f = ((0.5 + s) - d * delta) / (L * L);     // projection, fraction from node 1
  const double slip = std::abs(f - 0.5);                  // reference length 1
  const double rotation = std::hypot(-delta / L, 1 / L - 1);  // |n - n^p|
  EXPECT_NEAR(e.gapWork, std::abs(g - gFrozen), kRoundoff);
  EXPECT_NEAR(e.normalWork, rotation * slip, kRoundoff);
  EXPECT_GT(e.normalWork, 1e-3) << "the case does not test the normal term";
  EXPECT_NEAR(e.total(), e.gapWork + e.normalWork, 0.0);

  // Nothing moved in a step: no error.
  const std::vector<ddc::ContactSlot> again = c->slots();
  c->updatePairing(*u, true, true);
  const ddc::FrozenGeometryError none = c->frozenGeometryError(again);
  EXPECT_NEAR(none.gapWork, 0.0, kRoundoff);
  EXPECT_NEAR(none.normalWork, 0.0, kRoundoff);
  EXPECT_EQ(e.tangentWork, 0.0) << "no friction, no tangential term";
  EXPECT_THROW(c->frozenGeometryError({}), std::invalid_argument);
}

TEST(ContactComponent, TheFrozenGeometryErrorOfAFrictionalStepHasTheTangentialTerm) {
  // The step of the test above with a frictional pair: the tangent basis is
  // frozen with the normal, so slave 11's tangential force along the
  // frozen τ^p lies across the updated τ by |τ − τ^p| = |n − n^p| (2-D: τ
  // = (−n_y, n_x)) over the same slip; slave 10's basis does not turn.
  Host h;
  auto c = registered(h, true, [](std::vector<ddc::ContactNode>&, ddc::ContactPairSurfaces& p) {
    p.friction = 0.3;
    p.frictionStiffness = 10.0;
  });
  auto map = h.map();
  c->setDofs(map, dofsOf(h));
  c->updatePairing(*state(h, map, 0.0), true, true);
  const double s = 0.2, d = 0.01, delta = 0.1, lambdaT = 0.25;
  auto u = state(h, map, kGap0 + d);
  for (int i = 3; i < 5; ++i)
    if (h.owns(i)) u->replaceGlobalValue(GO(2 * i), s);
  if (h.owns(2)) u->replaceGlobalValue(GO(2 * 2 + 1), delta);
  ddc::Vector lambda(c->multiplierMap());
  c->updateActiveSet(*u, &lambda);
  std::vector<ddc::ContactSlot> converged = c->slots();
  for (auto& sl : converged) {
    ASSERT_TRUE(sl.active);
    ASSERT_EQ(c->numMultipliers(&sl - converged.data()), 2);
    sl.state.multiplier = -1.0;
    sl.tangential[0] = lambdaT;
  }
  c->updatePairing(*u, true, true);
  const ddc::FrozenGeometryError e = c->frozenGeometryError(converged);
  const double L = std::sqrt(1 + delta * delta);
  const double f = ((0.5 + s) - d * delta) / (L * L);
  const double slip = std::abs(f - 0.5);
  const double rotation = std::hypot(-delta / L, 1 / L - 1);
  EXPECT_NEAR(e.tangentWork, lambdaT * rotation * slip, kRoundoff);
  EXPECT_NEAR(e.normalWork, rotation * slip, kRoundoff) << "the normal term as without friction";
  EXPECT_NEAR(e.total(), e.gapWork + e.normalWork + e.tangentWork, 0.0);
}

TEST(ContactComponent, ConventionalContributionsUseHostDofs) {
  Host h;
  auto c = registered(h, false);
  auto map = h.map();
  c->setDofs(map, dofsOf(h));
  auto u = state(h, map, 0.15);
  c->updatePairing(*u, true, false);
  c->activateAllPaired();
  ddc::Vector lambda(c->multiplierMap());
  int evaluated = 0;
  c->assemble(*u, &lambda, ddc::kResidual, [&](const std::vector<GO>& dofs, ddc::ElementResult& r) {
    ++evaluated;
    ASSERT_EQ(dofs.size(), 7u) << "slave, two master nodes, multiplier";
    EXPECT_GE(dofs[0], 6) << "the slave node's host DOFs first";
    EXPECT_NEAR(r.residual[6], kGap0 - 0.15, kRoundoff) << "active: the multiplier row is the gap";
  });
  EXPECT_EQ(evaluated, h.ownsSlave() ? 2 : 0) << "each slot on the owner of its slave node";
}

TEST(ContactComponent, HostMultipliersAreReadFromTheHostVector) {
  // Multiplier DOFs in the host's map (a monolithic saddle-point host): the
  // host numbers them after its displacement DOFs.
  Host h;
  auto c = registered(h, true);
  std::vector<GO> gids;
  for (int i = 0; i < 5; ++i)
    if (h.owns(i)) gids.insert(gids.end(), {GO(2 * i), GO(2 * i + 1)});
  std::vector<GO> lm;
  if (h.ownsSlave()) lm = {10, 11};
  gids.insert(gids.end(), lm.begin(), lm.end());
  auto map = Teuchos::rcp(new ddc::Map(12, Teuchos::ArrayView<const GO>(gids), 0, h.comm));
  c->setDofs(map, dofsOf(h), lm);
  EXPECT_EQ(c->multiplierId(0), 10);
  auto u = Teuchos::rcp(new ddc::Vector(map));
  c->updatePairing(*u, true, true);
  c->activateAllPaired();
  if (h.ownsSlave()) u->replaceGlobalValue(GO(11), 2.0);  // slot 1 in tension
  const auto changed = c->updateActiveSet(*u);
  ASSERT_EQ(changed.size(), 1u);
  EXPECT_EQ(changed[0], 1);
  EXPECT_EQ(c->slots()[1].state.multiplier, 2.0);
}

TEST(ContactComponent, MultipliersMustComeFromSomewhere) {
  // Multipliers neither in the host's vector nor passed: a caller bug, not a
  // silent λ = 0 (both the conventional gather and the decomposed path).
  Host h;
  for (bool decomposed : {false, true}) {
    auto c = registered(h, decomposed);
    auto map = h.map();
    c->setDofs(map, dofsOf(h));
    auto u = state(h, map, 0.0);
    c->updatePairing(*u, true, true);
    EXPECT_THROW(c->updateActiveSet(*u), std::logic_error) << (decomposed ? "decomposed" : "conventional");
  }
}

// ---- registrations that do not match the host ------------------------------------

TEST(ContactComponent, DofIdsTheRegisteringRankDoesNotOwnAreRejectedOnEveryRank) {
  Host h;
  auto c = registered(h, true);
  auto map = h.map();
  auto dofs = dofsOf(h);
  // The slave owner claims a DOF id of the master surface (rank 0's) — or,
  // on one rank, an id outside the host's map.
  const GO foreign = h.comm->getSize() > 1 ? GO(0) : GO(99);
  if (h.ownsSlave()) dofs.back().dofs[1] = foreign;
  ddc::test::expectThrowWith<InputError>([&] { c->setDofs(map, dofs); },
                                         {"surface node 11", "DOF id " + std::to_string(foreign) + " for u_y",
                                          "does not own in the host's DOF map"});
}

TEST(ContactComponent, ANodeRegisteredByTwoRanksIsRejected) {
  Host h;
  if (h.comm->getSize() < 2) GTEST_SKIP() << "needs two ranks";
  ddc::test::expectThrowWith<InputError>(
      [&] {
        registered(h, true, [&](std::vector<ddc::ContactNode>& nodes, ddc::ContactPairSurfaces&) {
          if (h.ownsSlave()) nodes.push_back({0, Eigen::Vector2d(0, 0)});
        });
      },
      {"surface node 0 is registered by ranks 0 and", "registered once, by its owner"});
}

TEST(ContactComponent, AFacetOnAnUnregisteredNodeIsRejected) {
  Host h;
  ddc::test::expectThrowWith<InputError>(
      [&] {
        registered(h, true, [&](std::vector<ddc::ContactNode>&, ddc::ContactPairSurfaces& pair) {
          if (h.ownsMaster()) pair.masterFacets.push_back({2, {{0, 7}}, 102, 0, 1.0});
        });
      },
      {"contact pair 'P'", "master node 7 is not a registered surface node"});
}

TEST(ContactComponent, MultipliersOfSlotsTheRankDoesNotOwnAreRejected) {
  Host h;
  auto c = registered(h, true);
  auto map = h.map();
  // One multiplier id per owned slot is required; rank 0 owns none.
  std::vector<GO> lm = {0};
  ddc::test::expectThrowWith<InputError>([&] { c->setDofs(map, dofsOf(h), h.ownsMaster() ? lm : std::vector<GO>{}); },
                                         {"multiplier"});
}

// ---- misuse a host meets first ------------------------------------------------

TEST(ContactComponent, RowsAndContributionsBeforeTheFirstPairingAreAnError) {
  // Nothing is paired before updatePairing(): the rows were silently empty
  // and the contributions only the released slots' lambda^2/2.
  Host h;
  auto c = registered(h, true);
  auto map = h.map();
  c->setDofs(map, dofsOf(h));
  auto u = state(h, map, 0.0);
  ddc::test::expectThrowWith<std::logic_error>([&] { c->contactRows(); },
                                               {"contactRows", "no pairing yet", "updatePairing"});
  ddc::test::expectThrowWith<std::logic_error>(
      [&] { c->assemble(*u, nullptr, ddc::kResidual, [](const std::vector<GO>&, ddc::ElementResult&) {}); },
      {"assemble", "no pairing yet"});
  c->updatePairing(*u, true, true);
  EXPECT_NO_THROW(c->contactRows());
}

TEST(ContactComponent, AMultiplierIdThatIsAlsoADisplacementDofIsRejected) {
  // Host multiplier ids must be DOF ids of their own: the slave owner gives
  // u_y of node 10 (id 7), or the same id twice.
  Host h;
  for (const std::vector<GO>& given : {std::vector<GO>{10, 7}, std::vector<GO>{10, 10}}) {
    auto c = registered(h, true);
    std::vector<GO> gids;
    for (int i = 0; i < 5; ++i)
      if (h.owns(i)) gids.insert(gids.end(), {GO(2 * i), GO(2 * i + 1)});
    std::vector<GO> lm;
    if (h.ownsSlave()) lm = given;
    if (h.ownsSlave()) gids.push_back(10);
    auto map = Teuchos::rcp(new ddc::Map(11, Teuchos::ArrayView<const GO>(gids), 0, h.comm));
    const std::string other = given[1] == 7 ? "is also the u_y DOF of surface node 10" : "is also the multiplier of";
    ddc::test::expectThrowWith<InputError>([&] { c->setDofs(map, dofsOf(h), lm); },
                                           {"multiplier DOF id " + std::to_string(given[1]), "slave node 11", other,
                                            "a DOF id of its own"});
  }
}

TEST(ContactComponent, AMasterSurfaceRegisteredWrongSideOutIsReported) {
  // Both master facets reversed (consistent with each other, so commit()
  // accepts them): the master body seems above its surface, its normals
  // point away from the slave surface, and nothing pairs.
  Host h;
  auto c = registered(h, true, [&](std::vector<ddc::ContactNode>&, ddc::ContactPairSurfaces& pair) {
    for (auto& f : pair.masterFacets) std::swap(f.nodes[0], f.nodes[1]);
  });
  auto map = h.map();
  c->setDofs(map, dofsOf(h));
  auto u = state(h, map, 0.0);
  c->updatePairing(*u, true, true);
  const auto warnings = c->takeWarnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr("contact pair 'P': none of its 2 slave nodes pairs, and 2 of them lie within "
                                     "the search radius of master facets that do not face them"));
  EXPECT_THAT(warnings[0], HasSubstr("the master side set 'lower/top' faces away from or across the slave side set "
                                     "'upper/bottom'"));
  EXPECT_TRUE(c->takeWarnings().empty());  // once
  ASSERT_EQ(c->neverPairedPairs().size(), 1u);
  EXPECT_THAT(c->neverPairedPairs()[0], HasSubstr("contact pair 'P'"));
  // The right way out pairs both and warns about nothing.
  auto good = registered(h, true);
  good->setDofs(map, dofsOf(h));
  good->updatePairing(*u, true, true);
  EXPECT_TRUE(good->takeWarnings().empty());
  EXPECT_TRUE(good->neverPairedPairs().empty());
}

// ---- 3-D: Quad4 facets --------------------------------------------------------
// The host in 3-D: a master surface z = 0 of two Quad4 facets (nodes 0-5 at
// x = 0, 1, 2, y = 0, 2; the master body below, corners counter-clockwise
// seen from +z) and one slave Quad4 facet at z = kGap0 above it (nodes 10-13
// over (0.5..1.5)^2, counter-clockwise seen from below). Host DOFs: node n's
// u_x, u_y, u_z are 3·i, 3·i + 1, 3·i + 2 with i its position in kNodes3.
const int kNodes3[10] = {0, 1, 2, 3, 4, 5, 10, 11, 12, 13};
const double kX3[10][3] = {{0, 0, 0},   {1, 0, 0},     {2, 0, 0},         {0, 2, 0},         {1, 2, 0},
                           {2, 2, 0},   {0.5, 0.5, kGap0}, {1.5, 0.5, kGap0}, {1.5, 1.5, kGap0}, {0.5, 1.5, kGap0}};

struct Host3 : Host {
  /// The rank that registers the second master facet and its nodes 2 and 5
  /// (-1: the master rank, with the first).
  int rightFacetRank = -1;
  bool ownsRight() const { return rightFacetRank < 0 ? ownsMaster() : me == rightFacetRank; }
  bool owns3(int i) const { return i >= 6 ? ownsSlave() : (i == 2 || i == 5) ? ownsRight() : ownsMaster(); }
  Teuchos::RCP<const ddc::Map> map3() const {
    std::vector<GO> gids;
    for (int i = 0; i < 10; ++i)
      if (owns3(i)) gids.insert(gids.end(), {GO(3 * i), GO(3 * i + 1), GO(3 * i + 2)});
    return Teuchos::rcp(new ddc::Map(30, Teuchos::ArrayView<const GO>(gids), 0, comm));
  }
};

std::unique_ptr<ContactComponent> registered3(const Host3& h,
                                              const std::function<void(ddc::ContactPairSurfaces&)>& tweak = {},
                                              ContactComponent::SurfaceElementSource source =
                                                  ddc::makeSurfaceContactElement) {
  ddc::ContactComponentOptions o;
  o.decomposed = true;
  o.searchRadius = 0.5;
  o.penetrationTolerance = 1e-12;
  auto c = std::make_unique<ContactComponent>(h.comm, o, std::move(source));
  std::vector<ddc::ContactNode> nodes;
  for (int i = 0; i < 10; ++i)
    if (h.owns3(i)) nodes.push_back({kNodes3[i], Eigen::Vector3d(kX3[i][0], kX3[i][1], kX3[i][2])});
  ddc::ContactPairSurfaces pair;
  pair.name = "P3";
  pair.slaveFacetType = pair.masterFacetType = ddc::CellType::Quad4;
  if (h.ownsMaster()) pair.masterFacets.push_back({0, {0, 1, 4, 3}, 100, 0, 1.0});
  if (h.ownsRight()) pair.masterFacets.push_back({1, {1, 2, 5, 4}, 101, h.rightFacetRank < 0 ? 0 : 1, 1.0});
  if (h.ownsSlave()) {
    pair.slaveFacets.push_back({0, {10, 13, 12, 11}, 200, 1, 0.0});
    pair.slaveNodes = {10, 11, 12, 13};
  }
  if (tweak) tweak(pair);
  c->registerNodes(nodes);
  c->registerPair(pair);
  c->commit();
  return c;
}

TEST(ContactComponent3D, DecomposedRowsGapsAndActiveSetOnQuad4Facets) {
  Host3 h;
  auto c = registered3(h);
  EXPECT_EQ(c->dim(), 3);
  auto map = h.map3();
  std::vector<ddc::ContactNodeDofs> dofs;
  for (int i = 0; i < 10; ++i)
    if (h.owns3(i)) dofs.push_back({kNodes3[i], {{GO(3 * i), GO(3 * i + 1), GO(3 * i + 2)}}, {{false, false, false}}});
  c->setDofs(map, dofs);
  ASSERT_EQ(c->slots().size(), 4u);
  ddc::Vector u(map);
  c->updatePairing(u, /*global=*/true, /*freeze=*/true);
  for (int k = 0; k < 4; ++k) {
    const auto& s = c->slots()[k];
    ASSERT_TRUE(s.paired()) << c->describeSlot(k);
    EXPECT_EQ(s.numMaster, 4);
    EXPECT_NEAR(s.gap, kGap0, kRoundoff);
    EXPECT_NEAR((s.frozen.normal - Eigen::Vector3d(0, 0, 1)).norm(), 0.0, kRoundoff);
    // x < 1: the first facet; x > 1: the second.
    EXPECT_EQ(s.masterElement, c->referencePosition(s.slaveNode).x() < 1 ? 100 : 101);
    // The tributary area of a corner of the 1 x 1 slave facet: a quarter.
    EXPECT_NEAR(s.tributaryLength, 0.25, kRoundoff);
  }
  // Rows: n^p = (0, 0, 1) on the slave's u_z, −N_i(ξ^p) on the master nodes' u_z.
  double sums[2] = {0, 0}, total[2];
  for (const auto& e : c->contactRows()) {
    EXPECT_EQ(e.dof % 3, 2) << "only u_z: the normal is vertical";
    sums[e.role == ddc::SurfaceContactRole::Master] += e.coefficient;
  }
  Teuchos::reduceAll(*h.comm, Teuchos::REDUCE_SUM, 2, sums, total);
  EXPECT_NEAR(total[0], 4.0, kRoundoff) << "four slave rows with coefficient 1";
  EXPECT_NEAR(total[1], -4.0, kRoundoff) << "four master rows whose shape functions sum to 1";
  // Push the slave facet through the master surface: all four activate.
  ddc::Vector lambda(c->multiplierMap());
  for (int i = 6; i < 10; ++i)
    if (h.owns3(i)) u.replaceGlobalValue(GO(3 * i + 2), -0.15);
  EXPECT_EQ(c->updateActiveSet(u, &lambda).size(), 4u);
  for (const auto& s : c->slots()) EXPECT_NEAR(s.gap, kGap0 - 0.15, kRoundoff);
}

TEST(ContactComponent3D, ANewMasterRankTakesTheOwnersFrozenTangentBasis) {
  // Facet 0 (x in 0..1) registered by rank 0, facet 1 (x in 1..2) by rank
  // 1, the slave facet by the last rank; a frictional pair. The bodies
  // turn rigidly about y, so the owner rotates the slots' tangent basis
  // (tangentBasis(): least rotation from the last step's) while rank 1,
  // which evaluates nothing of them, keeps the first. Then they turn about
  // x and the slave slides onto facet 1: its new master rank must freeze
  // the owner's basis, not rotate its stale one.
  Host3 h;
  h.rightFacetRank = std::min(1, h.last);
  auto c = registered3(h, [](ddc::ContactPairSurfaces& p) {
    p.friction = 0.3;
    p.frictionStiffness = 10.0;
  });
  auto map = h.map3();
  std::vector<ddc::ContactNodeDofs> dofs;
  for (int i = 0; i < 10; ++i)
    if (h.owns3(i)) dofs.push_back({kNodes3[i], {{GO(3 * i), GO(3 * i + 1), GO(3 * i + 2)}}, {{false, false, false}}});
  c->setDofs(map, dofs);
  // u = R X + shift − X, the slave nodes shifted by `slide` along R e_x, the
  // slave's reference corners moved to x in 0.1..0.4 (on facet 0).
  auto moved = [&](const Eigen::Matrix3d& R, double slide) {
    ddc::Vector u(map);
    for (int i = 0; i < 10; ++i) {
      if (!h.owns3(i)) continue;
      const Eigen::Vector3d X(kX3[i][0], kX3[i][1], kX3[i][2]);
      Eigen::Vector3d x = X;
      if (i >= 6) x.x() = 0.1 + 0.3 * (X.x() - 0.5) + slide, x.y() = 0.1 + 0.3 * (X.y() - 0.5);
      const Eigen::Vector3d d = R * x - X;
      for (int k = 0; k < 3; ++k) u.replaceGlobalValue(GO(3 * i + k), d[k]);
    }
    return u;
  };
  const Eigen::Matrix3d Ry = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d Rxy = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()).toRotationMatrix() * Ry;
  c->updatePairing(moved(Eigen::Matrix3d::Identity(), 0.0), true, true);
  const Eigen::Vector3d first = c->slots()[0].frozen.tangent[0];  // every rank: the first pairing
  c->updatePairing(moved(Ry, 0.0), true, true);
  const bool bystander = h.comm->getSize() == 3 && h.me == 1;
  for (const auto& s : c->slots()) {
    ASSERT_EQ(s.masterElement, 100);
    if (bystander) EXPECT_EQ(s.frozen.tangent[0], first) << "an unchanged pairing goes only where it is evaluated";
  }
  c->updatePairing(moved(Rxy, 1.0), true, true);
  // The owner's basis against the one of every rank that evaluates the slots.
  std::vector<double> mine(12, 0.0), owners(12);
  for (int k = 0; k < 4; ++k) {
    const auto& s = c->slots()[k];
    ASSERT_EQ(s.masterElement, 101) << c->describeSlot(k);
    if (h.ownsSlave())
      for (int d = 0; d < 3; ++d) mine[size_t(3 * k + d)] = s.frozen.tangent[0][d];
  }
  Teuchos::reduceAll(*h.comm, Teuchos::REDUCE_SUM, 12, mine.data(), owners.data());
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d owner(owners[size_t(3 * k)], owners[size_t(3 * k + 1)], owners[size_t(3 * k + 2)]);
    const auto& s = c->slots()[k];
    EXPECT_NEAR((s.frozen.normal - Rxy.col(2)).norm(), 0.0, kRoundoff);
    EXPECT_GT((ddc::tangentBasis(3, s.frozen.normal, first)[0] - owner).norm(), 1e-3)
        << "a basis rotated from the first pairing's differs: the case tests the owner's";
    if (h.ownsRight() || h.ownsSlave())
      EXPECT_NEAR((s.frozen.tangent[0] - owner).norm(), 0.0, kRoundoff) << "slot " << k << " on rank " << h.me;
  }
}

TEST(ContactComponent3D, TheHostsElementSourceGivesTheElements) {
  // The component evaluates every facet type through the source it is
  // given: a host's source (here counting, then delegating to the built-in
  // elements) yields the same rows as the default.
  Host3 h;
  auto map = h.map3();
  std::vector<ddc::ContactNodeDofs> dofs;
  for (int i = 0; i < 10; ++i)
    if (h.owns3(i)) dofs.push_back({kNodes3[i], {{GO(3 * i), GO(3 * i + 1), GO(3 * i + 2)}}, {{false, false, false}}});
  std::vector<std::vector<ddc::ContactRowEntry>> rows;
  int asked = 0;
  auto counting = [&](ddc::SurfaceContactRole role, ddc::CellType facet) {
    ++asked;
    return ddc::makeSurfaceContactElement(role, facet);
  };
  for (bool host : {false, true}) {
    auto c = host ? registered3(h, {}, counting) : registered3(h);
    c->setDofs(map, dofs);
    ddc::Vector u(map);
    c->updatePairing(u, true, true);
    rows.push_back(c->contactRows());
  }
  EXPECT_EQ(asked, 2) << "the slave and master counterparts on Quad4, once each";
  ASSERT_EQ(rows[0].size(), rows[1].size());
  for (size_t i = 0; i < rows[0].size(); ++i) {
    EXPECT_EQ(rows[0][i].dof, rows[1][i].dof);
    EXPECT_EQ(rows[0][i].coefficient, rows[1][i].coefficient);
  }
}

TEST(ContactComponent, OptionsOutOfRangeAreRefused) {
  Host h;
  ddc::ContactComponentOptions o;  // searchRadius 0: no pair could ever form
  ddc::test::expectThrowWith<std::invalid_argument>([&] { ContactComponent c(h.comm, o); },
                                                    {"options.searchRadius must be > 0 and finite", "got 0"});
  o.searchRadius = 0.5;
  o.penetrationTolerance = -1.0;
  ddc::test::expectThrowWith<std::invalid_argument>([&] { ContactComponent c(h.comm, o); },
                                                    {"options.penetrationTolerance must be >= 0"});
}

TEST(ContactComponent, ASourceWithoutTheElementsOfAPairIsRefusedAtCommit) {
  // A Line2 pair takes the one facet path: the source must give its
  // counterparts, and commit() says which one it did not.
  Host h;
  ddc::ContactComponentOptions o;
  o.decomposed = true;
  o.searchRadius = 0.5;
  ContactComponent c(h.comm, o, [](ddc::SurfaceContactRole, ddc::CellType) {
    return std::shared_ptr<const ddc::SurfaceContactElement>();
  });
  std::vector<ddc::ContactNode> nodes;
  for (int i = 0; i < 5; ++i)
    if (h.owns(i)) nodes.push_back({kNodes[i], Eigen::Vector2d(kX[i][0], kX[i][1])});
  ddc::ContactPairSurfaces pair;
  pair.name = "P";
  if (h.ownsMaster()) pair.masterFacets.push_back({0, {{2, 1}}, 100, 0, 1.0});
  if (h.ownsSlave()) pair.slaveFacets.push_back({0, {{10, 11}}, 200, 1, 0.0}), pair.slaveNodes = {10, 11};
  c.registerNodes(nodes);
  c.registerPair(pair);
  ddc::test::expectThrowWith<std::invalid_argument>([&] { c.commit(); },
                                                    {"gave no 'Decomposed NTS Slave Line2' element"});
}

TEST(ContactComponent3D, AFacetWithAnInwardNormalIsRejected) {
  Host3 h;
  ddc::test::expectThrowWith<InputError>(
      [&] {
        registered3(h, [&](ddc::ContactPairSurfaces& pair) {
          if (h.ownsMaster()) pair.masterFacets[1].nodes = {1, 4, 5, 2};  // clockwise seen from +z
        });
      },
      {"contact pair 'P3'", "master surface is not consistently oriented", "facets 0 and 1",
       "inward normal"});
}

TEST(ContactComponent3D, SurfacesOfDifferentDimensionsAreRejected) {
  Host3 h;
  ddc::test::expectThrowWith<InputError>(
      [&] {
        registered3(h, [&](ddc::ContactPairSurfaces& pair) { pair.slaveFacetType = ddc::CellType::Line2; });
      },
      {"contact pair 'P3'", "Line2 facets are 2-D", "Quad4 master facets", "one dimension"});
}

TEST(ContactComponent3D, AFacetWithTheWrongNumberOfNodesIsRejectedOnEveryRank) {
  Host3 h;
  ddc::test::expectThrowWith<InputError>(
      [&] {
        registered3(h, [&](ddc::ContactPairSurfaces& pair) {
          if (h.ownsMaster()) pair.masterFacets[0].nodes.pop_back();
        });
      },
      {"contact pair 'P3'", "master facet 0 has 3 nodes; a Quad4 facet has 4"});
}

}  // namespace
