// Checkpoint files (DDC_Checkpoint.hpp): sections round-trip bit for bit, a
// distributed vector reads back on another number of ranks, and a file that
// is not a checkpoint, truncated or corrupted is refused on every rank with
// a message naming it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "DDC_Checkpoint.hpp"
#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_TestErrors.hpp"

namespace {

using ddc::GO;
using ::testing::HasSubstr;

Teuchos::RCP<const Teuchos::Comm<int>> world() { return Tpetra::getDefaultComm(); }

/// A map of 7 entries per rank with global indices 3 g + 1 (not contiguous),
/// entries of rank r on rank r.
Teuchos::RCP<const ddc::Map> spreadMap(const Teuchos::RCP<const Teuchos::Comm<int>>& comm, int ranksOfData) {
  std::vector<GO> gids;
  for (int r = 0; r < ranksOfData; ++r)
    if (comm->getSize() == 1 || r == comm->getRank())
      for (int i = 0; i < 7; ++i) gids.push_back(GO(3 * (7 * r + i) + 1));
  return Teuchos::rcp(new ddc::Map(Tpetra::global_size_t(7 * ranksOfData), Teuchos::ArrayView<const GO>(gids), 0, comm));
}

/// Values whose bits a text round trip would not keep.
double valueOf(GO gid) { return std::sin(double(gid)) / 3.0 + 1e-300 * double(gid); }

std::string fileName(const std::string& what) {
  return "checkpoint_test_" + what + "_np" + std::to_string(world()->getSize()) + ".ckpt";
}

void writeSample(const std::string& path) {
  auto comm = world();
  ddc::Vector v(spreadMap(comm, comm->getSize()));
  {
    auto d = v.getDataNonConst();
    for (size_t l = 0; l < v.getLocalLength(); ++l) d[l] = valueOf(v.getMap()->getGlobalElement(ddc::LO(l)));
  }
  ddc::CheckpointWriter w(comm);
  w.putBytes("parameters", std::string("<ParameterList/>\0binary", 23));
  w.putDoubles("scalars", {0.1, -2.5e-310, 1.0 / 3.0});
  w.putVector("u", v);
  w.write(path);
}

TEST(Checkpoint, SectionsRoundTripBitForBit) {
  const std::string path = fileName("roundtrip");
  writeSample(path);
  ddc::CheckpointReader r(world(), path);
  EXPECT_TRUE(r.has("u"));
  EXPECT_FALSE(r.has("v"));
  EXPECT_EQ(r.bytes("parameters"), std::string("<ParameterList/>\0binary", 23));
  const auto s = r.doubles("scalars");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0], 0.1);
  EXPECT_EQ(s[1], -2.5e-310);
  EXPECT_EQ(s[2], 1.0 / 3.0);
  ddc::Vector v(spreadMap(world(), world()->getSize()));
  r.vector("u", v);
  auto d = v.getData();
  for (size_t l = 0; l < v.getLocalLength(); ++l) EXPECT_EQ(d[l], valueOf(v.getMap()->getGlobalElement(ddc::LO(l))));
  // A section that is not there names itself and the file.
  const std::string err = ddc::test::inputErrorOf([&] { r.bytes("nope"); });
  EXPECT_THAT(err, HasSubstr("the checkpoint '" + path + "' has no section 'nope'"));
}

TEST(Checkpoint, AVectorReadsBackOnAnotherNumberOfRanks) {
  // Written on every rank, read by rank 0 alone (a communicator of its own)
  // into a map that holds every entry.
  const std::string path = fileName("ranks");
  writeSample(path);
  const int written = world()->getSize();
  auto self = world()->split(world()->getRank() == 0 ? 0 : 1, 0);
  if (world()->getRank() == 0) {
    ddc::CheckpointReader r(self, path);
    ddc::Vector v(spreadMap(self, written));
    EXPECT_EQ(v.getLocalLength(), size_t(7 * written));
    r.vector("u", v);
    auto d = v.getData();
    for (size_t l = 0; l < v.getLocalLength(); ++l)
      EXPECT_EQ(d[l], valueOf(v.getMap()->getGlobalElement(ddc::LO(l))));
    // A map with an index the vector does not have: a checkpoint of another model.
    std::vector<GO> more = {GO(2)};
    ddc::Vector w(Teuchos::rcp(new ddc::Map(1, Teuchos::ArrayView<const GO>(more), 0, self)));
    EXPECT_THAT(ddc::test::inputErrorOf([&] { r.vector("u", w); }), HasSubstr("has no entry 2"));
  }
  world()->barrier();
}

/// Rewrite the file on rank 0 with `edit` applied to its bytes.
void editFile(const std::string& path, const std::function<void(std::string&)>& edit) {
  if (world()->getRank() == 0) {
    std::ifstream in(path, std::ios::binary);
    std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    edit(s);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << s;
  }
  world()->barrier();
}

TEST(Checkpoint, ACorruptedFileIsRefusedOnEveryRank) {
  const std::string path = fileName("corrupted");
  writeSample(path);
  editFile(path, [](std::string& s) { s[s.size() / 2] ^= 0x10; });
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::CheckpointReader(world(), path); }),
              HasSubstr("the checkpoint '" + path + "' is corrupted or truncated"));
}

TEST(Checkpoint, ATruncatedFileIsRefusedOnEveryRank) {
  const std::string path = fileName("truncated");
  writeSample(path);
  editFile(path, [](std::string& s) { s.resize(s.size() - 20); });
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::CheckpointReader(world(), path); }),
              HasSubstr("the checkpoint '" + path + "' is corrupted or truncated"));
}

TEST(Checkpoint, AnotherFileOrNoneIsRefused) {
  const std::string path = fileName("other");
  if (world()->getRank() == 0) std::ofstream(path) << "step,load_factor\n1,0.1\n";
  world()->barrier();
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::CheckpointReader(world(), path); }),
              HasSubstr("'" + path + "' is not a DDContact checkpoint (version 1)"));
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::CheckpointReader(world(), "/nonexistent/run.ckpt"); }),
              HasSubstr("cannot read the checkpoint '/nonexistent/run.ckpt'"));
}

TEST(Checkpoint, AFailedWriteLeavesTheEarlierCheckpoint) {
  const std::string path = fileName("kept");
  writeSample(path);
  // The temporary file of the atomic write cannot be created (a directory
  // holds its name): the write fails and the earlier checkpoint stays.
  if (world()->getRank() == 0) std::filesystem::create_directory(path + ".tmp");
  world()->barrier();
  ddc::CheckpointWriter w(world());
  w.putDoubles("scalars", {1.0});
  EXPECT_THROW(w.write(path), ddc::OutputError);
  ddc::CheckpointReader r(world(), path);
  EXPECT_EQ(r.doubles("scalars").size(), 3u) << "the earlier checkpoint was replaced";
  if (world()->getRank() == 0) std::filesystem::remove(path + ".tmp");
  EXPECT_THROW(w.putDoubles("scalars", {2.0}), std::invalid_argument) << "a section given twice";
}

}  // namespace
