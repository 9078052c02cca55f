// The table of negative cases, test/negative_cases.txt (its header says the
// format): one block of "key value" lines per case, read here by the
// in-process check (DDC_NegativeCasesTest.cpp) and by CMake
// (test/cmake/NegativeCases.cmake), which declares the application runs.
#pragma once

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace ddc::test {

/// One negative case of the table.
struct NegativeCase {
  std::string id;                  ///< "case": the ctest / gtest name stem
  std::string stage;               ///< "stage": cli, startup, deck, validation, model, run, tool
  std::vector<int> ranks;          ///< "ranks": the rank counts it is checked on
  std::vector<std::string> via;    ///< "via": in-process and/or app (default: by stage)
  std::string deck;                ///< "deck", placeholders replaced
  std::vector<std::string> sets;   ///< "set": PATH=VALUE, in order
  std::vector<std::string> args;   ///< "arg": more command-line arguments
  std::string regex;               ///< "regex": the message, CMake regex syntax
  std::vector<std::string> fixtures;  ///< "fixture": files other tests make
  std::vector<std::string> labels;    ///< "labels": more ctest labels
  std::vector<std::string> other;     ///< keys of application runs only (launcher, env, app, mpmd)

  bool inProcess() const;
  bool checkedOn(int ranks) const;
};

/// A case in GoogleTest's messages: its id.
inline void PrintTo(const NegativeCase& c, std::ostream* os) { *os << c.id; }

/// The placeholders of deck and file paths (@INPUTS@, @NEGATIVE@, @EXAMPLES@,
/// @DECKS@, @RUNS@, @SOURCE@) and their directories.
using Placeholders = std::map<std::string, std::string>;

/// Every case of the table file `path`, placeholders replaced.
/// \throws std::runtime_error naming the file and line on a malformed table.
std::vector<NegativeCase> readNegativeCases(const std::string& path, const Placeholders& placeholders);

/// `cmakeRegex` (the table's syntax: CMake's regular expressions, where '.'
/// also matches a newline) as an ECMAScript regex for std::regex: every '.'
/// outside a bracket expression becomes [\s\S]; the rest of the syntax the
/// table uses (anchors, *, +, ?, |, groups, bracket expressions that do not
/// start with ']', \-escapes) means the same in both.
std::string ecmaScriptRegex(const std::string& cmakeRegex);

}  // namespace ddc::test
