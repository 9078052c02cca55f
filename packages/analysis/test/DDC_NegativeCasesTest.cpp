// The negative cases of test/negative_cases.txt that fail before the model is
// built (reading the deck, applying --set, validating the parameters, the
// mesh, the conditions, the pairs and the partition), checked in process:
// for each, the deck is read and the --set options applied as src/ddcontact.cpp
// does (ddc::readDeck, ddc::applyOverride), ddc::Analysis is constructed, and
// every rank must throw the same ddc::InputError, its message matching the
// table's regex. One process per rank count instead of one mpirun per case;
// test/cmake/NegativeCases.cmake declares the rest of the table (and a few of
// these again, end to end) as application runs.
//
// Instances: Decks/... need only files in the source tree or generated at
// configure time; RunOutputs/... need files that other tests make (their
// "fixture" lines), and run in a ctest of their own that requires those.
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "DDC_Analysis.hpp"
#include "DDC_AnalysisTestDecks.hpp"
#include "DDC_ElementFactory.hpp"
#include "DDC_Error.hpp"
#include "DDC_InputDeck.hpp"
#include "DDC_NegativeCaseTable.hpp"
#include "DDC_Parameters.hpp"
#include "DDC_TestErrors.hpp"

namespace {

using ddc::test::NegativeCase;
using ddc::test::worldComm;

const std::string kTable = DDC_SOURCE_DIR "/test/negative_cases.txt";

/// The table, read once; a table that cannot be read leaves `tableError`.
struct Table {
  std::vector<NegativeCase> cases;
  std::string error;
};

const Table& table() {
  static const Table t = [] {
    Table r;
    const std::string src = DDC_SOURCE_DIR, bin = DDC_TEST_BINARY_DIR;
    const ddc::test::Placeholders dirs = {
        {"@INPUTS@", src + "/test/inputs"}, {"@NEGATIVE@", src + "/test/inputs/negative"},
        {"@EXAMPLES@", src + "/examples"},  {"@SOURCE@", src},
        {"@DECKS@", bin + "/decks"},        {"@RUNS@", bin + "/runs"}};
    try {
      r.cases = ddc::test::readNegativeCases(kTable, dirs);
    } catch (const std::exception& e) {
      r.error = e.what();
    }
    return r;
  }();
  return t;
}

/// The in-process cases with (`fromRuns`) or without files made by other tests.
std::vector<NegativeCase> inProcessCases(bool fromRuns) {
  std::vector<NegativeCase> out;
  for (const auto& c : table().cases)
    if (c.inProcess() && c.fixtures.empty() != fromRuns) out.push_back(c);
  return out;
}

std::string caseName(const testing::TestParamInfo<NegativeCase>& info) { return info.param.id; }

/// What src/ddcontact.cpp does with the deck and the --set options before
/// it builds the analysis (the output directory aside), up to the end of
/// the Analysis constructor.
void readAndBuild(const NegativeCase& c) {
  const auto comm = worldComm();
  auto params = ddc::readDeck(*comm, c.deck);
  const auto valid = ddc::Analysis::getValidParameters();
  for (const auto& s : c.sets) ddc::applyOverride(*params, *valid, s);
  std::string base = std::filesystem::path(c.deck).parent_path().string();
  if (base.empty()) base = ".";
  ddc::Analysis analysis(comm, *params, ddc::ElementFactory::withBuiltins(), base);
}

class NegativeCaseInProcess : public testing::TestWithParam<NegativeCase> {};

TEST_P(NegativeCaseInProcess, SameInputErrorOnEveryRank) {
  const NegativeCase& c = GetParam();
  const auto comm = worldComm();
  if (!c.checkedOn(comm->getSize()))
    GTEST_SKIP() << "the table checks '" << c.id << "' on other rank counts";
  const std::string msg = ddc::test::inputErrorOf([&] { readAndBuild(c); });
  EXPECT_NE(msg, ddc::test::kNoInputError) << "case '" << c.id << "' raised no InputError on rank " << comm->getRank();
  EXPECT_TRUE(std::regex_search(msg, std::regex(ddc::test::ecmaScriptRegex(c.regex))))
      << "case '" << c.id << "', rank " << comm->getRank() << ": the message\n  " << msg
      << "\ndoes not match\n  " << c.regex;
  const auto rank0 = ddc::broadcastStrings(*comm, {msg});
  EXPECT_EQ(msg, rank0.front()) << "rank " << comm->getRank() << " has another message than rank 0";
}

INSTANTIATE_TEST_SUITE_P(Decks, NegativeCaseInProcess, testing::ValuesIn(inProcessCases(false)), caseName);
INSTANTIATE_TEST_SUITE_P(RunOutputs, NegativeCaseInProcess, testing::ValuesIn(inProcessCases(true)), caseName);

// The table itself: readable, every case's regex valid in both syntaxes
// (std::regex here; CMake's when test/cmake/NegativeCases.cmake reads it).
TEST(NegativeCaseTable, ReadsAndEveryRegexCompiles) {
  ASSERT_EQ(table().error, "");
  ASSERT_FALSE(table().cases.empty());
  for (const auto& c : table().cases)
    EXPECT_NO_THROW(std::regex(ddc::test::ecmaScriptRegex(c.regex))) << "case '" << c.id << "': " << c.regex;
}

// The conversion of the table's CMake regexes.
TEST(NegativeCaseTable, DotMatchesNewlineOutsideBrackets) {
  using ddc::test::ecmaScriptRegex;
  EXPECT_EQ(ecmaScriptRegex("a.b"), "a[\\s\\S]b");
  EXPECT_EQ(ecmaScriptRegex("a\\.b[.]c[^.]"), "a\\.b[.]c[^.]");
  EXPECT_TRUE(std::regex_search("step 1\nMax Bisections", std::regex(ecmaScriptRegex("step 1.*Max Bisections"))));
}

}  // namespace
