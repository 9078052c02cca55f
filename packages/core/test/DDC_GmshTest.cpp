// Gmsh MSH 4.1 reader: the small files in data/ and variants of them written
// to a temporary directory, one per unsupported or malformed case.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

#include "DDC_CoreTestUtils.hpp"
#include "DDC_Error.hpp"
#include "DDC_Gmsh.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestTolerances.hpp"

using ddc::CellType;
using ddc::InputError;
using ddc::Mesh;
using ::testing::HasSubstr;

namespace {

using ddc::test::inputErrorOf;

const std::string kData = std::string(DDC_SOURCE_DIR) + "/packages/core/test/data";

std::string slurp(const std::string& file) {
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Write `content` to a per-rank temporary file and return its path.
std::string writeTemp(const std::string& name, const std::string& content) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const std::string file = ::testing::TempDir() + "ddc_gmsh_" + std::to_string(rank) + "_" + name;
  std::ofstream(file) << content;
  return file;
}

/// `text` with the first occurrence of `from` replaced by `to` (must exist).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << "test bug: '" << from << "' not in the file";
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

std::string readError(const std::string& file, CellType t = CellType::Quad4, const std::string& surface = "") {
  return inputErrorOf([&] {
    Mesh m;
    ddc::readGmshFile(m, "Body", t, file, surface);
  });
}

/// Side-set segments point away from the body: for these convex bodies the
/// normal points from the body centroid towards the segment.
void expectOutward(const Mesh& m, int body, const std::string& set) {
  const auto c = ddc::test::bodyCentroid(m, body);
  for (const auto& s : m.sideSet(set)) {
    const auto n = ddc::test::segmentNormal(m, s);
    const auto mid = ddc::test::segmentMidpoint(m, s);
    EXPECT_GT(n[0] * (mid[0] - c[0]) + n[1] * (mid[1] - c[1]), 0.0) << set;
  }
}

}  // namespace

TEST(Gmsh, ReadsQuad4RectangleWithSets) {
  Mesh m;
  const int b = ddc::readGmshFile(m, "Block", CellType::Quad4, kData + "/rect2x1.msh");
  EXPECT_EQ(b, 0);
  EXPECT_NO_THROW(m.check());
  EXPECT_EQ(m.numNodes(), 6);
  EXPECT_EQ(m.numElements(), 2);
  // Compact numbering in tag order: tag 10 -> 0, ..., 60 -> 5.
  EXPECT_EQ(m.coord(0), (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_EQ(m.coord(5), (std::array<double, 3>{2.0, 1.0, 0.0}));
  // Element 5 is clockwise in the file and must have been reordered.
  double area = 0;
  for (int e = 0; e < 2; ++e) {
    double minDet;
    area += ddc::test::elementArea(m, e, &minDet);
    EXPECT_GT(minDet, 0.0) << "element " << e;
  }
  EXPECT_NEAR(area, 2.0, ddc::test::kRoundoff);
  ASSERT_TRUE(m.hasSideSet("Block/left"));
  ASSERT_TRUE(m.hasSideSet("Block/right"));
  EXPECT_EQ(m.sideSet("Block/left").size(), 1u);
  EXPECT_EQ(m.sideSet("Block/right").size(), 1u);
  EXPECT_EQ(m.nodeSet("Block/left").size(), 2u);
  // The "right" line runs top to bottom in the file; the segment follows the body.
  const auto& r = m.sideSet("Block/right")[0];
  EXPECT_EQ(m.coord(r.nodes[0]), (std::array<double, 3>{2.0, 0.0, 0.0}));
  EXPECT_EQ(m.coord(r.nodes[1]), (std::array<double, 3>{2.0, 1.0, 0.0}));
  expectOutward(m, b, "Block/left");
  expectOutward(m, b, "Block/right");
  // Physical point and physical surface -> node sets.
  EXPECT_EQ(m.nodeSet("Block/origin"), (std::vector<int>{0}));
  EXPECT_EQ(m.nodeSet("Block/block").size(), 6u);
  EXPECT_FALSE(m.hasSideSet("Block/origin"));
}

TEST(Gmsh, ReadsQuad9WithParametricNodesAndThreeNodeLines) {
  Mesh m;
  ddc::readGmshFile(m, "Plate", CellType::Quad9, kData + "/quad9.msh");
  EXPECT_NO_THROW(m.check());
  EXPECT_EQ(m.numNodes(), 9);
  ASSERT_EQ(m.numElements(), 1);
  double minDet;
  EXPECT_NEAR(ddc::test::elementArea(m, 0, &minDet), 4.0, ddc::test::kRoundoff);
  EXPECT_GT(minDet, 0.0);
  const auto& segs = m.sideSet("Plate/bottom");
  ASSERT_EQ(segs.size(), 1u);
  ASSERT_EQ(segs[0].numNodes, 3);
  EXPECT_EQ(m.coord(segs[0].nodes[0]), (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_EQ(m.coord(segs[0].nodes[1]), (std::array<double, 3>{2.0, 0.0, 0.0}));
  EXPECT_EQ(m.coord(segs[0].nodes[2]), (std::array<double, 3>{1.0, 0.0, 0.0}));
  expectOutward(m, 0, "Plate/bottom");
  EXPECT_EQ(m.nodeSet("Plate/plate").size(), 9u);
}

TEST(Gmsh, PhysicalSurfaceSelectsOneBody) {
  Mesh m;
  const std::string f = kData + "/two_surfaces.msh";
  const int a = ddc::readGmshFile(m, "A", CellType::Quad4, f, "block");
  const int b = ddc::readGmshFile(m, "B", CellType::Quad4, f, "pad");
  EXPECT_NO_THROW(m.check());
  EXPECT_EQ(m.body(a).numElements, 1);
  EXPECT_EQ(m.body(b).numElements, 1);
  EXPECT_EQ(m.body(a).numNodes, 4);
  EXPECT_EQ(m.body(b).firstNode, 4);
  EXPECT_TRUE(m.hasSideSet("A/left"));
  EXPECT_FALSE(m.hasSideSet("A/right"));  // a curve of the other body
  EXPECT_TRUE(m.hasSideSet("B/right"));
  EXPECT_FALSE(m.hasSideSet("B/left"));
  // The shared curve is on the boundary of each body separately.
  for (const char* s : {"A/left", "A/interface", "B/right", "B/interface"})
    expectOutward(m, std::string(s)[0] == 'A' ? a : b, s);
  EXPECT_EQ(m.coord(m.sideSet("A/interface")[0].nodes[0]), (std::array<double, 3>{1.0, 0.0, 0.0}));
  EXPECT_EQ(m.coord(m.sideSet("B/interface")[0].nodes[0]), (std::array<double, 3>{1.0, 1.0, 0.0}));
  EXPECT_FALSE(m.hasNodeSet("A/pad"));
  EXPECT_EQ(m.nodeSet("B/pad").size(), 4u);
  // Without a selection the shared curve is interior: rejected.
  EXPECT_THAT(readError(f), HasSubstr("physical curve 'interface' lies inside the body"));
  EXPECT_THAT(readError(f, CellType::Quad4, "Pad"), HasSubstr("no physical surface named 'Pad'"));
  EXPECT_THAT(readError(f, CellType::Quad4, "Pad"), HasSubstr("'block', 'pad'"));
}

TEST(Gmsh, ReadGmshBodyResolvesRelativePathsAndValidates) {
  Mesh m;
  Teuchos::ParameterList p;
  p.set("File", std::string("rect2x1.msh"));
  EXPECT_EQ(ddc::readGmshBody(m, "Block", CellType::Quad4, p, "Mesh/Bodies/Block/Gmsh", kData), 0);
  EXPECT_EQ(p.get<std::string>("Physical Surface"), "");
  p.set("File", kData + "/rect2x1.msh");  // absolute: base directory ignored
  EXPECT_EQ(ddc::readGmshBody(m, "Block2", CellType::Quad4, p, "G", "/nonexistent"), 1);

  Teuchos::ParameterList q;
  EXPECT_THAT(inputErrorOf([&] { ddc::readGmshBody(m, "C", CellType::Quad4, q, "Mesh/Bodies/C/Gmsh", kData); }),
              HasSubstr("parameter 'Mesh/Bodies/C/Gmsh/File' is required"));
  Teuchos::ParameterList r;
  r.set("File", std::string("rect2x1.msh"));
  r.set("Physical surface", std::string("block"));
  EXPECT_THAT(inputErrorOf([&] { ddc::readGmshBody(m, "C", CellType::Quad4, r, "Mesh/Bodies/C/Gmsh", kData); }),
              HasSubstr("unknown parameter 'Mesh/Bodies/C/Gmsh/Physical surface'"));
  Teuchos::ParameterList s;
  s.set("File", std::string("missing.msh"));
  const std::string e = inputErrorOf([&] { ddc::readGmshBody(m, "C", CellType::Quad4, s, "Mesh/Bodies/C/Gmsh", kData); });
  EXPECT_THAT(e, HasSubstr("Mesh/Bodies/C/Gmsh/File"));
  EXPECT_THAT(e, HasSubstr("cannot open Gmsh file '" + kData + "/missing.msh'"));
  // Failed reads left the mesh unchanged.
  EXPECT_EQ(m.numBodies(), 2);
  EXPECT_NO_THROW(m.check());
  for (auto it = ddc::GmshReader::getValidParameters()->begin(); it != ddc::GmshReader::getValidParameters()->end(); ++it)
    EXPECT_FALSE(ddc::GmshReader::getValidParameters()->entry(it).docString().empty());
}

TEST(Gmsh, RejectsUnsupportedVariants) {
  const std::string base = slurp(kData + "/rect2x1.msh");
  ASSERT_FALSE(base.empty());
  EXPECT_THAT(readError(kData + "/version22.msh"), HasSubstr("MSH version 2.2 is not supported; expected version 4.1"));
  EXPECT_THAT(readError(kData + "/version22.msh"), HasSubstr("version22.msh"));
  EXPECT_THAT(readError(writeTemp("v40.msh", replaced(base, "4.1 0 8", "4.0 0 8"))),
              HasSubstr("MSH version 4.0 is not supported"));
  EXPECT_THAT(readError(kData + "/binary.msh"), HasSubstr("binary MSH files are not supported"));
  const std::string tri = readError(kData + "/triangles.msh");
  EXPECT_THAT(tri, HasSubstr("triangles are not supported; mesh with quadrangles (Mesh.RecombineAll=1)"));
  EXPECT_THAT(tri, HasSubstr("triangles.msh"));
  EXPECT_THAT(readError(kData + "/rect2x1.msh", CellType::Quad9),
              HasSubstr("(4-node quadrangles) but body 'Body' has element type Quad9"));
  EXPECT_THAT(readError(kData + "/quad9.msh", CellType::Quad4),
              HasSubstr("(9-node quadrangles) but body 'Body' has element type Quad4"));
  EXPECT_THAT(readError(writeTemp("hex.msh", replaced(base, "2 1 3 2\n", "3 1 5 2\n"))),
              HasSubstr("3-D elements (type 5, volume 1) are not supported"));
  EXPECT_THAT(readError(writeTemp("quad8.msh", replaced(base, "2 1 3 2\n", "2 1 16 2\n"))),
              HasSubstr("8-node quadrangles"));
  EXPECT_THAT(readError(writeTemp("part.msh", replaced(base, "$Nodes", "$PartitionedEntities\n$EndPartitionedEntities\n$Nodes"))),
              HasSubstr("partitioned MSH files are not supported"));
  EXPECT_THAT(readError(writeTemp("z.msh", replaced(base, "2 1 0\n", "2 1 0.5\n"))),
              HasSubstr("node 60 has z = 0.5; only planar meshes"));
}

TEST(Gmsh, RejectsBadSideSetsAndMalformedFiles) {
  const std::string base = slurp(kData + "/rect2x1.msh");
  // The "left" line replaced by the diagonal (0,1)-(1,0): not an element side.
  EXPECT_THAT(readError(writeTemp("diag.msh", replaced(base, "3 40 10\n", "3 40 20\n"))),
              HasSubstr("line element 3 of physical curve 'left' is not on the boundary of any element"));
  // ... by the interior edge (1,0)-(1,1).
  EXPECT_THAT(readError(writeTemp("inner.msh", replaced(base, "3 40 10\n", "3 20 50\n"))),
              HasSubstr("lies inside the body (on a side shared by two elements)"));
  // Second-order line in a Quad4 body.
  EXPECT_THAT(readError(writeTemp("line3.msh", replaced(base, "1 4 1 1\n3 40 10\n", "1 4 8 1\n3 40 10 50\n"))),
              HasSubstr("physical curve 'left' (curve 4) has elements of type 8"));
  // No surface elements (Gmsh saves only physical groups).
  EXPECT_THAT(readError(writeTemp("nosurf.msh", replaced(replaced(base, "4 5 1 5\n", "3 3 1 3\n"),
                                                          "2 1 3 2\n4 10 20 50 40\n5 20 50 60 30\n", ""))),
              HasSubstr("no 2-D elements found"));
  EXPECT_THAT(readError(writeTemp("tag.msh", replaced(base, "4 10 20 50 40", "4 10 20 50 99"))),
              HasSubstr("node tag 99, which is not in $Nodes"));
  // Truncated in the middle of $Nodes.
  const std::string cut = base.substr(0, base.find("1 1 0 1\n20"));
  const std::string trunc = readError(writeTemp("trunc.msh", cut));
  EXPECT_THAT(trunc, HasSubstr("unexpected end of file in section $Nodes"));
  EXPECT_THAT(trunc, HasSubstr("trunc.msh"));
  // Counts larger than the contents.
  EXPECT_THAT(readError(writeTemp("count.msh", replaced(base, "4 5 1 5\n", "5 5 1 5\n"))),
              HasSubstr("section $Elements ends early"));
  EXPECT_THAT(readError(writeTemp("count2.msh", replaced(base, "6 6 10 60\n", "6 7 10 60\n"))),
              HasSubstr("announces 7 nodes"));
  EXPECT_THAT(readError(writeTemp("short.msh", replaced(base, "5 20 50 60 30\n", "5 20 50 60\n"))),
              HasSubstr("element 5 of type 3 must list 4 node tags, found 3"));
  EXPECT_THAT(readError(writeTemp("num.msh", replaced(base, "2 1 0\n", "2 x 0\n"))),
              HasSubstr("expected a number (y), found 'x'"));
  EXPECT_THAT(readError(writeTemp("notmsh.msh", "hello\n")), HasSubstr("not a Gmsh MSH file"));
  EXPECT_THAT(readError(writeTemp("degen.msh", replaced(base, "4 10 20 50 40", "4 10 20 30 10"))),
              HasSubstr("element 4 has zero area"));
  EXPECT_THAT(readError(kData + "/does_not_exist.msh"), HasSubstr("cannot open Gmsh file"));
}

TEST(Gmsh, SkipsUnknownSections) {
  const std::string base = slurp(kData + "/rect2x1.msh");
  const std::string f = writeTemp("extra.msh", base + "$NodeData\n1\n\"u\"\n$EndNodeData\n");
  Mesh m;
  EXPECT_NO_THROW(ddc::readGmshFile(m, "B", CellType::Quad4, f));
  EXPECT_EQ(m.numElements(), 2);
}
