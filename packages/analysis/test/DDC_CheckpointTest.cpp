// Checkpoint files (DDC_Checkpoint.hpp): sections round-trip bit for bit, a
// distributed vector reads back on another number of ranks, each rank writes
// its own piece of it, a version 1 file still reads, and a file that is not
// a checkpoint, truncated or corrupted (in any piece) is refused on every
// rank with a message naming it. What a restart checks: contact slots round-trip
// bit for bit (packSlots()), a deck may change only the parameters
// restartChangeableParameters() names, the files a run read must be
// unchanged, the final load factor not below the checkpoint's, and a
// checkpoint of an older layout or of other contact slots is refused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "DDC_Checkpoint.hpp"
#include "DDC_ContactComponent.hpp"
#include "DDC_Restart.hpp"
#include "DDC_RunCheckpoint.hpp"
#include "DDC_Error.hpp"
#include "DDC_FileFingerprint.hpp"
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

/// The vector table of the sample's section "u" (version 2): the entry
/// count of each piece, read from the file's bytes.
std::vector<std::uint64_t> pieceCounts(const std::string& bytes) {
  const std::string magic = "DDContact checkpoint 2\n";
  if (bytes.compare(0, magic.size(), magic) != 0) return {};
  size_t at = magic.size() + 8;  // the section count
  auto take = [&](size_t n) {
    std::uint64_t v = 0;
    std::memcpy(&v, bytes.data() + at, n);
    at += n;
    return v;
  };
  for (int k = 0; k < 3; ++k) {
    const std::uint64_t nameLength = take(4);
    const std::string name = bytes.substr(at, nameLength);
    at += nameLength;
    const std::uint64_t kind = take(1), length = take(8);
    if (kind == 0) {
      at += length;
      continue;
    }
    std::vector<std::uint64_t> counts;
    for (std::uint64_t p = 0; p < length; ++p) counts.push_back(take(8));
    if (name == "u") return counts;
  }
  return {};
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(Checkpoint, EachRankWritesItsOwnPiece) {
  // No rank gathers a vector: the file holds one piece per writing rank,
  // of that rank's 7 entries.
  const std::string path = fileName("pieces");
  writeSample(path);
  const std::vector<std::uint64_t> counts = pieceCounts(fileBytes(path));
  EXPECT_EQ(counts, std::vector<std::uint64_t>(size_t(world()->getSize()), 7u));
}

TEST(Checkpoint, ACorruptedPieceIsRefusedOnEveryRank) {
  // A changed byte in the last entry of the last piece: only the rank
  // reading that piece can see it; every rank refuses the file.
  const std::string path = fileName("piece");
  writeSample(path);
  editFile(path, [](std::string& s) { s[s.size() - 8 - 3] ^= 0x01; });  // before the 8-byte trailer
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::CheckpointReader(world(), path); }),
              HasSubstr("the checkpoint '" + path + "' is corrupted or truncated"));
}

TEST(Checkpoint, ACorruptedLengthIsRefusedBeforeAllocatingIt) {
  // The first section's name length set to 4 GiB - 1 (and later a vector
  // table of 2^60 pieces): refused as corrupted, without allocating it.
  const std::string path = fileName("length");
  writeSample(path);
  editFile(path, [](std::string& s) { std::memset(&s[23 + 8], 0xff, 4); });
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::CheckpointReader(world(), path); }),
              HasSubstr("the checkpoint '" + path + "' is corrupted or truncated"));
  writeSample(path);
  editFile(path, [](std::string& s) {
    // The section "u": its name length (u32 1), its name, kind 1, the pieces.
    const size_t u = s.find(std::string("\x01\0\0\0u\x01", 6));
    ASSERT_NE(u, std::string::npos);
    const std::uint64_t pieces = std::uint64_t(1) << 60;
    std::memcpy(&s[u + 6], &pieces, 8);
  });
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::CheckpointReader(world(), path); }),
              HasSubstr("the checkpoint '" + path + "' is corrupted or truncated"));
}

TEST(Checkpoint, AVersion1FileStillReads) {
  // A checkpoint of the earlier format (one hash over the whole file, each
  // vector one sorted section) reads back on any number of ranks.
  const std::string path = fileName("version1");
  const int n = 5;
  if (world()->getRank() == 0) {
    auto put = [](std::string& out, auto v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); };
    std::string out = "DDContact checkpoint 1\n";
    put(out, std::uint64_t(2));
    put(out, std::uint32_t(7));
    out += "scalars";
    put(out, std::uint64_t(8));
    put(out, 0.25);
    put(out, std::uint32_t(1));
    out += "u";
    put(out, std::uint64_t(16 * n));
    for (int i = 0; i < n; ++i) put(out, (long long)(3 * i + 1)), put(out, valueOf(3 * i + 1));
    put(out, ddc::fnv1a(out.data(), out.size()));
    std::ofstream(path, std::ios::binary | std::ios::trunc) << out;
  }
  world()->barrier();
  ddc::CheckpointReader r(world(), path);
  EXPECT_EQ(r.doubles("scalars"), std::vector<double>{0.25});
  // Index 3 i + 1 on rank i % P.
  std::vector<GO> gids;
  for (int i = 0; i < n; ++i)
    if (i % world()->getSize() == world()->getRank()) gids.push_back(GO(3 * i + 1));
  ddc::Vector v(Teuchos::rcp(new ddc::Map(Tpetra::global_size_t(n), Teuchos::ArrayView<const GO>(gids), 0, world())));
  r.vector("u", v);
  auto d = v.getData();
  for (size_t l = 0; l < v.getLocalLength(); ++l) EXPECT_EQ(d[l], valueOf(v.getMap()->getGlobalElement(ddc::LO(l))));
}

TEST(Checkpoint, ContactSlotsRoundTripBitForBit) {
  ddc::ContactSlot a;
  a.pair = 2;
  a.slaveNode = 4711;
  for (int i = 0; i < ddc::ContactSlot::kMaxFacetNodes; ++i) a.master[i] = 100 + i;
  a.numMaster = 9;
  a.segment = 17;
  a.masterElement = 3;
  a.active = true;
  a.state.active = true;
  a.state.multiplier = -std::nextafter(1.0 / 3.0, 1.0);
  a.state.frozenXi = 0.1;
  a.state.frozenNormal = {0.6, -0.8};
  a.frozen.xi = {{-0.25, 1.0 / 7.0}};
  a.frozen.normal = {0.0, std::sqrt(0.5), -std::sqrt(0.5)};
  a.gap = -1e-300;
  a.normal = {1e-17, 2.0, -3.0};
  a.tributaryLength = 0.125;
  a.tangent = {Eigen::Vector3d(0.6, 0.8, 0.0), Eigen::Vector3d(0.0, 0.0, -1.0)};
  a.frozen.tangent = {Eigen::Vector3d(1.0 / 3.0, 0.0, 1e-320), Eigen::Vector3d(-0.0, 1.0, 0.0)};
  a.tangential = {-std::nextafter(0.1, 1.0), 3e-17};
  a.friction = ddc::FrictionState::Slip;
  a.tangentialSlip = {1e-9, -2.5e-7};
  a.slip = std::hypot(1e-9, -2.5e-7);
  ddc::ContactSlot b;  // unpaired, defaults
  const auto back = ddc::unpackSlots(ddc::packSlots({a, b}));
  ASSERT_EQ(back.size(), 2u);
  const ddc::ContactSlot& c = back[0];
  EXPECT_EQ(c.pair, a.pair);
  EXPECT_EQ(c.slaveNode, a.slaveNode);
  EXPECT_EQ(c.master, a.master);
  EXPECT_EQ(c.numMaster, a.numMaster);
  EXPECT_EQ(c.segment, a.segment);
  EXPECT_EQ(c.masterElement, a.masterElement);
  EXPECT_EQ(c.active, a.active);
  EXPECT_EQ(c.state.active, a.state.active);
  EXPECT_EQ(c.state.multiplier, a.state.multiplier);
  EXPECT_EQ(c.state.frozenXi, a.state.frozenXi);
  EXPECT_EQ(c.state.frozenNormal, a.state.frozenNormal);
  EXPECT_EQ(c.frozen.xi, a.frozen.xi);
  EXPECT_EQ(c.frozen.normal, a.frozen.normal);
  EXPECT_EQ(c.gap, a.gap);
  EXPECT_EQ(c.normal, a.normal);
  EXPECT_EQ(c.tributaryLength, a.tributaryLength);
  EXPECT_EQ(c.tangent, a.tangent);
  EXPECT_EQ(c.frozen.tangent, a.frozen.tangent);
  EXPECT_EQ(c.tangential, a.tangential);
  EXPECT_EQ(c.friction, a.friction);
  EXPECT_EQ(c.tangentialSlip, a.tangentialSlip);
  EXPECT_EQ(c.slip, a.slip);
  EXPECT_EQ(back[1].friction, ddc::FrictionState::Open);
  EXPECT_FALSE(back[1].paired());
  EXPECT_EQ(back[1].slaveNode, -1);
  EXPECT_THROW(ddc::unpackSlots(std::vector<double>(31, 0.0)), std::invalid_argument);
  EXPECT_THROW(ddc::unpackSlots(std::vector<double>(30, 0.0)), std::invalid_argument) << "the frictionless layout";
}

// A checkpoint of another model's contact slots (only a host code or an
// edited file gets past the deck and input-file checks to here): another
// slot count, another slave node or pair in a slot, another number of slots
// read; each names the checkpoint.
TEST(Restart, ACheckpointOfOtherContactSlotsIsRefused) {
  const std::string file = "run/checkpoint.ddc";
  const std::string message = "checkpoint 'run/checkpoint.ddc': its contact slave nodes are not this model's";
  std::vector<ddc::ContactSlot> now(3);
  for (int k = 0; k < 3; ++k) {
    now[k].pair = k / 2;
    now[k].slaveNode = 10 + k;
  }
  EXPECT_NO_THROW(ddc::requireContactSlotCount({3.0}, now.size(), file));
  EXPECT_NO_THROW(ddc::requireSameContactSlots(now, now, file));
  for (const std::vector<double>& count : {std::vector<double>{4.0}, std::vector<double>{}, std::vector<double>{3.0, 3.0}})
    EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::requireContactSlotCount(count, now.size(), file); }),
                HasSubstr(message));
  auto node = now;
  node[2].slaveNode = 11;
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::requireSameContactSlots(node, now, file); }), HasSubstr(message));
  auto pair = now;
  pair[1].pair = 1;
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::requireSameContactSlots(pair, now, file); }), HasSubstr(message));
  const std::vector<ddc::ContactSlot> fewer(now.begin(), now.end() - 1);
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::requireSameContactSlots(fewer, now, file); }), HasSubstr(message));
}

TEST(Restart, ADeckMayChangeOnlyTheStepsTheSolutionMethodAndTheOutput) {
  Teuchos::ParameterList saved;
  saved.sublist("Load Stepping").set("Number of Steps", 10);
  saved.sublist("Dynamics").set("Integrator", std::string("None"));
  saved.sublist("Dynamics").set("Time Step", 0.1);
  saved.sublist("Solver").sublist("FETI-DP").set("Preconditioner", std::string("Dirichlet"));
  saved.sublist("Contact").set("Penetration Tolerance", 1e-6);
  saved.sublist("Boundary Conditions").sublist("Fix").set("Set", std::string("Block/left"));
  saved.sublist("Output").set("VTK", true);
  const std::string file = "run/checkpoint.ddc";
  // Allowed: steps, time step, solver, output (also sublists added there).
  Teuchos::ParameterList now = saved;
  now.sublist("Load Stepping").set("Number of Steps", 40);
  now.sublist("Dynamics").set("Time Step", 0.05);
  now.sublist("Solver").sublist("FETI-DP").set("Preconditioner", std::string("Lumped"));
  now.sublist("Solver").sublist("Linear Solver").set("Type", std::string("Amesos2"));
  now.sublist("Output").set("VTK", false);
  EXPECT_NO_THROW(ddc::checkRestartParameters(saved, now, file));
  // Not allowed: each names the parameter, both values and the checkpoint.
  Teuchos::ParameterList contact = saved;
  contact.sublist("Contact").set("Penetration Tolerance", 2e-6);
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::checkRestartParameters(saved, contact, file); }),
              HasSubstr("parameter 'Contact/Penetration Tolerance' is '2e-06' in this deck but was '1e-06' in the "
                        "run that wrote the checkpoint 'run/checkpoint.ddc'"));
  Teuchos::ParameterList integrator = saved;
  integrator.sublist("Dynamics").set("Integrator", std::string("Newmark"));
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::checkRestartParameters(saved, integrator, file); }),
              HasSubstr("parameter 'Dynamics/Integrator' is 'Newmark'"));
  Teuchos::ParameterList added = saved;
  added.sublist("Boundary Conditions").sublist("Push").set("Set", std::string("Block/right"));
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::checkRestartParameters(saved, added, file); }),
              HasSubstr("parameter 'Boundary Conditions/Push' is a sublist in this deck but was (none)"));
  Teuchos::ParameterList removed = saved;
  removed.sublist("Boundary Conditions").remove("Fix");
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::checkRestartParameters(saved, removed, file); }),
              HasSubstr("parameter 'Boundary Conditions/Fix' is (none) in this deck but was a sublist"));
}

TEST(Restart, AFileTheRunReadMustBeUnchanged) {
  const std::vector<ddc::InputFileIdentity> read = {{"Mesh/Bodies/Block/Gmsh/File", "decks/block.msh", 967, 12345},
                                                    {"Partition/Element Map File", "decks/block.map", 219, 678}};
  const std::string saved = ddc::describeInputFiles(read);
  const std::string file = "run/checkpoint.ddc";
  EXPECT_NO_THROW(ddc::checkRestartInputFiles(saved, read, file));
  // The same size, other content; another size: each names the file, its parameter and the checkpoint.
  auto content = read;
  content[0].hash = 12346;
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::checkRestartInputFiles(saved, content, file); }),
              HasSubstr("restart: the file 'decks/block.msh' ('Mesh/Bodies/Block/Gmsh/File') changed since the run "
                        "that wrote the checkpoint 'run/checkpoint.ddc' read it (then 967 bytes, now 967 bytes with "
                        "other content)"));
  auto size = read;
  size[1].size = 220;
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::checkRestartInputFiles(saved, size, file); }),
              HasSubstr("the file 'decks/block.map' ('Partition/Element Map File') changed since the run that wrote "
                        "the checkpoint 'run/checkpoint.ddc' read it (then 219 bytes, now 220 bytes)"));
}

TEST(Restart, TheFinalValueMayNotLieBelowTheCheckpoints) {
  ddc::StepRecord last;
  last.step = 3;
  last.loadFactor = 0.5;
  ddc::StepLoopSettings settings;
  settings.finalValue = 0.5;
  EXPECT_NO_THROW(ddc::checkRestartFinalValue(last, settings, "run/checkpoint.ddc"));
  settings.finalValue = 0.4;
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::checkRestartFinalValue(last, settings, "run/checkpoint.ddc"); }),
              HasSubstr("restart: 'Load Stepping/Final Load Factor' = 0.4 lies below the load factor 0.5 the "
                        "checkpoint 'run/checkpoint.ddc' reached (step 3)"));
  settings.stepping = "Dynamics";
  settings.factorName = "time";
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::checkRestartFinalValue(last, settings, "run/checkpoint.ddc"); }),
              HasSubstr("'Dynamics/Final Time' = 0.4 lies below the time 0.5"));
}

TEST(Restart, ACheckpointOfAnOlderLayoutIsRefused) {
  const std::string path = fileName("layout2");
  ddc::CheckpointWriter w(world());
  w.putDoubles("run", {2.0, 1.0, 0.0, 0.0});  // layout 2: no record of the files the run read
  w.write(path);
  const ddc::CheckpointReader c(world(), path);
  EXPECT_THAT(ddc::test::inputErrorOf([&] { ddc::requireCheckpointLayout(c); }),
              HasSubstr("checkpoint '" + path + "': written by another version of DDContact (layout 2, which does "
                        "not record the mesh and element-map files the run read"));
  world()->barrier();
  if (world()->getRank() == 0) std::remove(path.c_str());
}

}  // namespace
