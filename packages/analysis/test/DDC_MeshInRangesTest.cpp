// A mesh no rank holds whole (doc/architecture.md, "What a distributed mesh
// has to change"), on 1-3 ranks: the bodies generated in even ranges of
// element ids are the whole mesh's parts, PT-Scotch gives them the whole
// mesh's subdomains, and each rank ends with the part and subdomains it
// would cut from the whole mesh; the set-up's messages are the whole mesh's.
// A mesh built on rank 0 alone and dealt in ranges (buildMeshOnRankZero())
// is the same parts, and so are an Exodus II file read in slabs
// (readExodusBodyInRange()) and a Gmsh file read in ranges
// (readGmshBodyInRange()), their faults named as the whole readers name them.
#include <gtest/gtest.h>
#include <mpi.h>
#include <unistd.h>

#include <Teuchos_DefaultSerialComm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "DDC_ElementFactory.hpp"
#include "DDC_ExodusWriter.hpp"
#include "DDC_MeshInRanges.hpp"
#include "DDC_MeshPartCompare.hpp"
#include "DDC_ModelSetUp.hpp"
#include "DDC_ParallelPartition.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestRanks.hpp"

namespace {

using ddc::test::rank;
using ddc::test::ranks;

using ddc::test::inputErrorOf;
using PL = Teuchos::ParameterList;


/// "Mesh" with a distorted Hex8 box and a Tet4 box beside it (two bodies,
/// random vertex displacements, cells split into tetrahedra).
PL twoBoxes() {
  PL mesh("Mesh");
  PL& left = mesh.sublist("Bodies").sublist("Left");
  left.set("Generator", std::string("Box"));
  left.sublist("Element").set("Type", std::string("Hex8"));
  left.sublist("Element").sublist("Material").set("Type", std::string("Linear Elastic"));
  PL& lb = left.sublist("Box");
  lb.set("Elements X", 6);
  lb.set("Elements Y", 3);
  lb.set("Elements Z", 2);
  lb.set("Distortion", 0.2);
  PL& right = mesh.sublist("Bodies").sublist("Right");
  right.set("Generator", std::string("Box"));
  right.sublist("Element").set("Type", std::string("Tet4"));
  right.sublist("Element").sublist("Material").set("Type", std::string("Linear Elastic"));
  PL& rb = right.sublist("Box");
  rb.set("Origin X", 2.0);
  rb.set("Elements X", 2);
  rb.set("Elements Y", 2);
  rb.set("Elements Z", 3);
  return mesh;
}

/// This rank's even range of the whole mesh's elements, cut from it.
ddc::Mesh evenPart(const ddc::Mesh& whole) {
  const long long ne = whole.numElements();
  std::vector<int> mine;
  for (long long e = ne * rank() / ranks(); e < ne * (rank() + 1) / ranks(); ++e) mine.push_back(int(e));
  return whole.part(mine);
}

TEST(MeshInRanges, TheWholeMeshPartitionedAndCut) {
  const auto factory = ddc::ElementFactory::withBuiltins();
  PL forRanges = twoBoxes(), forWhole = twoBoxes();
  const auto range = ddc::buildMeshInRanges(forRanges, factory, nullptr, "", MPI_COMM_WORLD);
  const auto whole = ddc::buildMesh(forWhole, factory, ".");
  ddc::test::expectSameParts(*range, evenPart(*whole));
  for (int b = 0; b < whole->numBodies(); ++b) {
    EXPECT_EQ(range->bodyGlobalNodes(b), whole->body(b).numNodes);
    EXPECT_EQ(range->bodyGlobalElements(b), whole->body(b).numElements);
  }
  // PT-Scotch on the ranges: the whole mesh's subdomains, edge cut and summary.
  const int subdomains = 5;
  const ddc::Partition p = ddc::partitionRangePtScotch(*range, subdomains, MPI_COMM_WORLD);
  const ddc::Partition wp = ddc::partitionPtScotch(*whole, subdomains, MPI_COMM_WORLD);
  ASSERT_EQ(p.elementSubdomain.size(), size_t(range->numElements()));
  for (int e = 0; e < range->numElements(); ++e)
    EXPECT_EQ(p.elementSubdomain[e], wp.elementSubdomain[range->elementId(e)]) << "element " << range->elementId(e);
  EXPECT_EQ(p.edgeCut, wp.edgeCut);
  EXPECT_EQ(ddc::partitionSummary(*range, p, "PT-Scotch", MPI_COMM_WORLD),
            ddc::partitionSummary(*whole, wp, "PT-Scotch"));
  // Each element to the rank of its subdomain: the part rankPart() cuts.
  const ddc::RankPart moved = ddc::migratedRankPart(MPI_COMM_WORLD, *range, p);
  const ddc::RankPart cut = ddc::rankPart(*whole, wp, rank(), ranks());
  ddc::test::expectSameParts(moved.mesh, cut.mesh);
  EXPECT_EQ(moved.partition.elementSubdomain, cut.partition.elementSubdomain);
  for (int b = 0; b < whole->numBodies(); ++b) EXPECT_EQ(moved.mesh.bodyGlobalNodes(b), whole->body(b).numNodes);
}

TEST(MeshInRanges, RangesThatDoNotCoverTheMeshInRankOrderAreRefused) {
  PL mesh = twoBoxes();
  const auto whole = ddc::buildMesh(mesh, ddc::ElementFactory::withBuiltins(), ".");
  // Every rank the whole mesh's first element: not ranges in rank order
  // (on one rank: not the whole mesh).
  const ddc::Mesh first = whole->part({0});
  EXPECT_THROW(ddc::partitionRangePtScotch(first, 2, MPI_COMM_WORLD), std::invalid_argument);
}

TEST(MeshInRanges, ChosenForPtScotchAndRangeGeneratorsWithoutTheWholeMesh) {
  PL deck;
  deck.sublist("Mesh") = twoBoxes();
  deck.sublist("Partition").set("Mesh On Every Rank", false);
  deck.sublist("Partition").set("Method", std::string("PT-Scotch"));
  EXPECT_TRUE(ddc::meshBuiltInRanges(deck));
  deck.sublist("Mesh").sublist("Bodies").sublist("Left").remove("Generator");  // Rectangle by default
  EXPECT_TRUE(ddc::meshBuiltInRanges(deck));
  deck.sublist("Partition").set("Method", std::string("METIS"));
  EXPECT_FALSE(ddc::meshBuiltInRanges(deck));
  deck.sublist("Partition").set("Method", std::string("PT-Scotch"));
  deck.sublist("Partition").set("Mesh On Every Rank", true);
  EXPECT_FALSE(ddc::meshBuiltInRanges(deck));
  deck.sublist("Partition").set("Mesh On Every Rank", false);
  deck.sublist("Mesh").sublist("Bodies").sublist("Right").set("Generator", std::string("Sphere Octant"));
  EXPECT_TRUE(ddc::meshBuiltInRanges(deck));  // every built-in generator makes ranges
  deck.sublist("Mesh").sublist("Bodies").sublist("Right").set("Generator", std::string("Gmsh"));
  EXPECT_TRUE(ddc::meshBuiltInRanges(deck));  // read in ranges as the file streams by
  deck.sublist("Mesh").sublist("Bodies").sublist("Right").set("Generator", 3);
  EXPECT_FALSE(ddc::meshBuiltInRanges(deck));  // buildMesh() says what is wrong
}

TEST(MeshInRanges, TheOriginOfTheMeshByPartitionerAndBodies) {
  PL deck;
  deck.sublist("Mesh") = twoBoxes();
  deck.sublist("Partition").set("Mesh On Every Rank", false);
  deck.sublist("Partition").set("Method", std::string("PT-Scotch"));
  EXPECT_EQ(ddc::meshOrigin(deck), ddc::MeshOrigin::Ranges);
  deck.sublist("Mesh").sublist("Bodies").sublist("Right").set("Generator", std::string("Exodus"));
  EXPECT_EQ(ddc::meshOrigin(deck), ddc::MeshOrigin::Ranges);  // read in slabs
  deck.sublist("Mesh").sublist("Bodies").sublist("Right").set("Generator", std::string("Gmsh"));
  EXPECT_EQ(ddc::meshOrigin(deck), ddc::MeshOrigin::Ranges);  // read as the file streams by
  deck.sublist("Partition").set("Method", std::string("METIS"));
  EXPECT_EQ(ddc::meshOrigin(deck), ddc::MeshOrigin::EveryRank);
  deck.sublist("Partition").set("Method", std::string("PT-Scotch"));
  deck.sublist("Partition").set("Mesh On Every Rank", true);
  EXPECT_EQ(ddc::meshOrigin(deck), ddc::MeshOrigin::EveryRank);
}

TEST(MeshInRanges, BuiltOnRankZeroAndSentInRangesIsWhatTheRangesMake) {
  // Rank 0 alone builds the whole mesh and deals it: every rank holds the
  // part it would have generated in its range (the sets by id: the deal
  // sorts a side set's segments by element id).
  PL forRanges = twoBoxes(), onRankZero = twoBoxes();
  const auto factory = ddc::ElementFactory::withBuiltins();
  const auto ranges = ddc::buildMeshInRanges(forRanges, factory, nullptr, "", MPI_COMM_WORLD);
  const auto dealt = ddc::buildMeshOnRankZero(onRankZero, factory, ".", nullptr, "", MPI_COMM_WORLD);
  ddc::test::expectSameParts(*dealt, *ranges);
  // Every rank has the parameters with the generators' defaults, as the ranges do.
  EXPECT_TRUE(Teuchos::haveSameValues(onRankZero, forRanges)) << onRankZero << "\n" << forRanges;
}

TEST(MeshInRanges, AnErrorOfTheMeshOnRankZeroStopsEveryRank) {
  // A file only rank 0 reads, missing: the whole mesh's message on every rank.
  PL forWhole("Mesh");
  PL& body = forWhole.sublist("Bodies").sublist("Block");
  body.set("Generator", std::string("Gmsh"));
  body.sublist("Element").set("Type", std::string("Quad4"));
  body.sublist("Element").sublist("Material").set("Type", std::string("Linear Elastic"));
  body.sublist("Gmsh").set("File", std::string("no_such_mesh.msh"));
  PL onRankZero = forWhole;
  const auto factory = ddc::ElementFactory::withBuiltins();
  const std::string expected = inputErrorOf([&] { ddc::buildMesh(forWhole, factory, "."); });
  EXPECT_NE(expected.find("no_such_mesh.msh"), std::string::npos) << expected;
  EXPECT_EQ(inputErrorOf([&] { ddc::buildMeshOnRankZero(onRankZero, factory, ".", nullptr, "", MPI_COMM_WORLD); }),
            expected);
}

/// "Mesh" with the Mindlin sphere's two bodies, each a physical volume of
/// examples/mindlin_sphere.msh.
PL mindlinBodies() {
  PL mesh("Mesh");
  for (const char* name : {"Sphere", "Block"}) {
    PL& body = mesh.sublist("Bodies").sublist(name);
    body.set("Generator", std::string("Gmsh"));
    body.sublist("Element").set("Type", std::string("Hex8"));
    body.sublist("Element").sublist("Material").set("Type", std::string("Linear Elastic"));
    body.sublist("Gmsh").set("File", std::string(DDC_SOURCE_DIR) + "/examples/mindlin_sphere.msh");
    body.sublist("Gmsh").set("Physical Volume", std::string(name == std::string("Sphere") ? "sphere" : "block"));
  }
  return mesh;
}

TEST(MeshInRanges, GmshFilesReadInRangesAreWhatRankZeroDeals) {
  // Read in ranges (each rank keeps its range as the file streams by), as
  // rank 0 reads them whole and deals them; a missing file stops every
  // rank with the whole reader's message.
  const PL mesh = mindlinBodies();
  const auto factory = ddc::ElementFactory::withBuiltins();
  PL forRanges = mesh, onRankZero = mesh;
  const auto ranges = ddc::buildMeshInRanges(forRanges, factory, nullptr, "", MPI_COMM_WORLD, ".");
  const auto dealt = ddc::buildMeshOnRankZero(onRankZero, factory, ".", nullptr, "", MPI_COMM_WORLD);
  ddc::test::expectSameParts(*ranges, *dealt);
  EXPECT_TRUE(Teuchos::haveSameValues(onRankZero, forRanges)) << onRankZero << "\n" << forRanges;
  EXPECT_TRUE(ranges->hasSideSet("Sphere/surface")) << "every rank names the file's face sets";
  EXPECT_TRUE(ranges->hasSideSet("Block/top"));
  PL missing = mesh, missingWhole = mesh;
  for (PL* m : {&missing, &missingWhole})
    m->sublist("Bodies").sublist("Block").sublist("Gmsh").set("File", std::string("no_such_mesh.msh"));
  const std::string expected = inputErrorOf([&] { ddc::buildMesh(missingWhole, factory, "."); });
  EXPECT_NE(expected.find("'Mesh/Bodies/Block/Gmsh/File' (body 'Block'): cannot open Gmsh file"), std::string::npos)
      << expected;
  EXPECT_EQ(inputErrorOf([&] { ddc::buildMeshInRanges(missing, factory, nullptr, "", MPI_COMM_WORLD, "."); }),
            expected);
}

TEST(MeshInRanges, AGmshBodyWithoutRoomForItsShareStopsEveryRank) {
  PL mesh = mindlinBodies();
  const ddc::MemoryLimit tiny{1000.0, "a test's budget"};
  const std::string msg = inputErrorOf([&] {
    ddc::buildMeshInRanges(mesh, ddc::ElementFactory::withBuiltins(), &tiny, "run on more ranks", MPI_COMM_WORLD);
  });
  EXPECT_NE(msg.find("'Mesh/Bodies/Sphere/Gmsh/File' (body 'Sphere'): '"), std::string::npos) << msg;
  EXPECT_NE(msg.find("mindlin_sphere.msh': the mesh would have"), std::string::npos) << msg;
  EXPECT_NE(msg.find("on this rank (its share of the mesh), more than the 1000 B available (a test's budget); run on "
                     "more ranks"),
            std::string::npos)
      << msg;
}

TEST(MeshInRanges, ABodyTooThinIsRefusedWithTheWholeMeshesMessage) {
  PL forRanges = twoBoxes(), forWhole = twoBoxes();
  for (PL* p : {&forRanges, &forWhole})
    p->sublist("Bodies").sublist("Right").sublist("Box").set("Length Z", 1e-101);
  const auto factory = ddc::ElementFactory::withBuiltins();
  const std::string expected = inputErrorOf([&] { ddc::buildMesh(forWhole, factory, "."); });
  EXPECT_NE(expected.find("body 'Right' spans 1e-101 along its thinnest axis"), std::string::npos) << expected;
  EXPECT_EQ(inputErrorOf([&] { ddc::buildMeshInRanges(forRanges, factory, nullptr, "", MPI_COMM_WORLD); }), expected);
}

TEST(MeshInRanges, ARankWithoutRoomForItsShareStopsEveryRank) {
  PL mesh = twoBoxes();
  const ddc::MemoryLimit tiny{1000.0, "a test's budget"};
  const std::string msg = inputErrorOf([&] {
    ddc::buildMeshInRanges(mesh, ddc::ElementFactory::withBuiltins(), &tiny, "run on more ranks", MPI_COMM_WORLD);
  });
  EXPECT_NE(msg.find("'Mesh/Bodies/Left/Box': the mesh would have"), std::string::npos) << msg;
  EXPECT_NE(msg.find("on this rank (its share of the mesh), more than the 1000 B available (a test's budget); run on "
                     "more ranks"),
            std::string::npos)
      << msg;
}

TEST(MeshInRanges, AnInvertedElementIsNamedByItsIdInTheWholeMesh) {
  // Element 30 of Left (in the first rank's range) and the Tet4 elements
  // at a node of element 100 of Right (the last rank's on 1-3 ranks)
  // turned inside out: every rank names the lowest, as on the whole mesh.
  for (bool withLeft : {false, true}) {
    PL mesh = twoBoxes();
    const auto whole = ddc::buildMesh(mesh, ddc::ElementFactory::withBuiltins(), ".");
    whole->coord(whole->elementNodes(100)[0])[1] += 3.0;
    if (withLeft) whole->coord(whole->elementNodes(30)[6])[0] -= 2.0;
    const auto all = ddc::makeBodyElements(*whole, mesh, ddc::ElementFactory::withBuiltins());
    const std::string expected = inputErrorOf([&] { ddc::requireAdmissibleElements(*whole, all, MPI_COMM_SELF); });
    EXPECT_NE(expected.find(withLeft ? "mesh: element 30 of body 'Left'" : "of body 'Right' is inverted"),
              std::string::npos)
        << expected;
    const ddc::Mesh part = evenPart(*whole);
    const auto elements = ddc::makeBodyElements(part, mesh, ddc::ElementFactory::withBuiltins());
    EXPECT_EQ(inputErrorOf([&] { ddc::requireAdmissibleElements(part, elements, MPI_COMM_WORLD); }), expected);
  }
}

/// twoBoxes() written whole to an Exodus II file by rank 0 (the Exodus II
/// library: one block per body, named after it, and the sets), and the
/// "Mesh" that reads each body back from its block.
class ExodusInRanges : public testing::Test {
 protected:
  void SetUp() override {
    long long pid = ::getpid();
    MPI_Bcast(&pid, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
    dir_ = std::filesystem::temp_directory_path() / ("ddc_mesh_in_ranges_exodus_" + std::to_string(pid));
    if (rank() == 0) std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    MPI_Barrier(MPI_COMM_WORLD);
    if (rank() == 0) std::filesystem::remove_all(dir_);
  }
  /// `whole` as the file `name`, written on rank 0 before any rank reads it.
  std::string write(const ddc::Mesh& whole, const std::string& name) const {
    const std::string path = (dir_ / name).string();
    if (rank() == 0)
      ddc::ExodusWriter(Teuchos::rcp(new Teuchos::SerialComm<int>()), path, whole, ddc::ExodusVariables());
    MPI_Barrier(MPI_COMM_WORLD);
    return path;
  }
  static PL readBack(const std::string& file) {
    PL mesh = twoBoxes();
    for (const char* name : {"Left", "Right"}) {
      PL& body = mesh.sublist("Bodies").sublist(name);
      body.remove("Box");
      body.set("Generator", std::string("Exodus"));
      body.sublist("Exodus").set("File", file);
      body.sublist("Exodus").set("Element Block", std::string(name));
    }
    return mesh;
  }

  std::filesystem::path dir_;
};

TEST_F(ExodusInRanges, SlabsOfTheFileAreTheWholeBodysParts) {
  // Each block uses some of the file's nodes (the two bodies share the
  // file's coordinates); each body has its own sets and none of the other's.
  const auto factory = ddc::ElementFactory::withBuiltins();
  PL generate = twoBoxes();
  const std::string file = write(*ddc::buildMesh(generate, factory, "."), "two_boxes.e");
  PL slabs = readBack(file), onRankZero = readBack(file), whole = readBack(file);
  ddc::Mesh::GlobalId total = 0;
  const auto ranges = ddc::buildMeshInRanges(slabs, factory, nullptr, "", MPI_COMM_WORLD, ".");
  const auto dealt = ddc::buildMeshOnRankZero(onRankZero, factory, ".", nullptr, "", MPI_COMM_WORLD);
  const auto read = ddc::buildMesh(whole, factory, ".");
  ddc::test::expectSameParts(*ranges, *dealt);
  ddc::test::expectSameParts(*ranges, evenPart(*read));
  for (int b = 0; b < read->numBodies(); ++b) {
    EXPECT_EQ(ranges->bodyGlobalNodes(b), read->body(b).numNodes);
    total += read->body(b).numNodes;
  }
  EXPECT_EQ(ranges->numGlobalNodes(), total);
  EXPECT_TRUE(read->hasSideSet("Left/Left/left")) << "the file's side sets are read";
  EXPECT_FALSE(read->hasNodeSet("Left/Right/left")) << "another body's sets are left out";
}

TEST_F(ExodusInRanges, AGeneratedBodyBeforeOneReadInSlabs) {
  // Left generated in its range, Right read from its block: Right's ids
  // follow Left's, in the file's slabs as in the generator's ranges.
  const auto factory = ddc::ElementFactory::withBuiltins();
  PL generate = twoBoxes();
  const std::string file = write(*ddc::buildMesh(generate, factory, "."), "two_boxes.e");
  PL mixed = readBack(file);
  mixed.sublist("Bodies").sublist("Left") = twoBoxes().sublist("Bodies").sublist("Left");
  PL slabs = mixed, onRankZero = mixed;
  const auto ranges = ddc::buildMeshInRanges(slabs, factory, nullptr, "", MPI_COMM_WORLD, ".");
  const auto dealt = ddc::buildMeshOnRankZero(onRankZero, factory, ".", nullptr, "", MPI_COMM_WORLD);
  ddc::test::expectSameParts(*ranges, *dealt);
  EXPECT_EQ(ranges->body(0).name, "Left");
  EXPECT_EQ(ranges->bodyGlobalElements(1), 72);  // Right's 2 x 2 x 3 cells of 6 tetrahedra
}

TEST_F(ExodusInRanges, AFaultIsNamedAsTheWholeReaderNamesIt) {
  // The faults of AnInvertedElementIsNamedByItsIdInTheWholeMesh (file
  // elements 78, on the last rank's range on 2 and 3 ranks, and 31, on the
  // first's), and a coordinate that is not a number at a node of element 90
  // (file node 108, whose owner is the last rank): each rank checks its
  // slab, and every rank throws the first fault the whole reader meets.
  const auto factory = ddc::ElementFactory::withBuiltins();
  const std::vector<std::string> expected = {"element 78 (element 42 of element block 'Right') is inverted",
                                             "element 31 (element 31 of element block 'Left') is inverted",
                                             "node 108 of element block 'Right' has y = nan; every coordinate must"};
  for (int fault = 0; fault < 3; ++fault) {
    PL generate = twoBoxes();
    const auto mesh = ddc::buildMesh(generate, factory, ".");
    if (fault < 2) mesh->coord(mesh->elementNodes(100)[0])[1] += 3.0;
    if (fault == 1) mesh->coord(mesh->elementNodes(30)[6])[0] -= 2.0;
    if (fault == 2) mesh->coord(mesh->elementNodes(90)[2])[1] = std::numeric_limits<double>::quiet_NaN();
    const std::string file = write(*mesh, "fault" + std::to_string(fault) + ".e");
    PL slabs = readBack(file), whole = readBack(file);
    const std::string message = inputErrorOf([&] { ddc::buildMesh(whole, factory, "."); });
    EXPECT_NE(message.find(expected[fault]), std::string::npos) << message;
    EXPECT_EQ(inputErrorOf([&] { ddc::buildMeshInRanges(slabs, factory, nullptr, "", MPI_COMM_WORLD, "."); }),
              message);
  }
}

}  // namespace
