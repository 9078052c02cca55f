// Output contract (doc/user-guide.md, "The output directory"): staged output
// directory, history.csv, VTK
// XML time series. Runs on 1 and 2 ranks; every check that involves an error
// expects the same exception on every rank (and no hang).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultComm.hpp>

#include "DDC_Error.hpp"
#include "DDC_HistoryWriter.hpp"
#include "DDC_OutputDirectory.hpp"
#include "DDC_ResultFile.hpp"
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

  /// A committed DDContact result in `final` holding `files` (relative path
  /// -> content), written by rank 0.
  void makeResult(const fs::path& final, const std::vector<std::pair<std::string, std::string>>& files) {
    OutputDirectory out(comm_, final.string());
    if (rank() == 0)
      for (const auto& [rel, text] : files) {
        fs::create_directories((fs::path(out.path()) / rel).parent_path());
        writeFile(fs::path(out.path()) / rel, text);
      }
    out.commit();
  }

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
  makeResult(final, {{"history.csv", "earlier results\n"}});
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
  makeResult(final, {{"history.csv", "earlier results\n"}, {"vtk/stale.vtu", "stale\n"}});
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
  {
    // A run that failed: its staging directory stays behind.
    OutputDirectory failed(comm_, final.string());
    if (rank() == 0) writeFile(fs::path(failed.path()) / "leftover.txt", "from a failed run\n");
    comm_->barrier();
  }
  OutputDirectory out(comm_, final.string());
  EXPECT_FALSE(fs::exists(fs::path(out.path()) / "leftover.txt"));
  ASSERT_EQ(out.recoveryNotes().size(), 1u);  // said, not silent
  EXPECT_NE(out.recoveryNotes()[0].find("did not finish"), std::string::npos) << out.recoveryNotes()[0];
  out.commit();
  EXPECT_TRUE(fs::is_directory(final));
  // Nothing was written but the manifest that marks the result as DDContact's.
  std::vector<std::string> entries;
  for (const auto& e : fs::directory_iterator(final)) entries.push_back(e.path().filename().string());
  EXPECT_EQ(entries, std::vector<std::string>{OutputDirectory::manifestFileName()});
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

// The mark of a result, recovery from interrupted commits, the run lock
// (doc/user-guide.md, "The output directory").

/// Every regular file below `dir` with its content, for before/after checks.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> out;
  if (!fs::exists(dir)) return out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out[e.path().lexically_relative(dir).string()] = readFile(e.path());
  return out;
}

std::string manifestStatus(const fs::path& dir) {
  const std::string m = readFile(dir / OutputDirectory::manifestFileName());
  const auto pos = m.rfind("status: ");
  return pos == std::string::npos ? std::string("<none>") : m.substr(pos + 8, m.find('\n', pos) - pos - 8);
}

TEST_F(OutputTest, ForeignDirectoryIsNeverRemovedOrReplaced) {
  const fs::path mine = base_ / "mine";
  if (rank() == 0) {
    fs::create_directories(mine / "notes");
    writeFile(mine / "thesis.tex", "two years of work\n");
    writeFile(mine / "notes" / "a.txt", "a\n");
  }
  comm_->barrier();
  const auto before = snapshot(mine);
  // Directly, and through a path that only resolves to it ("mine/notes/..").
  for (const std::string path : {mine.string(), (mine / "notes" / "..").string(), mine.string() + "/"}) {
    try {
      OutputDirectory out(comm_, path);
      ADD_FAILURE() << "expected ddc::InputError for " << path;
    } catch (const ddc::InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("'" + mine.string() + "' exists and was not written by ddcontact"), std::string::npos) << what;
      EXPECT_NE(what.find("choose another --output-dir"), std::string::npos) << what;
    }
  }
  comm_->barrier();
  EXPECT_EQ(snapshot(mine), before);
  EXPECT_FALSE(fs::exists(mine.string() + ".partial"));
  EXPECT_FALSE(fs::exists(mine.string() + ".lock"));  // the lock is released on failure
}

TEST_F(OutputTest, ForeignStagingOrOldDirectoryIsNeverRemoved) {
  const fs::path final = base_ / "run";
  for (const char* suffix : {".partial", ".old"}) {
    const fs::path other = final.string() + suffix;
    if (rank() == 0) {
      fs::create_directories(other);
      writeFile(other / "keep.txt", "not ddcontact's\n");
    }
    comm_->barrier();
    try {
      OutputDirectory out(comm_, final.string());
      ADD_FAILURE() << "expected ddc::InputError for a foreign " << suffix;
    } catch (const ddc::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("'" + other.string() + "' exists and was not written by ddcontact"),
                std::string::npos)
          << e.what();
    }
    comm_->barrier();
    EXPECT_EQ(readFile(other / "keep.txt"), "not ddcontact's\n");
    comm_->barrier();  // every rank has read it before rank 0 cleans up
    if (rank() == 0) fs::remove_all(other);
    comm_->barrier();
  }
}

TEST_F(OutputTest, EarlierResultWithForeignFilesIsRefused) {
  const fs::path final = base_ / "run";
  makeResult(final, {{"history.csv", "earlier\n"}});
  if (rank() == 0) writeFile(final / "my_plot.png", "user's plot\n");
  comm_->barrier();
  const auto before = snapshot(final);
  try {
    OutputDirectory out(comm_, final.string());
    ADD_FAILURE() << "expected ddc::InputError";
  } catch (const ddc::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("holds files DDContact did not write: '" + (final / "my_plot.png").string()),
              std::string::npos)
        << e.what();
  }
  comm_->barrier();
  EXPECT_EQ(snapshot(final), before);
}

/// The InputError message of opening `final` as an output directory, "" if
/// there is none.
std::string refusalOf(const Comm& comm, const fs::path& final) {
  try {
    OutputDirectory out(comm, final.string());
  } catch (const ddc::InputError& e) {
    return e.what();
  }
  return "";
}

TEST_F(OutputTest, EarlierResultWithAnEditedFileOrAnAddedDirectoryIsRefused) {
  const fs::path final = base_ / "run";
  makeResult(final, {{"history.csv", "earlier\n"}, {"vtk/a.vtu", "abc"}});
  const std::string m = readFile(final / OutputDirectory::manifestFileName());
  EXPECT_NE(m.find("\nfnv1a64: "), std::string::npos) << m;
  EXPECT_NE(m.find("\ndir: vtk\n"), std::string::npos) << m;
  // The same size, other content: the user's file now.
  if (rank() == 0) writeFile(final / "history.csv", "edited!\n");
  comm_->barrier();
  auto before = snapshot(final);
  EXPECT_NE(refusalOf(comm_, final).find("'" + (final / "history.csv").string() +
                                         "' changed since DDContact wrote it"),
            std::string::npos);
  comm_->barrier();
  EXPECT_EQ(snapshot(final), before);
  comm_->barrier();  // every rank has looked before rank 0 changes it again
  // A directory added.
  if (rank() == 0) {
    writeFile(final / "history.csv", "earlier\n");
    fs::create_directory(final / "mine");
  }
  comm_->barrier();
  before = snapshot(final);
  EXPECT_NE(refusalOf(comm_, final).find("'" + (final / "mine").string() + "/' is a directory DDContact did not make"),
            std::string::npos);
  comm_->barrier();
  EXPECT_EQ(snapshot(final), before);
  EXPECT_TRUE(fs::is_directory(final / "mine"));
}

TEST_F(OutputTest, AStagingDirectoryMarkedResumableIsKept) {
  const fs::path final = base_ / "run";
  {
    OutputDirectory stopped(comm_, final.string());
    if (rank() == 0) writeFile(fs::path(stopped.path()) / "checkpoint.ddc", "state\n");
    comm_->barrier();
    stopped.markResumable("checkpoint.ddc");
  }
  const fs::path staging = final.string() + ".partial";
  EXPECT_NE(readFile(staging / OutputDirectory::manifestFileName()).find("\nresumable: checkpoint.ddc\n"),
            std::string::npos);
  const auto before = snapshot(staging);
  EXPECT_NE(refusalOf(comm_, final).find("'" + staging.string() +
                                         "' is the staging directory of an earlier run that did not finish "
                                         "and holds its checkpoint"),
            std::string::npos);
  comm_->barrier();
  EXPECT_EQ(snapshot(staging), before);
  comm_->barrier();
  // Continuing it (a restart into the same directory) keeps and reuses it.
  ddc::RunDescription restart;
  restart.resumeWith = "checkpoint.ddc";
  OutputDirectory continued(comm_, final.string(), restart);
  EXPECT_EQ(readFile(fs::path(continued.path()) / "checkpoint.ddc"), "state\n");
}

TEST_F(OutputTest, EmptyDirectoryMayBeUsed) {
  const fs::path final = base_ / "empty";
  if (rank() == 0) fs::create_directories(final);
  comm_->barrier();
  OutputDirectory out(comm_, final.string());
  if (rank() == 0) writeFile(fs::path(out.path()) / "history.csv", "new\n");
  out.commit();
  EXPECT_EQ(readFile(final / "history.csv"), "new\n");
  EXPECT_EQ(manifestStatus(final), "complete");
}

TEST_F(OutputTest, ManifestListsEveryFileOfACommittedResult) {
  const fs::path final = base_ / "run";
  makeResult(final, {{"history.csv", "1,2\n"}, {"vtk/a.vtu", "abc"}});
  const std::string m = readFile(final / OutputDirectory::manifestFileName());
  EXPECT_EQ(m.rfind("ddcontact-result 1\n", 0), 0u) << m;
  EXPECT_NE(m.find("\nfile: 4 history.csv\n"), std::string::npos) << m;
  EXPECT_NE(m.find("\nfile: 3 vtk/a.vtu\n"), std::string::npos) << m;
  EXPECT_NE(m.find("\nprogram: ddcontact "), std::string::npos) << m;
  EXPECT_EQ(manifestStatus(final), "complete");
  EXPECT_FALSE(fs::exists(final.string() + ".lock"));
}

TEST_F(OutputTest, SecondRunIntoTheSameDirectoryStopsNamingTheFirst) {
  const fs::path final = base_ / "run";
  makeResult(final, {{"history.csv", "earlier\n"}});
  const auto before = snapshot(final);
  OutputDirectory first(comm_, final.string());
  // Open file descriptions lock independently (fcntl OFD locks), so a second
  // OutputDirectory in this process meets the first's lock as another run would.
  try {
    OutputDirectory second(comm_, final.string());
    ADD_FAILURE() << "expected ddc::InputError";
  } catch (const ddc::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("is in use by another ddcontact run"), std::string::npos) << what;
    // The lock is held by rank 0's process.
    int pid0 = static_cast<int>(::getpid());
    Teuchos::broadcast<int, int>(*comm_, 0, Teuchos::outArg(pid0));
    EXPECT_NE(what.find("pid: " + std::to_string(pid0)), std::string::npos) << what;
  }
  comm_->barrier();
  EXPECT_TRUE(fs::exists(first.path()));  // the first run's staging is intact
  if (rank() == 0) writeFile(fs::path(first.path()) / "history.csv", "first\n");
  first.commit();
  EXPECT_EQ(readFile(final / "history.csv"), "first\n");
  (void)before;
}

TEST_F(OutputTest, ForeignLockFileIsNotOverwritten) {
  const fs::path final = base_ / "run";
  if (rank() == 0) writeFile(final.string() + ".lock", "someone's file\n");
  comm_->barrier();
  EXPECT_THROW(OutputDirectory(comm_, final.string()), ddc::InputError);
  comm_->barrier();
  EXPECT_EQ(readFile(final.string() + ".lock"), "someone's file\n");
}

// Each intermediate state of a commit (OutputDirectory::commit), rebuilt by
// hand, and what the next run makes of it: the newest complete result ends up
// in D, and no complete result is lost before a newer one is in place.
class OutputRecoveryTest : public OutputTest {
 protected:
  void SetUp() override {
    OutputTest::SetUp();
    final_ = base_ / "run";
    partial_ = final_.string() + ".partial";
    old_ = final_.string() + ".old";
    // The old and the new complete results, made under other names.
    makeResult(base_ / "old-result", {{"history.csv", "old\n"}});
    makeResult(base_ / "new-result", {{"history.csv", "new\n"}, {"vtk/s.vtu", "new vtu\n"}});
  }
  void place(const std::string& which, const fs::path& where) {
    if (rank() == 0) fs::rename(base_ / which, where);
    comm_->barrier();
  }
  /// A staging directory of a run that did not finish.
  void unfinishedStaging() {
    OutputDirectory failed(comm_, (base_ / "unfinished").string());
    if (rank() == 0) writeFile(fs::path(failed.path()) / "history.csv", "partial\n");
    comm_->barrier();
    place("unfinished.partial", partial_);
  }
  /// Opens the directory as the next run does; returns the history in D.
  std::string nextRun(std::vector<std::string>* notes = nullptr) {
    OutputDirectory next(comm_, final_.string());
    if (notes) *notes = next.recoveryNotes();
    EXPECT_FALSE(fs::exists(old_));
    EXPECT_EQ(manifestStatus(final_), "complete");
    EXPECT_EQ(manifestStatus(partial_), "running");  // the next run's own staging
    const std::string history = readFile(final_ / "history.csv");
    // Rank 0 removes the empty staging directory when `next` goes: every rank
    // looks at it first.
    comm_->barrier();
    return history;
  }
  fs::path final_, partial_, old_;
};

TEST_F(OutputRecoveryTest, KilledDuringTheRunKeepsTheOldResult) {
  place("old-result", final_);
  unfinishedStaging();
  std::vector<std::string> notes;
  EXPECT_EQ(nextRun(&notes), "old\n");
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("did not finish"), std::string::npos);
}

TEST_F(OutputRecoveryTest, KilledAfterTheManifestPublishesTheNewResult) {
  place("old-result", final_);
  place("new-result", partial_);  // complete manifest, not yet renamed
  EXPECT_EQ(nextRun(), "new\n");
  EXPECT_EQ(readFile(final_ / "vtk" / "s.vtu"), "new vtu\n");
}

TEST_F(OutputRecoveryTest, KilledAfterMovingTheOldResultPublishesTheNewResult) {
  place("old-result", old_);
  place("new-result", partial_);
  std::vector<std::string> notes;
  EXPECT_EQ(nextRun(&notes), "new\n");
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("completed a commit interrupted"), std::string::npos) << notes[0];
}

TEST_F(OutputRecoveryTest, KilledAfterPublishingRemovesTheOldResult) {
  place("old-result", old_);
  place("new-result", final_);
  EXPECT_EQ(nextRun(), "new\n");
}

TEST_F(OutputRecoveryTest, KilledWhileRemovingTheOldResultFinishesTheRemoval) {
  place("old-result", old_);
  place("new-result", final_);
  if (rank() == 0) fs::remove(old_ / "history.csv");  // half removed: manifest still there
  comm_->barrier();
  EXPECT_EQ(nextRun(), "new\n");
}

TEST_F(OutputRecoveryTest, OldResultWithoutANewOneIsRestored) {
  place("old-result", old_);
  unfinishedStaging();
  EXPECT_EQ(nextRun(), "old\n");
}

// A real full disk: /dev/full fails every write with ENOSPC.
TEST_F(OutputTest, FullDiskIsAnErrorNamingTheFile) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  if (rank() == 0) {
    try {
      ddc::CheckedFile f("/dev/full");
      f.write(std::string(100, 'x'));
      f.close();
      ADD_FAILURE() << "expected ddc::OutputError";
    } catch (const ddc::OutputError& e) {
      EXPECT_NE(std::string(e.what()).find("cannot write '/dev/full': No space left on device"), std::string::npos)
          << e.what();
    }
  }
  try {
    HistoryWriter h(comm_, "/dev/full", {"step"});
    ADD_FAILURE() << "expected ddc::OutputError on every rank";
  } catch (const ddc::OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("'/dev/full': No space left on device"), std::string::npos) << e.what();
  }
}

TEST_F(OutputTest, AtomicWriteKeepsTheOldContentWhenItFails) {
  if (rank() == 0) {
    const fs::path p = base_ / "parameters.xml";
    writeFile(p, "old\n");
    ddc::writeFileAtomically(p.string(), "new\n");
    EXPECT_EQ(readFile(p), "new\n");
    EXPECT_FALSE(fs::exists(p.string() + ".tmp"));
    // The temporary file cannot be created (a directory holds its name).
    fs::create_directories(p.string() + ".tmp");
    EXPECT_THROW(ddc::writeFileAtomically(p.string(), "newer\n"), ddc::OutputError);
    EXPECT_EQ(readFile(p), "new\n");
  }
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
