// Gmsh MSH 4.1 reader: the small files in data/ and variants of them written
// to a temporary directory, one per unsupported or malformed case; in 3-D
// also generated meshes written to MSH and read back. Every fault is also
// read in ranges on all ranks (readError()), with the whole reader's
// message, and the files that read are read in ranges into the parts the
// whole read cuts.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mpi.h>

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

#include "DDC_CoreTestUtils.hpp"
#include "DDC_Error.hpp"
#include "DDC_Gmsh.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_MeshPartCompare.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestTolerances.hpp"

using ddc::CellType;
using ddc::InputError;
using ddc::Mesh;
using ::testing::HasSubstr;

namespace {

using ddc::test::inputErrorOf;

const std::string kData = std::string(DDC_SOURCE_DIR) + "/packages/io/test/data";

std::string slurp(const std::string& file) {
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Write `content` to a temporary file of this run (rank 0 writes it, every
/// rank reads it) and return its path. Collective.
std::string writeTemp(const std::string& name, const std::string& content) {
  long long pid = ::getpid();
  MPI_Bcast(&pid, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  const std::string file = ::testing::TempDir() + "ddc_gmsh_" + std::to_string(pid) + "_" + name;
  MPI_Barrier(MPI_COMM_WORLD);
  if (ddc::commRank(MPI_COMM_WORLD) == 0) std::ofstream(file) << content;
  MPI_Barrier(MPI_COMM_WORLD);
  return file;
}

/// The bodies (name, physical group) of `file` read in ranges: each rank its
/// even share of their elements. Collective.
Mesh readInRanges(const std::string& file, CellType t, const std::vector<std::pair<std::string, std::string>>& bodies) {
  long long total = 0;
  for (const auto& [name, group] : bodies) total += ddc::gmshFileElementCount(file, name, t, group, MPI_COMM_WORLD);
  const auto [first, last] = ddc::evenShare(total, MPI_COMM_WORLD);
  Mesh part = Mesh::startPart();
  for (const auto& [name, group] : bodies)
    ddc::readGmshFileInRange(part, name, t, file, group, {first, last}, MPI_COMM_WORLD);
  return part;
}

/// The whole read of `file`'s bodies, and what reading them in ranges gives
/// each rank: the part the whole read cuts (its even share of the elements).
void expectSameInRanges(const std::string& file, CellType t,
                        const std::vector<std::pair<std::string, std::string>>& bodies) {
  Mesh whole;
  for (const auto& [name, group] : bodies) ddc::readGmshFile(whole, name, t, file, group);
  const auto [first, last] = ddc::evenShare(whole.numElements(), MPI_COMM_WORLD);
  std::vector<int> mine;
  for (long long e = first; e < last; ++e) mine.push_back(int(e));
  SCOPED_TRACE(file);
  ddc::test::expectSameParts(readInRanges(file, t, bodies), whole.part(mine));
}

/// `text` with the first occurrence of `from` replaced by `to` (must exist).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << "test bug: '" << from << "' not in the file";
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

/// The whole reader's message for `file`; reading it in ranges must stop
/// every rank with the same message. Collective.
std::string readError(const std::string& file, CellType t = CellType::Quad4, const std::string& surface = "") {
  const std::string whole = inputErrorOf([&] {
    Mesh m;
    ddc::readGmshFile(m, "Body", t, file, surface);
  });
  EXPECT_EQ(inputErrorOf([&] { readInRanges(file, t, {{"Body", surface}}); }), whole) << "in ranges: " << file;
  return whole;
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
  // A header count that disagrees with the blocks (was accepted silently).
  EXPECT_THAT(readError(writeTemp("count3.msh", replaced(base, "4 5 1 5\n", "4 6 1 5\n"))),
              HasSubstr("section $Elements announces 6 elements but its blocks hold 5"));
  EXPECT_THAT(readError(writeTemp("short.msh", replaced(base, "5 20 50 60 30\n", "5 20 50 60\n"))),
              HasSubstr("element 5 of type 3 must list 4 node tags, found 3"));
  EXPECT_THAT(readError(writeTemp("num.msh", replaced(base, "2 1 0\n", "2 x 0\n"))),
              HasSubstr("expected a number (y), found 'x'"));
  EXPECT_THAT(readError(writeTemp("notmsh.msh", "hello\n")), HasSubstr("not a Gmsh MSH file"));
  EXPECT_THAT(readError(writeTemp("degen.msh", replaced(base, "4 10 20 50 40", "4 10 20 30 10"))),
              HasSubstr("element 4 has zero area"));
  EXPECT_THAT(readError(kData + "/does_not_exist.msh"), HasSubstr("cannot open Gmsh file"));
  // A physical point on a node of no element.
  EXPECT_THAT(readError(writeTemp("stray_point.msh", replaced(base, "0 1 15 1\n1 10\n", "0 1 15 1\n1 70\n"))),
              HasSubstr("physical point 'origin' (node 70) belongs to no 2-D element"));
}

TEST(Gmsh, SkipsUnknownSections) {
  const std::string base = slurp(kData + "/rect2x1.msh");
  const std::string f = writeTemp("extra.msh", base + "$NodeData\n1\n\"u\"\n$EndNodeData\n");
  Mesh m;
  EXPECT_NO_THROW(ddc::readGmshFile(m, "B", CellType::Quad4, f));
  EXPECT_EQ(m.numElements(), 2);
}

// ---------------------------------------------------------------------- 3-D

namespace {

using ddc::test::Vec3;

/// Every face of a side set points away from the centroid of the body's
/// nodes (these bodies are convex).
void expectOutwardFaces(const Mesh& m, int body, const std::string& set) {
  const Vec3 c = ddc::test::nodeCentroid(m, body);
  for (const auto& s : m.sideSet(set))
    EXPECT_GT(ddc::test::dot(ddc::test::faceNormal(m, s), ddc::test::sub(ddc::test::faceCentroid(m, s), c)), 0.0)
        << set;
}

/// Gmsh element type of a cell type (as the reader's header lists them).
int gmshType(CellType t) {
  switch (t) {
    case CellType::Hex8: return 5;
    case CellType::Hex20: return 17;
    case CellType::Hex27: return 12;
    case CellType::Tet4: return 4;
    case CellType::Tet10: return 11;
    case CellType::Quad4: return 3;
    case CellType::Quad8: return 16;
    case CellType::Quad9: return 10;
    case CellType::Tri3: return 2;
    case CellType::Tri6: return 9;
    default: return -1;
  }
}

/// Write body 0 of a 3-D mesh as MSH 4.1: one volume (physical "solid"),
/// one surface per side set (physical named after the set), node tags in
/// reverse order of the mesh's numbering (so the reader must renumber).
std::string writeMsh(const Mesh& m, const std::vector<std::string>& sets) {
  std::ostringstream os;
  os.precision(17);
  const int nn = m.numNodes(), ne = m.numElements();
  const auto tag = [&](int n) { return nn - n; };
  os << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n" << sets.size() + 1 << "\n";
  for (size_t k = 0; k < sets.size(); ++k) os << "2 " << k + 1 << " \"" << sets[k].substr(sets[k].find('/') + 1) << "\"\n";
  os << "3 " << sets.size() + 1 << " \"solid\"\n$EndPhysicalNames\n$Entities\n0 0 " << sets.size() << " 1\n";
  for (size_t k = 0; k < sets.size(); ++k) os << k + 1 << " 0 0 0 1 1 1 1 " << k + 1 << " 0\n";
  os << "1 0 0 0 1 1 1 1 " << sets.size() + 1 << " 0\n$EndEntities\n";
  os << "$Nodes\n1 " << nn << " 1 " << nn << "\n3 1 0 " << nn << "\n";
  for (int n = 0; n < nn; ++n) os << tag(n) << "\n";
  for (int n = 0; n < nn; ++n) os << m.coord(n)[0] << " " << m.coord(n)[1] << " " << m.coord(n)[2] << "\n";
  size_t total = ne;
  for (const auto& s : sets) total += m.sideSet(s).size();
  os << "$EndNodes\n$Elements\n" << sets.size() + 1 << " " << total << " 1 " << total << "\n";
  size_t id = 1;
  for (size_t k = 0; k < sets.size(); ++k) {
    const auto& segs = m.sideSet(sets[k]);
    const CellType ft = ddc::referenceCell(m.elementType(0)).facets[0].type;
    os << "2 " << k + 1 << " " << gmshType(ft) << " " << segs.size() << "\n";
    for (const auto& s : segs) {
      os << id++;
      for (int i = 0; i < s.numNodes; ++i) os << " " << tag(s.nodes[i]);
      os << "\n";
    }
  }
  os << "3 1 " << gmshType(m.elementType(0)) << " " << ne << "\n";
  for (int e = 0; e < ne; ++e) {
    os << id++;
    for (int i = 0; i < m.elementNumNodes(e); ++i) os << " " << tag(m.elementNodes(e)[i]);
    os << "\n";
  }
  os << "$EndElements\n";
  return os.str();
}

std::string readError3(const std::string& file, CellType t = CellType::Hex8, const std::string& volume = "") {
  return readError(file, t, volume);
}

}  // namespace

TEST(Gmsh3D, ReadsHex8BlockWithFaceSetsEdgesAndPoints) {
  Mesh m;
  const int b = ddc::readGmshFile(m, "Block", CellType::Hex8, kData + "/hex2x1x1.msh");
  EXPECT_EQ(m.dim(), 3);
  EXPECT_NO_THROW(m.check());
  EXPECT_EQ(m.numNodes(), 12);
  EXPECT_EQ(m.numElements(), 2);
  double minDet;
  EXPECT_NEAR(ddc::test::meshMeasure(m, &minDet), 2.0, ddc::test::kRoundoff);
  EXPECT_GT(minDet, 0.0);
  EXPECT_EQ(m.coord(11), (Vec3{2.0, 1.0, 1.0}));
  ASSERT_EQ(m.sideSet("Block/left").size(), 1u);
  ASSERT_EQ(m.sideSet("Block/right").size(), 1u);
  ASSERT_EQ(m.sideSet("Block/bottom").size(), 2u);
  // The faces in the file run either way; the side sets are outward.
  for (const char* s : {"Block/left", "Block/right", "Block/bottom"}) expectOutwardFaces(m, b, s);
  const Vec3 n = ddc::test::faceNormal(m, m.sideSet("Block/left")[0]);
  EXPECT_EQ(n, (Vec3{-1.0, 0.0, 0.0}));
  EXPECT_EQ(m.sideSet("Block/bottom")[1].element, 1);
  EXPECT_EQ(m.nodeSet("Block/bottom").size(), 6u);
  // Physical curve and point -> node sets; physical volume -> node set.
  EXPECT_FALSE(m.hasSideSet("Block/edge"));
  EXPECT_EQ(m.nodeSet("Block/edge"), (std::vector<int>{0, 6}));
  EXPECT_EQ(m.nodeSet("Block/origin"), (std::vector<int>{0}));
  EXPECT_EQ(m.nodeSet("Block/block").size(), 12u);
}

TEST(Gmsh3D, ReadsHex20AndTetrahedraWithTheirFaces) {
  {
    Mesh m;
    ddc::readGmshFile(m, "Cube", CellType::Hex20, kData + "/hex20.msh");
    EXPECT_NO_THROW(m.check());
    EXPECT_EQ(m.numNodes(), 20);
    double minDet;
    // The sheared unit cube keeps volume 1.
    EXPECT_NEAR(ddc::test::meshMeasure(m, &minDet), 1.0, ddc::test::kRoundoff);
    const auto& top = m.sideSet("Cube/top");
    ASSERT_EQ(top.size(), 1u);
    EXPECT_EQ(top[0].numNodes, 8);
    EXPECT_EQ(top[0].localSide, 5);
    expectOutwardFaces(m, 0, "Cube/top");
    for (int i = 0; i < 8; ++i) EXPECT_EQ(m.coord(top[0].nodes[i])[2], 1.0);
    // Mid-edge nodes of the face are the midpoints of its corners.
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d)
        EXPECT_NEAR(m.coord(top[0].nodes[4 + k])[d],
                    0.5 * (m.coord(top[0].nodes[k])[d] + m.coord(top[0].nodes[(k + 1) % 4])[d]), ddc::test::kRoundoff);
  }
  {
    Mesh m;
    ddc::readGmshFile(m, "P", CellType::Tet4, kData + "/tet2.msh");
    EXPECT_NO_THROW(m.check());
    EXPECT_EQ(m.numElements(), 2);
    double minDet;
    EXPECT_NEAR(ddc::test::meshMeasure(m, &minDet), 1.0 / 6 + 2.0 / 6, ddc::test::kRoundoff);
    ASSERT_EQ(m.sideSet("P/base").size(), 1u);
    // "base" is z = 0, written with normal +z in the file: outward is -z.
    EXPECT_EQ(ddc::test::faceNormal(m, m.sideSet("P/base")[0]), (Vec3{0.0, 0.0, -0.5}));
    expectOutwardFaces(m, 0, "P/slant");
    EXPECT_EQ(m.sideSet("P/slant")[0].element, 1);
  }
  {
    Mesh m;
    ddc::readGmshFile(m, "T", CellType::Tet10, kData + "/tet10.msh", "tet");
    EXPECT_NO_THROW(m.check());
    EXPECT_EQ(m.numNodes(), 10);
    const auto& base = m.sideSet("T/base");
    ASSERT_EQ(base.size(), 1u);
    ASSERT_EQ(base[0].numNodes, 6);
    EXPECT_EQ(ddc::test::faceNormal(m, base[0]), (Vec3{0.0, 0.0, -0.5}));
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d)
        EXPECT_EQ(m.coord(base[0].nodes[3 + k])[d],
                  0.5 * (m.coord(base[0].nodes[k])[d] + m.coord(base[0].nodes[(k + 1) % 3])[d]));
  }
}

TEST(Gmsh3D, GeneratedMeshesOfEveryTypeSurviveARoundTrip) {
  for (CellType t : {CellType::Hex8, CellType::Hex20, CellType::Hex27, CellType::Tet4, CellType::Tet10}) {
    for (bool sector : {false, true}) {
      Mesh g;
      Teuchos::ParameterList p;
      std::vector<std::string> sets;
      if (sector) {
        p.set("Radial Elements", 2);
        p.set("Circumferential Elements", 5);
        p.set("Axial Elements", 2);
        ddc::generateCylindricalShellSector(g, "G", t, p, "S");
        sets = {"G/inner", "G/outer", "G/start", "G/end", "G/back", "G/front"};
      } else {
        p.set("Elements X", 2);
        p.set("Elements Y", 3);
        p.set("Elements Z", 2);
        p.set("Distortion", 0.2);
        ddc::generateBox(g, "G", t, p, "B");
        sets = {"G/left", "G/right", "G/bottom", "G/top", "G/back", "G/front"};
      }
      const std::string file = writeTemp(std::string("roundtrip_") + ddc::cellTypeName(t) + (sector ? "_s" : "_b") + ".msh",
                                         writeMsh(g, sets));
      Mesh m;
      ddc::readGmshFile(m, "G", t, file, "solid");
      EXPECT_NO_THROW(m.check());
      ASSERT_EQ(m.numNodes(), g.numNodes()) << ddc::cellTypeName(t);
      ASSERT_EQ(m.numElements(), g.numElements());
      // Tags were reversed: node n of the file is node N-1-n of the mesh.
      const int nn = g.numNodes();
      for (int e = 0; e < g.numElements(); ++e)
        for (int i = 0; i < g.elementNumNodes(e); ++i)
          ASSERT_EQ(m.elementNodes(e)[i], nn - 1 - g.elementNodes(e)[i]) << ddc::cellTypeName(t);
      // 17 significant digits print a double exactly.
      for (int n = 0; n < nn; ++n) ASSERT_EQ(m.coord(nn - 1 - n), g.coord(n));
      for (const auto& s : sets) {
        const auto& a = g.sideSet(s);
        const auto& b = m.sideSet(s);
        ASSERT_EQ(a.size(), b.size()) << s;
        for (size_t k = 0; k < a.size(); ++k) {
          EXPECT_EQ(b[k].element, a[k].element) << s;
          EXPECT_EQ(b[k].localSide, a[k].localSide) << s;
        }
      }
    }
  }
}

TEST(Gmsh3D, PhysicalVolumeSelectsOneBody) {
  Mesh m;
  const std::string f = kData + "/two_volumes.msh";
  const int a = ddc::readGmshFile(m, "A", CellType::Hex8, f, "block");
  const int b = ddc::readGmshFile(m, "B", CellType::Hex8, f, "pad");
  EXPECT_NO_THROW(m.check());
  EXPECT_EQ(m.body(a).numElements, 1);
  EXPECT_EQ(m.body(b).numNodes, 8);
  EXPECT_TRUE(m.hasSideSet("A/left"));
  EXPECT_FALSE(m.hasSideSet("B/left"));  // a face of the other body
  // The shared face is on the boundary of each body, outward from each.
  expectOutwardFaces(m, a, "A/interface");
  expectOutwardFaces(m, b, "B/interface");
  EXPECT_EQ(ddc::test::faceNormal(m, m.sideSet("A/interface")[0]), (Vec3{1.0, 0.0, 0.0}));
  EXPECT_EQ(ddc::test::faceNormal(m, m.sideSet("B/interface")[0]), (Vec3{-1.0, 0.0, 0.0}));
  // Without a selection the shared face is interior.
  EXPECT_THAT(readError3(f), HasSubstr("face element 1 of physical surface 'interface' lies inside the body (on a "
                                       "face shared by two elements)"));
  EXPECT_THAT(readError3(f, CellType::Hex8, "Pad"), HasSubstr("no physical volume named 'Pad'; physical volumes are "
                                                              "'block', 'pad'"));
  EXPECT_THAT(readError3(f, CellType::Hex8, "left"), HasSubstr("('left' is a physical surface)"));
  // readGmshBody: the parameter of the body's dimension selects.
  Teuchos::ParameterList p;
  p.set("File", f);
  p.set("Physical Volume", std::string("pad"));
  Mesh n;
  EXPECT_EQ(ddc::readGmshBody(n, "Pad", CellType::Hex8, p, "Mesh/Bodies/Pad/Gmsh", ""), 0);
  EXPECT_EQ(n.numElements(), 1);
  EXPECT_THAT(inputErrorOf([&] { ddc::readGmshBody(n, "Pad2", CellType::Quad4, p, "Mesh/Bodies/Pad2/Gmsh", ""); }),
              HasSubstr("parameter 'Mesh/Bodies/Pad2/Gmsh/Physical Volume' does not apply to body 'Pad2': its "
                        "element type Quad4 is 2-D, so 'Physical Surface' selects its elements"));
  Teuchos::ParameterList q;
  q.set("File", f);
  q.set("Physical Surface", std::string("pad"));
  EXPECT_THAT(inputErrorOf([&] { ddc::readGmshBody(n, "Pad3", CellType::Hex8, q, "Mesh/Bodies/Pad3/Gmsh", ""); }),
              HasSubstr("'Mesh/Bodies/Pad3/Gmsh/Physical Surface' does not apply to body 'Pad3': its element type "
                        "Hex8 is 3-D, so 'Physical Volume' selects its elements (its physical surfaces become side "
                        "sets)"));
}

TEST(Gmsh3D, RejectsUnsupportedAndMixedElementTypes) {
  const std::string base = slurp(kData + "/hex2x1x1.msh");
  ASSERT_FALSE(base.empty());
  const std::string hexBlock = "3 1 5 2\n7 1 2 5 4 7 8 11 10\n8 2 3 6 5 8 9 12 11\n";
  // Prisms, pyramids: the type is named, with the supported list.
  std::string e = readError3(writeTemp("prism.msh", replaced(base, hexBlock, "3 1 6 2\n7 1 2 5 7 8 11\n8 2 3 6 8 9 12\n")));
  EXPECT_THAT(e, HasSubstr("prism.msh', line 64: volume 1 has 6-node prisms (type 6), which DDContact does not "
                           "support; a 3-D body reads 8-node hexahedra (type 5) for Hex8, 20-node hexahedra (type 17) "
                           "for Hex20, 27-node hexahedra (type 12) for Hex27, 4-node tetrahedra (type 4) for Tet4, "
                           "10-node tetrahedra (type 11) for Tet10"));
  EXPECT_THAT(readError3(writeTemp("pyramid.msh", replaced(base, "3 1 5 2\n", "3 1 7 2\n"))),
              HasSubstr("volume 1 has 5-node pyramids (type 7), which DDContact does not support"));
  EXPECT_THAT(readError3(writeTemp("prism18.msh", replaced(base, "3 1 5 2\n", "3 1 13 2\n"))),
              HasSubstr("volume 1 has 18-node prisms (type 13), which DDContact does not support"));
  EXPECT_THAT(readError3(writeTemp("type99.msh", replaced(base, "3 1 5 2\n", "3 1 99 2\n"))),
              HasSubstr("volume 1 has elements of type 99 (unknown to DDContact), which DDContact does not support"));
  // Hexahedra and tetrahedra in one body.
  const std::string mixed =
      replaced(replaced(replaced(base, "6 8 1 8\n", "7 9 1 9\n"), "$EndElements", "3 2 4 1\n9 2 3 6 9\n$EndElements"),
               "$Entities\n1 1 3 1\n", "$Entities\n1 1 3 2\n");  // one more volume entity
  e = readError3(writeTemp("mixed.msh", replaced(mixed, "1 0 0 0 2 1 1 1 6 3 1 2 3\n",
                                                 "1 0 0 0 2 1 1 1 6 3 1 2 3\n2 1 0 0 2 1 1 1 6 0\n")));
  EXPECT_THAT(e, HasSubstr("line 68: mixed element types in one body: volume 1 (line 65) has 8-node hexahedra (type "
                           "5), volume 2 has 4-node tetrahedra (type 4); body 'Body' has one element type"));
  // The right type family, the wrong order for the body.
  EXPECT_THAT(readError3(kData + "/hex2x1x1.msh", CellType::Hex20),
              HasSubstr("volume 1 has 8-node hexahedra (type 5) but body 'Body' has element type Hex20; expected "
                        "20-node hexahedra (type 17) (Mesh.ElementOrder=2, Mesh.SecondOrderIncomplete=1)"));
  EXPECT_THAT(readError3(kData + "/hex20.msh", CellType::Hex27),
              HasSubstr("expected 27-node hexahedra (type 12) (Mesh.ElementOrder=2, Mesh.SecondOrderIncomplete=0)"));
  EXPECT_THAT(readError3(kData + "/tet2.msh", CellType::Hex8),
              HasSubstr("volume 1 has 4-node tetrahedra (type 4) but body 'Body' has element type Hex8"));
  // A 3-D file for a 2-D body, a 2-D file for a 3-D body.
  EXPECT_THAT(readError3(kData + "/hex2x1x1.msh", CellType::Quad4),
              HasSubstr("3-D elements (type 5, volume 1) are not supported in body 'Body' of 2-D element type Quad4; "
                        "a 3-D mesh needs a 3-D element type"));
  EXPECT_THAT(readError3(kData + "/rect2x1.msh", CellType::Hex8),
              HasSubstr("no 3-D elements found (expected 8-node hexahedra (type 5)). Note: once physical groups "
                        "exist, Gmsh saves only their elements: define a Physical Volume"));
  // Wrong node count in a 3-D element.
  EXPECT_THAT(readError3(writeTemp("count3.msh", replaced(base, "8 2 3 6 5 8 9 12 11\n", "8 2 3 6 5 8 9 12\n"))),
              HasSubstr("line 66: element 8 of type 5 must list 8 node tags, found 7"));
}

TEST(Gmsh3D, RejectsInvertedAndDegenerateElements) {
  const std::string base = slurp(kData + "/hex2x1x1.msh");
  // Element 8 with its two layers swapped: inside out.
  std::string e = readError3(writeTemp("inv.msh", replaced(base, "8 2 3 6 5 8 9 12 11", "8 8 9 12 11 2 3 6 5")));
  EXPECT_THAT(e, HasSubstr("inv.msh', line 66: element 8 (volume 1) of body 'Body' is inverted (det J = -0.125"));
  EXPECT_THAT(e, HasSubstr("corners 0-3 must run counter-clockwise seen from corners 4-7"));
  // Element 7 with corner 6 on corner 5 (node 8 twice).
  e = readError3(writeTemp("degen.msh", replaced(base, "7 1 2 5 4 7 8 11 10", "7 1 2 5 4 7 8 8 10")));
  EXPECT_THAT(e, HasSubstr("line 65: element 7 (volume 1) of body 'Body' is degenerate (det J = 0 at corner"));
  // A flat tetrahedron: node 5 moved into the plane of face 2-3-4.
  e = readError3(writeTemp("flat.msh", replaced(slurp(kData + "/tet2.msh"), "1 1 1\n$EndNodes", "0.5 0.5 0\n$EndNodes")),
                 CellType::Tet4);
  EXPECT_THAT(e, HasSubstr("element 4 (volume 1) of body 'Body' is degenerate (det J = 0 of the Tet4 corner map"));
  const std::string tetInv = readError3(
      writeTemp("tetinv.msh", replaced(slurp(kData + "/tet2.msh"), "3 1 2 3 4\n", "3 1 3 2 4\n")), CellType::Tet4);
  EXPECT_THAT(tetInv, HasSubstr("element 3 (volume 1) of body 'Body' is inverted (det J = -1 of the Tet4 corner map"));
}

TEST(Gmsh3D, RejectsBadFaceSets) {
  const std::string base = slurp(kData + "/hex2x1x1.msh");
  // Triangles in a face set of a hexahedral body.
  std::string e = readError3(writeTemp("tri.msh", replaced(base, "2 1 3 1\n3 1 7 10 4\n", "2 1 2 1\n3 1 7 10\n")));
  EXPECT_THAT(e, HasSubstr("tri.msh', line 57: physical surface 'left' (surface 1) has elements of type 2 (3-node "
                           "triangles) but the faces of body 'Body' (Hex8) are Quad4; expected 4-node quadrangles "
                           "(type 3)"));
  // Lines in a physical surface: a face set of the wrong dimension.
  e = readError3(writeTemp("lines.msh", replaced(base, "2 1 3 1\n3 1 7 10 4\n", "2 1 1 1\n3 1 7\n")));
  EXPECT_THAT(e, HasSubstr("physical surface 'left' (surface 1) has elements of type 1 (2-node lines, 1-D): a side "
                           "set of a 3-D body is made of 2-D faces; expected 4-node quadrangles (type 3)"));
  // 8-node quadrangles on a Hex8 body.
  EXPECT_THAT(readError3(writeTemp("quad8f.msh", replaced(base, "2 1 3 1\n3 1 7 10 4\n", "2 1 16 1\n3 1 7 10 4 2 3 5 6\n"))),
              HasSubstr("(8-node quadrangles) but the faces of body 'Body' (Hex8) are Quad4"));
  // A face that is no element face: the diagonal plane 1-3-12-10.
  EXPECT_THAT(readError3(writeTemp("diag.msh", replaced(base, "3 1 7 10 4\n", "3 1 3 12 10\n"))),
              HasSubstr("line 58: face element 3 of physical surface 'left' is not on the boundary of any element "
                        "(its corners are not the corners of an element face)"));
  // The interior face x = 1.
  EXPECT_THAT(readError3(writeTemp("inner3.msh", replaced(base, "3 1 7 10 4\n", "3 2 5 11 8\n"))),
              HasSubstr("face element 3 of physical surface 'left' lies inside the body (on a face shared by two "
                        "elements); side sets must lie on the boundary"));
  // ... and in the two-tetrahedron mesh.
  const std::string tets = slurp(kData + "/tet2.msh");
  EXPECT_THAT(readError3(writeTemp("inner_tet.msh", replaced(tets, "2 3 5 4\n", "2 2 3 4\n")), CellType::Tet4),
              HasSubstr("face element 2 of physical surface 'slant' lies inside the body"));
  EXPECT_THAT(readError3(writeTemp("off_tet.msh", replaced(tets, "2 3 5 4\n", "2 1 2 5\n")), CellType::Tet4),
              HasSubstr("face element 2 of physical surface 'slant' is not on the boundary of any element"));
  // Tet10 face whose mid-edge nodes are not the element face's.
  EXPECT_THAT(readError3(writeTemp("mid.msh", replaced(slurp(kData + "/tet10.msh"), "1 1 2 3 5 6 7\n", "1 1 2 3 5 6 8\n")),
                         CellType::Tet10),
              HasSubstr("the mid-edge / centre nodes of face element 1 of physical surface 'base' are not those of "
                        "the element face it lies on"));
  // A face or edge with a node of no element.
  EXPECT_THAT(readError3(writeTemp("stray.msh", replaced(base, "3 1 7 10 4\n", "3 1 7 10 99\n"))),
              HasSubstr("face element 3 of physical surface 'left' has a node that belongs to no 3-D element"));
  EXPECT_THAT(readError3(writeTemp("stray_line.msh", replaced(base, "2 1 7\n", "2 1 99\n"))),
              HasSubstr("line element 2 of physical curve 'edge' has a node that belongs to no 3-D element"));
  EXPECT_THAT(readError3(writeTemp("curve_quad.msh", replaced(base, "1 1 1 1\n2 1 7\n", "1 1 3 1\n2 1 7 10 4\n"))),
              HasSubstr("physical curve 'edge' (curve 1) has 4-node quadrangles (type 3); expected 2-node lines"));
}

TEST(GmshInRanges, EveryFileReadsIntoThePartsOfTheWholeRead) {
  // Each rank its even share of the elements, of one body or of two bodies
  // selected by their physical groups (the second's ids after the first's).
  const std::string examples = std::string(DDC_SOURCE_DIR) + "/examples";
  expectSameInRanges(kData + "/rect2x1.msh", CellType::Quad4, {{"Body", ""}});
  expectSameInRanges(kData + "/quad9.msh", CellType::Quad9, {{"Body", ""}});
  expectSameInRanges(kData + "/hex2x1x1.msh", CellType::Hex8, {{"Body", ""}});
  expectSameInRanges(kData + "/hex20.msh", CellType::Hex20, {{"Body", ""}});
  expectSameInRanges(kData + "/tet2.msh", CellType::Tet4, {{"Body", ""}});
  expectSameInRanges(kData + "/tet10.msh", CellType::Tet10, {{"Body", ""}});
  expectSameInRanges(kData + "/two_surfaces.msh", CellType::Quad4, {{"A", "block"}, {"B", "pad"}});
  expectSameInRanges(kData + "/two_volumes.msh", CellType::Hex8, {{"A", "block"}, {"B", "pad"}});
  expectSameInRanges(std::string(DDC_SOURCE_DIR) + "/test/inputs/restart_block.msh", CellType::Quad4, {{"Block", ""}});
  expectSameInRanges(examples + "/cattaneo_2d.msh", CellType::Quad4, {{"Cylinder", "cylinder"}, {"Block", "block"}});
  expectSameInRanges(examples + "/mindlin_sphere.msh", CellType::Hex8, {{"Sphere", "sphere"}, {"Block", "block"}});
  // Generated bodies of every 3-D type with face sets, their tags reversed.
  for (CellType t : {CellType::Hex8, CellType::Hex20, CellType::Hex27, CellType::Tet4, CellType::Tet10}) {
    Mesh g;
    Teuchos::ParameterList p;
    p.set("Elements X", 3);
    p.set("Elements Y", 2);
    p.set("Elements Z", 2);
    p.set("Distortion", 0.2);
    ddc::generateBox(g, "G", t, p, "B");
    const std::vector<std::string> sets = {"G/left", "G/right", "G/bottom", "G/top", "G/back", "G/front"};
    const std::string file = writeTemp(std::string("ranges_") + ddc::cellTypeName(t) + ".msh", writeMsh(g, sets));
    expectSameInRanges(file, t, {{"G", "solid"}});
  }
}

TEST(GmshInRanges, ANodeTagGivenTwiceIsNamedBeforeALaterFault) {
  // Tag 40 given to the node at (1, 1) as well: only the tag's owner (the
  // second rank on 2 and 3 ranks) sees both, while the first rank meets the
  // element with a node too few further down first. The first fault in the
  // file is named, as the whole reader names it (readError() compares).
  const std::string base = slurp(kData + "/rect2x1.msh");
  const std::string twice =
      replaced(replaced(base, "1 3 0 1\n50\n", "1 3 0 1\n40\n"), "5 20 50 60 30\n", "5 20 50 60\n");
  EXPECT_THAT(readError(writeTemp("twice.msh", twice)), HasSubstr("line 42: node tag 40 appears twice in section $Nodes"));
  EXPECT_THAT(readError(writeTemp("twice_only.msh", replaced(base, "1 3 0 1\n50\n", "1 3 0 1\n40\n"))),
              HasSubstr("node tag 40 appears twice"));
}

TEST(GmshInRanges, GroupsNamedAfterTheElementsAreRefusedForASelection) {
  // A selection needs the groups while the elements stream by: a file that
  // names them after $Elements is refused with what to do; without a
  // selection it reads.
  const std::string base = slurp(kData + "/two_surfaces.msh");
  const auto names = base.substr(base.find("$PhysicalNames"),
                                 base.find("$EndPhysicalNames") + 18 - base.find("$PhysicalNames"));
  const std::string late = replaced(base, names, "") + names;
  const std::string file = writeTemp("late_names.msh", late);
  EXPECT_NO_THROW({
    Mesh m;
    ddc::readGmshFile(m, "A", CellType::Quad4, file, "block");
  });
  EXPECT_THAT(inputErrorOf([&] { readInRanges(file, CellType::Quad4, {{"A", "block"}}); }),
              HasSubstr("$PhysicalNames or $Entities comes after $Elements; a body selected by a physical group "
                        "('block') is read in ranges only from a file that names its groups first"));
}

TEST(GmshInRanges, RangesThatDoNotFollowEachOtherAreRefused) {
  // Every rank the whole body: the ranges overlap (on one rank they are the
  // whole, and read).
  const std::string file = kData + "/rect2x1.msh";
  Mesh part = Mesh::startPart();
  const auto read = [&] { ddc::readGmshFileInRange(part, "Body", CellType::Quad4, file, "", {0, 2}, MPI_COMM_WORLD); };
  if (ddc::commSize(MPI_COMM_WORLD) == 1)
    EXPECT_NO_THROW(read());
  else
    EXPECT_THROW(read(), std::logic_error);
}
