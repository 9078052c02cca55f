// The rigid-motion check (packages/model/src/DDC_RigidMotionCheck.hpp):
// which rigid motions of the bodies prescribed displacements and contact
// rows leave free, and how they are named; the two parts of a contact row
// may come from two ranks and are summed before they restrain anything.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Teuchos_DefaultComm.hpp>

#include "DDC_MeshGenerators.hpp"
#include "DDC_RigidMotionCheck.hpp"

using ::testing::HasSubstr;
using PL = Teuchos::ParameterList;

namespace {

/// Unit cubes "A" (0 <= y <= 1) and "B" (1 <= y <= 2), 2 x 2 x 2 Hex8 each.
ddc::Mesh twoCubes() {
  ddc::Mesh m;
  for (const char* name : {"A", "B"}) {
    PL box;
    box.set("Elements X", 2);
    box.set("Elements Y", 2);
    box.set("Elements Z", 2);
    if (name[0] == 'B') box.set("Origin Y", 1.0);
    ddc::generateBox(m, name, ddc::CellType::Hex8, box, std::string("Mesh/Bodies/") + name + "/Box");
  }
  return m;
}

void prescribe(ddc::RigidMotionCheck& check, const ddc::Mesh& m, const std::string& set, const std::string& comps) {
  for (int n : m.nodeSet(set))
    for (char c : comps) check.addPrescribed(n, c - 'x', m.coord(n));
}

const Teuchos::Comm<int>& comm() { return *Teuchos::DefaultComm<int>::getComm(); }

}  // namespace

TEST(RigidMotionCheck, ThreeNodesHeldInEveryDirectionLeaveNothingFree) {
  const ddc::Mesh m = twoCubes();
  ddc::RigidMotionCheck check(m, 0);
  // Body A: three corners of its bottom, not on one line; body B: its top face.
  for (const char* set : {"A/bottom left back", "A/bottom right back", "A/bottom left front"})
    prescribe(check, m, set, "xyz");
  prescribe(check, m, "B/top", "xyz");
  EXPECT_EQ(check.freeBasis(comm()).cols(), 0);
  EXPECT_EQ(check.freeMotions(comm()), "");
}

TEST(RigidMotionCheck, ABodyHeldInOneDirectionSlidesAndSpinsAndIsNamed) {
  const ddc::Mesh m = twoCubes();
  ddc::RigidMotionCheck check(m, 0);
  prescribe(check, m, "A/bottom", "xyz");
  prescribe(check, m, "B/top", "y");  // y on a face: x, z and the spin about y stay free
  EXPECT_EQ(check.freeBasis(comm()).cols(), 3);
  const std::string text = check.freeMotions(comm());
  EXPECT_EQ(text,
            "body 'B' translation along x; body 'B' translation along z; "
            "body 'B' rotation about the y axis through (0.5, 1.5, 0.5)");
}

TEST(RigidMotionCheck, APinnedBodyRotatesAboutThePin) {
  const ddc::Mesh m = twoCubes();
  ddc::RigidMotionCheck check(m, 0);
  prescribe(check, m, "A/bottom", "xyz");
  // B held in every direction at two nodes on the line x = 0, z = 0: the
  // rotation about that line (the y axis through the origin) is free.
  prescribe(check, m, "B/top left back", "xyz");
  prescribe(check, m, "B/bottom left back", "xyz");
  EXPECT_EQ(check.freeBasis(comm()).cols(), 1);
  EXPECT_EQ(check.freeMotions(comm()), "body 'B' rotation about the y axis through (0, 1.5, 0)");
}

TEST(RigidMotionCheck, ContactRowsRestrainOnlyAlongTheirNormalAndTheirPartsAreSummedOverRanks) {
  const ddc::Mesh m = twoCubes();
  const auto& c = comm();
  // Each body held in x and z on its bottom and top faces (on one face
  // alone the rotations about axes in that face would stay free: they move
  // its nodes along y only): each is free to move along y alone. Contact rows g = y_B - y_A at the nine node
  // pairs of the interface y = 1 tie the two: only the joint translation
  // along y stays free. The slave part (B) is added on the first rank, the
  // master part (A) on the last: added up separately, they would hold each
  // body on its own.
  const auto top = m.nodeSet("A/top"), bottom = m.nodeSet("B/bottom");
  ASSERT_EQ(top.size(), bottom.size());
  std::vector<int> below(top.size(), -1);  // the B node at the same x, z as each A node of the interface
  for (size_t k = 0; k < top.size(); ++k)
    for (int n : bottom)
      if (m.coord(n)[0] == m.coord(top[k])[0] && m.coord(n)[2] == m.coord(top[k])[2]) below[k] = n;
  ASSERT_THAT(below, ::testing::Each(::testing::Ge(0)));
  auto build = [&](bool withRows) {
    ddc::RigidMotionCheck check(m, static_cast<int>(top.size()));
    if (c.getRank() == 0) {
      for (const char* set : {"A/bottom", "A/top", "B/bottom", "B/top"}) prescribe(check, m, set, "xz");
    }
    if (!withRows) return check;
    for (size_t k = 0; k < top.size(); ++k) {
      const int master = top[k], slave = below[k];
      if (c.getRank() == 0) check.addRowEntry(static_cast<int>(k), slave, 1, m.coord(slave), 1.0);
      if (c.getRank() == c.getSize() - 1) check.addRowEntry(static_cast<int>(k), master, 1, m.coord(master), -1.0);
    }
    return check;
  };
  EXPECT_EQ(build(false).freeMotions(c), "body 'A' translation along y; body 'B' translation along y");
  EXPECT_EQ(build(true).freeMotions(c), "body 'A' translation along y together with body 'B' translation along y");
}

TEST(RigidMotionCheck, TwoDimensionalBodyOnRollersAlongOneLineRotatesAboutTheCorner) {
  ddc::Mesh m;
  PL rect;
  rect.set("Elements X", 3);
  rect.set("Elements Y", 2);
  ddc::generateRectangle(m, "Block", ddc::CellType::Quad4, rect, "Mesh/Bodies/Block/Rectangle");
  ddc::RigidMotionCheck check(m, 0);
  prescribe(check, m, "Block/bottom", "x");
  prescribe(check, m, "Block/left", "y");
  EXPECT_EQ(check.freeMotions(comm()), "body 'Block' rotation about the point (0, 0)");
  prescribe(check, m, "Block/right", "y");
  EXPECT_EQ(check.freeMotions(comm()), "");
}
