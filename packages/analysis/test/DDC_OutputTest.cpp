// Output contract (DESIGN.md §4): staged output directory, history.csv, VTK
// XML time series. Runs on 1 and 2 ranks; every check that involves an error
// expects the same exception on every rank (and no hang).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultComm.hpp>

#include "DDC_Error.hpp"
#include "DDC_HistoryWriter.hpp"
#include "DDC_OutputDirectory.hpp"
#include "DDC_VtkWriter.hpp"

namespace fs = std::filesystem;
using ddc::HistoryWriter;
using ddc::OutputDirectory;
using ddc::VtkField;
using ddc::VtkPiece;
using ddc::VtkWriter;

namespace {

using Comm = Teuchos::RCP<const Teuchos::Comm<int>>;

Comm worldComm() { return Teuchos::DefaultComm<int>::getComm(); }

std::string readFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void writeFile(const fs::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text;
}

int countOccurrences(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1))
    ++n;
  return n;
}

/// Attribute value of the first element `<tag ... attr="value"` in `xml`.
std::string attribute(const std::string& xml, const std::string& tag, const std::string& attr) {
  std::smatch m;
  const std::regex re("<" + tag + "\\b[^>]*\\b" + attr + "=\"([^\"]*)\"");
  return std::regex_search(xml, m, re) ? m[1].str() : std::string("<missing>");
}

/// Numbers inside the DataArray whose opening tag contains `key` (e.g. Name="offsets").
std::vector<double> dataArray(const std::string& xml, const std::string& key,
                              std::string* openingTag = nullptr) {
  std::size_t pos = 0;
  while ((pos = xml.find("<DataArray", pos)) != std::string::npos) {
    const std::size_t close = xml.find('>', pos);
    const std::string tag = xml.substr(pos, close - pos + 1);
    if (tag.find(key) != std::string::npos) {
      if (openingTag) *openingTag = tag;
      const std::size_t end = xml.find("</DataArray>", close);
      std::istringstream in(xml.substr(close + 1, end - close - 1));
      std::vector<double> values;
      double v;
      while (in >> v) values.push_back(v);
      return values;
    }
    pos = close;
  }
  ADD_FAILURE() << "no DataArray with " << key;
  return {};
}

/// A per-test scratch directory, the same on every rank, removed afterwards.
class OutputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    comm_ = worldComm();
    std::string base;
    if (comm_->getRank() == 0) {
      const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
      base = (fs::temp_directory_path() /
              ("ddc_output_test_" + std::to_string(::getpid()) + "_" + info->name()))
                 .string();
      fs::remove_all(base);
      fs::create_directories(base);
    }
    int n = static_cast<int>(base.size());
    Teuchos::broadcast<int, int>(*comm_, 0, Teuchos::outArg(n));
    base.resize(n);
    Teuchos::broadcast<int, char>(*comm_, 0, n, &base[0]);
    base_ = base;
    comm_->barrier();
  }
  void TearDown() override {
    comm_->barrier();
    if (comm_->getRank() == 0) fs::remove_all(base_);
  }
  int rank() const { return comm_->getRank(); }
  int size() const { return comm_->getSize(); }

  Comm comm_;
  fs::path base_;
};

// ---------------------------------------------------------------- OutputDirectory

TEST_F(OutputTest, FirstErrorOnAnyRankAgrees) {
  EXPECT_EQ(ddc::firstErrorOnAnyRank(*comm_, ""), "");
  const std::string mine = rank() == size() - 1 ? "boom on last rank" : "";
  EXPECT_EQ(ddc::firstErrorOnAnyRank(*comm_, mine), "boom on last rank");
  const std::string all = "rank " + std::to_string(rank());
  EXPECT_EQ(ddc::firstErrorOnAnyRank(*comm_, all), "rank 0");
}

TEST_F(OutputTest, UncommittedRunLeavesEarlierResultsUntouched) {
  const fs::path final = base_ / "run";
  if (rank() == 0) {
    fs::create_directories(final);
    writeFile(final / "history.csv", "earlier results\n");
  }
  comm_->barrier();
  {
    OutputDirectory out(comm_, final.string());
    EXPECT_EQ(fs::path(out.path()), fs::path(final.string() + ".partial"));
    EXPECT_FALSE(out.committed());
    EXPECT_TRUE(fs::is_directory(out.path()));
    writeFile(fs::path(out.path()) / ("rank" + std::to_string(rank()) + ".txt"), "new\n");
    comm_->barrier();
    // The run "fails" here: no commit().
  }
  comm_->barrier();
  EXPECT_EQ(readFile(final / "history.csv"), "earlier results\n");
  EXPECT_FALSE(fs::exists(final / "rank0.txt"));
  // The staging directory stays for inspection.
  for (int r = 0; r < size(); ++r)
    EXPECT_TRUE(fs::exists(fs::path(final.string() + ".partial") / ("rank" + std::to_string(r) + ".txt")));
}

TEST_F(OutputTest, CommitReplacesEarlierResults) {
  const fs::path final = base_ / "deeper" / "run";  // parent created as needed
  if (rank() == 0) {
    fs::create_directories(final / "vtk");
    writeFile(final / "history.csv", "earlier results\n");
    writeFile(final / "vtk" / "stale.vtu", "stale\n");
  }
  comm_->barrier();
  OutputDirectory out(comm_, final.string() + "/");  // trailing separator is fine
  EXPECT_EQ(out.finalPath(), final.string());
  writeFile(fs::path(out.path()) / ("rank" + std::to_string(rank()) + ".txt"), "new\n");
  out.commit();
  EXPECT_TRUE(out.committed());
  EXPECT_EQ(out.path(), final.string());
  for (int r = 0; r < size(); ++r)
    EXPECT_EQ(readFile(final / ("rank" + std::to_string(r) + ".txt")), "new\n");
  EXPECT_FALSE(fs::exists(final / "history.csv"));
  EXPECT_FALSE(fs::exists(final / "vtk"));
  EXPECT_FALSE(fs::exists(final.string() + ".partial"));
  EXPECT_FALSE(fs::exists(final.string() + ".old"));
  EXPECT_NO_THROW(out.commit());  // second commit: no-op
}

TEST_F(OutputTest, CommitWithoutEarlierResultsAndStaleStagingIsCleared) {
  const fs::path final = base_ / "run";
  if (rank() == 0) {
    fs::create_directories(final.string() + ".partial");
    writeFile(fs::path(final.string() + ".partial") / "leftover.txt", "from a failed run\n");
  }
  comm_->barrier();
  OutputDirectory out(comm_, final.string());
  EXPECT_FALSE(fs::exists(fs::path(out.path()) / "leftover.txt"));
  out.commit();
  EXPECT_TRUE(fs::is_directory(final));
  EXPECT_TRUE(fs::is_empty(final));
}

TEST_F(OutputTest, ParentPathIsAFileRaisesInputErrorOnEveryRank) {
  if (rank() == 0) writeFile(base_ / "blocker", "a file, not a directory\n");
  comm_->barrier();
  const std::string bad = (base_ / "blocker" / "run").string();
  try {
    OutputDirectory out(comm_, bad);
    ADD_FAILURE() << "expected ddc::InputError";
  } catch (const ddc::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
  // Final directory itself is a file.
  EXPECT_THROW(OutputDirectory(comm_, (base_ / "blocker").string()), ddc::InputError);
  EXPECT_THROW(OutputDirectory(comm_, ""), ddc::InputError);
  EXPECT_EQ(readFile(base_ / "blocker"), "a file, not a directory\n");
}

// ---------------------------------------------------------------- HistoryWriter

TEST_F(OutputTest, HistoryHeaderIsExactlyTheDesignString) {
  {
    HistoryWriter h(comm_, base_.string(), HistoryWriter::standardColumns());
    EXPECT_EQ(h.path(), (base_ / "history.csv").string());
  }
  comm_->barrier();
  EXPECT_EQ(readFile(base_ / "history.csv"),
            "step,load_factor,strain_energy,newton_iterations,dual_iterations,active_contacts,"
            "contact_force_x,contact_force_y,contact_exchanges,wall_seconds\n");
}

TEST_F(OutputTest, HistoryRowsParseBackExactly) {
  std::vector<std::string> columns = HistoryWriter::standardColumns();
  columns.push_back("extra_column");
  const fs::path file = base_ / "h.csv";
  HistoryWriter h(comm_, file.string(), columns);
  const std::vector<std::vector<double>> rows = {
      {1, 0.1, 1.0 / 3.0, 5, 0, 12, -2.5e-7, 1e300, 3, 0.123456789012345678, -0.0},
      {2, 0.2, 4.9406564584124654e-324, 4, 117, 0, 6.02214076e23, -1.0 / 7.0, 0, 1.5, 12345678901.0}};
  for (const auto& r : rows) h.appendRow(r);
  EXPECT_EQ(h.numRows(), 2);
  // Flushed after every row: readable while the writer is still open.
  comm_->barrier();
  std::istringstream in(readFile(file));
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(countOccurrences(line, ","), static_cast<int>(columns.size()) - 1);
  for (const auto& r : rows) {
    ASSERT_TRUE(std::getline(in, line));
    std::istringstream fields(line);
    std::string field;
    std::size_t k = 0;
    while (std::getline(fields, field, ',')) {
      ASSERT_LT(k, r.size());
      EXPECT_EQ(std::strtod(field.c_str(), nullptr), r[k]) << "column " << columns[k] << ": " << field;
      ++k;
    }
    EXPECT_EQ(k, r.size());
  }
  EXPECT_FALSE(std::getline(in, line));
  EXPECT_EQ(HistoryWriter::formatValue(1.0), "1");
  EXPECT_EQ(HistoryWriter::formatValue(117.0), "117");
  EXPECT_EQ(HistoryWriter::formatValue(0.1), "0.10000000000000001");
}

TEST_F(OutputTest, HistoryErrorsAreRaisedOnEveryRank) {
  HistoryWriter h(comm_, (base_ / "h.csv").string(), {"step", "value"});
  EXPECT_THROW(h.appendRow({1.0}), std::invalid_argument);
  EXPECT_THROW(HistoryWriter(comm_, (base_ / "x.csv").string(), {"a", "a"}), ddc::InputError);
  EXPECT_THROW(HistoryWriter(comm_, (base_ / "x.csv").string(), {"a,b"}), ddc::InputError);
  if (rank() == 0) writeFile(base_ / "blocker", "file\n");
  comm_->barrier();
  EXPECT_THROW(HistoryWriter(comm_, (base_ / "blocker" / "history.csv").string(), {"step"}),
               ddc::InputError);
}

// ---------------------------------------------------------------- VtkWriter

/// A biquadratic quad (9 nodes, Gmsh = VTK order) and a linear quad next to it.
VtkPiece makePiece(int id, double shift) {
  VtkPiece p;
  p.id = id;
  const double xy[][2] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 0}, {2, 1}, {1, 2}, {0, 1}, {1, 1},
                          {3, 0}, {3, 2}};
  for (const auto& c : xy) {
    p.points.push_back(c[0] + shift);
    p.points.push_back(c[1]);
    p.points.push_back(0.0);
  }
  p.connectivity = {0, 1, 2, 3, 4, 5, 6, 7, 8, 1, 9, 10, 2};
  p.offsets = {9, 13};
  p.types = {28, 9};
  VtkField u{"displacement", 2, {}};
  for (int i = 0; i < p.numPoints(); ++i) {
    u.values.push_back(0.01 * i);
    u.values.push_back(-0.02 * i);
  }
  VtkField stress{"stress", 3, std::vector<double>(3 * p.numPoints(), 1.5)};
  p.pointData = {u, stress};
  p.cellData = {VtkField{"subdomain", 1, {double(id), double(id)}}};
  return p;
}

TEST_F(OutputTest, VtkWritesPiecesStepsAndSeries) {
  VtkWriter w(comm_, base_.string(), "solution.pvd");
  EXPECT_EQ(w.vtkDirectory(), (base_ / "vtk").string());
  // Rank 0 owns two pieces, the others one: variable counts per rank.
  std::vector<VtkPiece> pieces;
  if (rank() == 0) {
    pieces.push_back(makePiece(0, 0.0));
    pieces.push_back(makePiece(1, 3.0));
  } else {
    pieces.push_back(makePiece(rank() + 1, 3.0 * (rank() + 1)));
  }
  const int numPieces = size() + 1;
  w.writeStep(0, 0.0, pieces);
  w.writeStep(1, 0.25, pieces);
  w.writeStep(1, 0.5, pieces);  // same step again: replaces its entry
  comm_->barrier();

  const fs::path vtk = base_ / "vtk";
  for (int step = 0; step < 2; ++step) {
    const std::string pvtu = readFile(vtk / VtkWriter::pvtuFileName(step));
    EXPECT_EQ(countOccurrences(pvtu, "<Piece "), numPieces) << pvtu;
    for (int id = 0; id < numPieces; ++id) {
      EXPECT_TRUE(fs::exists(vtk / VtkWriter::vtuFileName(step, id)));
      EXPECT_NE(pvtu.find("Source=\"" + VtkWriter::vtuFileName(step, id) + "\""), std::string::npos);
    }
    EXPECT_NE(pvtu.find("Name=\"displacement\" NumberOfComponents=\"3\""), std::string::npos);
    EXPECT_NE(pvtu.find("Name=\"stress\" NumberOfComponents=\"3\""), std::string::npos);
    EXPECT_NE(pvtu.find("Name=\"subdomain\" NumberOfComponents=\"1\""), std::string::npos);
    EXPECT_NE(pvtu.find("type=\"PUnstructuredGrid\""), std::string::npos);
  }
  EXPECT_EQ(VtkWriter::vtuFileName(1, 2), "step_00001_piece_0002.vtu");
  EXPECT_EQ(VtkWriter::pvtuFileName(12), "step_00012.pvtu");

  const std::string pvd = readFile(w.pvdPath());
  EXPECT_EQ(w.pvdPath(), (vtk / "solution.pvd").string());
  EXPECT_EQ(countOccurrences(pvd, "<DataSet "), 2) << pvd;
  EXPECT_NE(pvd.find("timestep=\"0\" group=\"\" part=\"0\" file=\"step_00000.pvtu\""), std::string::npos) << pvd;
  EXPECT_NE(pvd.find("timestep=\"0.5\" group=\"\" part=\"0\" file=\"step_00001.pvtu\""), std::string::npos) << pvd;
  EXPECT_FALSE(fs::exists(w.pvdPath() + ".tmp"));
  ASSERT_EQ(w.steps().size(), 2u);

  // One .vtu, parsed as text.
  const std::string vtu = readFile(vtk / VtkWriter::vtuFileName(1, numPieces - 1));
  EXPECT_EQ(attribute(vtu, "VTKFile", "type"), "UnstructuredGrid");
  EXPECT_EQ(attribute(vtu, "Piece", "NumberOfPoints"), "11");
  EXPECT_EQ(attribute(vtu, "Piece", "NumberOfCells"), "2");
  EXPECT_EQ(countOccurrences(vtu, "<DataArray"), countOccurrences(vtu, "</DataArray>"));
  const VtkPiece ref = makePiece(numPieces - 1, 3.0 * (numPieces - 1));
  std::string tag;
  const std::vector<double> points = dataArray(vtu.substr(vtu.find("<Points>")), "<DataArray", &tag);
  EXPECT_EQ(points, ref.points);
  const std::vector<double> u = dataArray(vtu, "Name=\"displacement\"", &tag);
  EXPECT_NE(tag.find("NumberOfComponents=\"3\""), std::string::npos) << tag;
  ASSERT_EQ(u.size(), 3u * 11u);
  for (int i = 0; i < 11; ++i) {
    EXPECT_EQ(u[3 * i + 0], ref.pointData[0].values[2 * i + 0]);
    EXPECT_EQ(u[3 * i + 1], ref.pointData[0].values[2 * i + 1]);
    EXPECT_EQ(u[3 * i + 2], 0.0);
  }
  EXPECT_EQ(dataArray(vtu, "Name=\"stress\"").size(), 3u * 11u);
  EXPECT_EQ(dataArray(vtu, "Name=\"subdomain\""), std::vector<double>(2, double(numPieces - 1)));
  const std::vector<double> conn = dataArray(vtu, "Name=\"connectivity\"");
  EXPECT_EQ(conn, std::vector<double>(ref.connectivity.begin(), ref.connectivity.end()));
  EXPECT_EQ(dataArray(vtu, "Name=\"offsets\""), (std::vector<double>{9, 13}));
  EXPECT_EQ(dataArray(vtu, "Name=\"types\""), (std::vector<double>{28, 9}));
}

TEST_F(OutputTest, VtkRanksWithoutPiecesAreFine) {
  VtkWriter w(comm_, base_.string(), "series");  // ".pvd" appended
  EXPECT_EQ(w.pvdPath(), (base_ / "vtk" / "series.pvd").string());
  // Only the last rank has a piece: the declarations come from it.
  std::vector<VtkPiece> pieces;
  if (rank() == size() - 1) pieces.push_back(makePiece(7, 0.0));
  w.writeStep(3, 1.0, pieces);
  comm_->barrier();
  const std::string pvtu = readFile(base_ / "vtk" / "step_00003.pvtu");
  EXPECT_EQ(countOccurrences(pvtu, "<Piece "), 1);
  EXPECT_NE(pvtu.find("step_00003_piece_0007.vtu"), std::string::npos);
  EXPECT_NE(pvtu.find("Name=\"displacement\" NumberOfComponents=\"3\""), std::string::npos);
  EXPECT_TRUE(fs::exists(base_ / "vtk" / "series.pvd"));
}

TEST_F(OutputTest, VtkInvalidPiecesRaiseOnEveryRank) {
  VtkWriter w(comm_, base_.string());
  auto expectInvalid = [&](const std::vector<VtkPiece>& pieces, const std::string& fragment) {
    try {
      w.writeStep(0, 0.0, pieces);
      ADD_FAILURE() << "expected std::invalid_argument containing '" << fragment << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  const bool last = rank() == size() - 1;
  std::vector<VtkPiece> pieces{makePiece(rank(), 0.0)};
  if (last) pieces[0].points.pop_back();
  expectInvalid(pieces, "expected 3 per point");

  pieces = {makePiece(rank(), 0.0)};
  if (last) pieces[0].pointData[0].values.pop_back();
  expectInvalid(pieces, "point field 'displacement' has 21 values, expected 2 components x 11 points = 22");

  pieces = {makePiece(rank(), 0.0)};
  if (last) pieces[0].connectivity[3] = 11;
  expectInvalid(pieces, "connectivity[3] = 11");

  pieces = {makePiece(rank(), 0.0)};
  if (last) pieces[0].offsets = {8, 13};
  expectInvalid(pieces, "cell 0 (VTK type 28) has 8 nodes");

  pieces = {makePiece(rank(), 0.0)};
  if (last) pieces[0].types[1] = 42;
  expectInvalid(pieces, "unsupported VTK cell type 42");

  pieces = {makePiece(rank(), 0.0), makePiece(rank(), 0.0)};
  expectInvalid(pieces, "piece id given twice");

  if (size() > 1) {
    pieces = {makePiece(0, 0.0)};  // the same id on every rank
    expectInvalid(pieces, "piece id 0 is used on more than one rank");
    pieces = {makePiece(rank(), 0.0)};
    if (last) pieces[0].cellData[0].name = "rank";
    expectInvalid(pieces, "fields differ from those of the pieces on rank 0");
  }
  // Nothing was written for the failed step.
  comm_->barrier();
  EXPECT_FALSE(fs::exists(base_ / "vtk" / "step_00000.pvtu"));
  EXPECT_FALSE(fs::exists(w.pvdPath()));
}

TEST_F(OutputTest, VtkDirectoryErrorRaisesInputErrorOnEveryRank) {
  if (rank() == 0) writeFile(base_ / "blocker", "file\n");
  comm_->barrier();
  EXPECT_THROW(VtkWriter(comm_, (base_ / "blocker").string()), ddc::InputError);
  EXPECT_THROW(VtkWriter(comm_, base_.string(), "sub/dir.pvd"), ddc::InputError);
}

}  // namespace
