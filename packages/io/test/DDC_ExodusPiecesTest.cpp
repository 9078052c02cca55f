// Exodus II results on parts of a mesh (ExodusWriter on Mesh::part()): each
// rank writes its piece NAME.P.r with its nodes and elements, their ids in
// the whole mesh as the id maps, every body's block (empty where the rank
// has none of its elements) and the whole mesh's counts; nothing is
// gathered. A restart copies the steps of an earlier run by node and
// element id from one file into pieces and from pieces into one file
// (ExodusWriter::copySteps()); resultFiles() finds either layout. Run on
// 1-3 ranks: on 2 and 3 the second body is on rank 0 only.
#include <gtest/gtest.h>
#include <mpi.h>
#include <unistd.h>

#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <exodusII.h>
#include <filesystem>
#include <string>
#include <vector>

#include "DDC_ExodusWriter.hpp"
#include "DDC_MeshGenerators.hpp"

namespace fs = std::filesystem;

namespace {

using Comm = Teuchos::RCP<const Teuchos::Comm<int>>;

/// Body A (3 x 2 Quad4, elements 0-5) and body B (2 x 2, elements 6-9).
ddc::Mesh twoBodies() {
  ddc::Mesh m;
  Teuchos::ParameterList a, b;
  a.set("Elements X", 3);
  a.set("Elements Y", 2);
  ddc::generateRectangle(m, "A", ddc::CellType::Quad4, a, "Rectangle");
  b.set("Elements X", 2);
  b.set("Elements Y", 2);
  b.set("Origin X", 5.0);
  ddc::generateRectangle(m, "B", ddc::CellType::Quad4, b, "Rectangle");
  return m;
}

/// This rank's elements: those of A by stride, all of B on rank 0.
std::vector<int> mine(const ddc::Mesh& whole, int rank, int ranks) {
  std::vector<int> out;
  for (int e = 0; e < whole.numElements(); ++e)
    if ((whole.elementBody(e) == 0 ? e % ranks : 0) == rank) out.push_back(e);
  return out;
}

ddc::ExodusVariables variables() {
  ddc::ExodusVariables v;
  v.nodal = {"u"};
  v.element = {"s"};
  v.global = {"g"};
  return v;
}

/// Values of step k: node id * 10 + k, element id + 100 k, global k.
ddc::ExodusStepValues stepValues(const ddc::Mesh& mesh, int k) {
  ddc::ExodusStepValues v;
  for (int n = 0; n < mesh.numNodes(); ++n) v.nodes.push_back(n), v.nodal.push_back(double(mesh.nodeId(n)) * 10 + k);
  for (int e = 0; e < mesh.numElements(); ++e)
    v.elements.push_back(e), v.element.push_back(double(mesh.elementId(e)) + 100.0 * k);
  v.global = {double(k)};
  return v;
}

/// Checks that file `path` holds `mesh`'s values of steps 1 .. steps.
void expectSteps(const std::string& path, const ddc::Mesh& mesh, int steps) {
  int cpu = 8, io = 0;
  float version = 0;
  const int id = ex_open(path.c_str(), EX_READ, &cpu, &io, &version);
  ASSERT_GE(id, 0) << path;
  EXPECT_EQ(ex_inquire_int(id, EX_INQ_TIME), steps) << path;
  for (int k = 1; k <= steps; ++k) {
    double time = -1;
    ex_get_time(id, k, &time);
    EXPECT_EQ(time, double(k));
    std::vector<double> u(size_t(mesh.numNodes()));
    ASSERT_GE(ex_get_var(id, k, EX_NODAL, 1, 1, mesh.numNodes(), u.data()), 0);
    for (int n = 0; n < mesh.numNodes(); ++n) EXPECT_EQ(u[size_t(n)], double(mesh.nodeId(n)) * 10 + k) << path;
    for (int b = 0; b < mesh.numBodies(); ++b) {
      const ddc::Body& body = mesh.body(b);
      std::vector<double> s(size_t(body.numElements));
      if (body.numElements > 0) ASSERT_GE(ex_get_var(id, k, EX_ELEM_BLOCK, 1, b + 1, body.numElements, s.data()), 0);
      for (int i = 0; i < body.numElements; ++i)
        EXPECT_EQ(s[size_t(i)], double(mesh.elementId(body.firstElement + i)) + 100.0 * k) << path;
    }
    double g = -1;
    ex_get_var(id, k, EX_GLOBAL, 1, 0, 1, &g);
    EXPECT_EQ(g, double(k));
  }
  ex_close(id);
}

class ExodusPieces : public testing::Test {
 protected:
  void SetUp() override {
    comm_ = Teuchos::DefaultComm<int>::getComm();
    rank_ = comm_->getRank();
    ranks_ = comm_->getSize();
    int pid = int(::getpid());
    MPI_Bcast(&pid, 1, MPI_INT, 0, MPI_COMM_WORLD);
    dir_ = fs::temp_directory_path() / ("ddc_io_exodus_pieces_" + std::to_string(pid));
    if (rank_ == 0) fs::create_directories(dir_);
    MPI_Barrier(MPI_COMM_WORLD);
    part_ = whole_.part(mine(whole_, rank_, ranks_));
  }
  void TearDown() override {
    MPI_Barrier(MPI_COMM_WORLD);
    if (rank_ == 0) fs::remove_all(dir_);
  }
  /// Pieces of `name` with steps 1 .. steps.
  void writePieces(const std::string& name, int steps) {
    ddc::ExodusWriter w(comm_, path(name), part_, variables());
    for (int k = 1; k <= steps; ++k) w.writeStep(double(k), stepValues(part_, k));
    w.close();
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  Comm comm_;
  int rank_ = 0, ranks_ = 1;
  fs::path dir_;
  ddc::Mesh whole_ = twoBodies();
  ddc::Mesh part_;
};

TEST_F(ExodusPieces, EachRankWritesItsPieceWithTheWholeMeshIds) {
  writePieces("r.e", 2);
  const std::string piece = ddc::ExodusWriter::piecePath(path("r.e"), ranks_, rank_);
  EXPECT_FALSE(fs::exists(path("r.e")));
  int cpu = 8, io = 0;
  float version = 0;
  const int id = ex_open(piece.c_str(), EX_READ, &cpu, &io, &version);
  ASSERT_GE(id, 0) << piece;
  int procs = 0, inFile = 0;
  char type[2] = {0, 0};
  ASSERT_GE(ex_get_init_info(id, &procs, &inFile, type), 0);
  EXPECT_EQ(procs, ranks_);
  EXPECT_EQ(inFile, 1);
  int nodes = 0, elements = 0, blocks = 0, nodeSets = 0, sideSets = 0;
  ASSERT_GE(ex_get_init_global(id, &nodes, &elements, &blocks, &nodeSets, &sideSets), 0);
  EXPECT_EQ(nodes, whole_.numNodes());
  EXPECT_EQ(elements, whole_.numElements());
  EXPECT_EQ(blocks, 2);
  EXPECT_EQ(ex_inquire_int(id, EX_INQ_NODES), part_.numNodes());
  EXPECT_EQ(ex_inquire_int(id, EX_INQ_ELEM_BLK), 2);
  std::vector<int> nodeIds(size_t(part_.numNodes())), elementIds(size_t(part_.numElements()));
  ASSERT_GE(ex_get_id_map(id, EX_NODE_MAP, nodeIds.data()), 0);
  ASSERT_GE(ex_get_id_map(id, EX_ELEM_MAP, elementIds.data()), 0);
  for (int n = 0; n < part_.numNodes(); ++n) EXPECT_EQ(nodeIds[size_t(n)], part_.nodeId(n) + 1);
  for (int e = 0; e < part_.numElements(); ++e) EXPECT_EQ(elementIds[size_t(e)], part_.elementId(e) + 1);
  // Body B's block: all 4 elements on rank 0, empty on the others.
  ex_block block{};
  block.id = 2;
  block.type = EX_ELEM_BLOCK;
  ASSERT_GE(ex_get_block_param(id, &block), 0);
  EXPECT_EQ(block.num_entry, rank_ == 0 ? 4 : 0);
  ex_close(id);
  expectSteps(piece, part_, 2);
}

TEST_F(ExodusPieces, ResultFilesFindOneFileOrEveryPiece) {
  EXPECT_TRUE(ddc::ExodusWriter::resultFiles(path("none.e")).empty());
  writePieces("r.e", 1);
  MPI_Barrier(MPI_COMM_WORLD);
  const auto files = ddc::ExodusWriter::resultFiles(path("r.e"));
  ASSERT_EQ(int(files.size()), ranks_);
  for (int r = 0; r < ranks_; ++r) EXPECT_EQ(files[size_t(r)], ddc::ExodusWriter::piecePath(path("r.e"), ranks_, r));
  EXPECT_EQ(ddc::ExodusWriter::piecePath("x.e", 12, 3), "x.e.12.03");
  EXPECT_EQ(ddc::ExodusWriter::piecePath("x.e", 9, 3), "x.e.9.3");
  MPI_Barrier(MPI_COMM_WORLD);
  if (ranks_ > 1 && rank_ == 0) {
    // An incomplete set of pieces is none.
    fs::remove(ddc::ExodusWriter::piecePath(path("r.e"), ranks_, ranks_ - 1));
    EXPECT_TRUE(ddc::ExodusWriter::resultFiles(path("r.e")).empty());
  }
}

TEST_F(ExodusPieces, ARestartCopiesStepsByIdBetweenOneFileAndPieces) {
  writePieces("r.e", 3);
  // Pieces into one file (a run continued with the whole mesh on rank 0).
  if (rank_ == 0) {
    Comm self = Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF));
    ddc::ExodusWriter w(self, path("w.e"), whole_, variables());
    const auto [copied, why] = w.copySteps(path("r.e"), 2);
    EXPECT_EQ(copied, 2);
    EXPECT_EQ(why, "");
    w.writeStep(3.0, stepValues(whole_, 3));
    w.close();
    expectSteps(path("w.e"), whole_, 3);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  // One file into pieces (a run continued on parts).
  {
    ddc::ExodusWriter w(comm_, path("p.e"), part_, variables());
    const auto [copied, why] = w.copySteps(path("w.e"), 3);
    EXPECT_EQ(copied, 3);
    EXPECT_EQ(why, "");
    w.close();
  }
  expectSteps(ddc::ExodusWriter::piecePath(path("p.e"), ranks_, rank_), part_, 3);
  // Fewer steps than asked: all there are, and why.
  {
    ddc::ExodusWriter w(comm_, path("q.e"), part_, variables());
    const auto [copied, why] = w.copySteps(path("r.e"), 5);
    EXPECT_EQ(copied, 3);
    EXPECT_NE(why.find("has 3 of the 5 steps before the checkpoint"), std::string::npos) << why;
  }
  // Other variables: none.
  {
    ddc::ExodusVariables other = variables();
    other.nodal.push_back("v");
    ddc::ExodusWriter w(comm_, path("o.e"), part_, other);
    const auto [copied, why] = w.copySteps(path("r.e"), 2);
    EXPECT_EQ(copied, 0);
    EXPECT_NE(why.find("has other variables or another mesh"), std::string::npos) << why;
  }
  // Missing: none, and why.
  {
    ddc::ExodusWriter w(comm_, path("m.e"), part_, variables());
    const auto [copied, why] = w.copySteps(path("missing.e"), 2);
    EXPECT_EQ(copied, 0);
    EXPECT_NE(why.find("no such file, nor its pieces"), std::string::npos) << why;
  }
}

}  // namespace
