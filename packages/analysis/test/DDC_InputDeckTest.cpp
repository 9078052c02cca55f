// The deck reader (DDC_InputDeck.hpp): strict values, unique names, the
// nesting limit, rank-0 reading with a broadcast, the check of files named in
// the parameters, and that every int/double parameter has its range.
// Runs on 1 and 2 ranks; an error must be the same InputError on every rank.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <Teuchos_XMLParameterListHelpers.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "DDC_Analysis.hpp"
#include "DDC_AnalysisTestDecks.hpp"
#include "DDC_Error.hpp"
#include "DDC_InputDeck.hpp"
#include "DDC_Parameters.hpp"
#include "DDC_TestErrors.hpp"

namespace fs = std::filesystem;
using ddc::InputError;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using PL = Teuchos::ParameterList;

namespace {

using ddc::test::inputErrorOf;

using ddc::test::worldComm;

/// The same message on every rank (collective).
void expectSameOnEveryRank(const std::string& msg) {
  const auto all = ddc::broadcastStrings(*worldComm(), {msg});
  EXPECT_EQ(msg, all.front()) << "rank " << worldComm()->getRank() << " has another message";
}

std::string parseError(const std::string& text) {
  return inputErrorOf([&] { ddc::parseDeck(text, "deck.xml"); });
}

/// A deck whose Load Stepping list holds `entries` (XML text).
std::string deckWith(const std::string& entries) {
  return "<ParameterList name=\"DDContact\">\n  <ParameterList name=\"Load Stepping\">\n" + entries +
         "\n  </ParameterList>\n</ParameterList>\n";
}

std::string param(const std::string& name, const std::string& type, const std::string& value) {
  return "<Parameter name=\"" + name + "\" type=\"" + type + "\" value=\"" + value + "\"/>";
}

/// `levels` nested lists, the innermost holding one parameter at level
/// `levels + 1`.
std::string nested(int levels) {
  std::string open, close;
  for (int i = 0; i < levels; ++i) {
    open += "<ParameterList name=\"L" + std::to_string(i) + "\">";
    close += "</ParameterList>";
  }
  return open + param("x", "int", "1") + close;
}

std::string readText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// A fresh directory per test and rank.
fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("ddc_input_deck_" + name + "_" + std::to_string(::getpid()) + "_" +
                        std::to_string(worldComm()->getRank()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// ---------------------------------------------------------------- values

TEST(ParseDeck, ValuesMustParseAsTheirTypeAsAWhole) {
  const struct {
    std::string entry, message;
  } cases[] = {
      {param("Number of Steps", "int", "3abc"),
       "input file 'deck.xml': parameter 'Load Stepping/Number of Steps' expects an integer, got '3abc'"},
      {param("Number of Steps", "int", "2.9"),
       "input file 'deck.xml': parameter 'Load Stepping/Number of Steps' expects an integer, got '2.9'"},
      {param("Number of Steps", "int", "99999999999"),
       "input file 'deck.xml': parameter 'Load Stepping/Number of Steps' expects an integer, got '99999999999': out "
       "of range, integers are between -2147483648 and 2147483647"},
      {param("Final Load Factor", "double", "abc"),
       "input file 'deck.xml': parameter 'Load Stepping/Final Load Factor' expects a number, got 'abc'"},
      {param("Final Load Factor", "double", "1.0.0"),
       "input file 'deck.xml': parameter 'Load Stepping/Final Load Factor' expects a number, got '1.0.0'"},
      {param("Print", "bool", "yes"), "input file 'deck.xml': parameter 'Load Stepping/Print' expects true or false, "
                                      "got 'yes'"},
  };
  for (const auto& c : cases) EXPECT_EQ(parseError(deckWith(c.entry)), c.message) << c.entry;
}

TEST(ParseDeck, ParametersNeedNameTypeAndAKnownType) {
  EXPECT_EQ(parseError(deckWith(param("Ratio", "float", "0.3"))),
            "input file 'deck.xml': parameter 'Load Stepping/Ratio' has type 'float'; parameters have type int, "
            "double, bool or string");
  EXPECT_THAT(parseError(deckWith("<Parameter name=\"N\" value=\"3\"/>")),
              HasSubstr("parameter 'Load Stepping/N' has no type attribute"));
  EXPECT_THAT(parseError(deckWith("<Parameter name=\"N\" type=\"int\"/>")),
              HasSubstr("parameter 'Load Stepping/N' has no value attribute"));
  EXPECT_THAT(parseError(deckWith("<Parameter type=\"int\" value=\"3\"/>")),
              HasSubstr("a <Parameter> in sublist 'Load Stepping' has no name attribute"));
  EXPECT_THAT(parseError(deckWith("<ParameterList/>")),
              HasSubstr("a <ParameterList> in sublist 'Load Stepping' has no name attribute"));
  EXPECT_THAT(parseError(deckWith("<Param name=\"N\" type=\"int\" value=\"3\"/>")),
              HasSubstr("unexpected element <Param> in sublist 'Load Stepping'"));
}

TEST(ParseDeck, NamesAppearOncePerList) {
  EXPECT_EQ(parseError(deckWith(param("Number of Steps", "int", "2") + param("Number of Steps", "int", "3"))),
            "input file 'deck.xml': 'Load Stepping/Number of Steps' is given twice in sublist 'Load Stepping' (as a "
            "parameter and as a parameter); every name may appear once in a list");
  EXPECT_THAT(parseError("<ParameterList name=\"D\"><ParameterList name=\"Newton\"/><ParameterList "
                         "name=\"Newton\"/></ParameterList>"),
              HasSubstr("'Newton' is given twice in the top-level list (as a sublist and as a sublist)"));
  EXPECT_THAT(parseError(deckWith(param("X", "int", "2") + "<ParameterList name=\"X\"/>")),
              HasSubstr("'Load Stepping/X' is given twice in sublist 'Load Stepping' (as a parameter and as a "
                        "sublist)"));
  // The same name in different lists is fine.
  EXPECT_NO_THROW(ddc::parseDeck(
      "<ParameterList name=\"D\"><ParameterList name=\"A\">" + param("X", "int", "1") +
          "</ParameterList><ParameterList name=\"B\">" + param("X", "int", "2") + "</ParameterList></ParameterList>",
      "deck.xml"));
}

TEST(ParseDeck, MalformedXmlNamesTheFile) {
  EXPECT_THAT(parseError("<ParameterList name=\"D\">"),
              StartsWith("input file 'deck.xml' is not a valid Teuchos XML parameter list: "));
  EXPECT_THAT(parseError(""), StartsWith("input file 'deck.xml' is not a valid Teuchos XML parameter list: "));
  EXPECT_THAT(parseError("<!-- only a comment -->"),
              StartsWith("input file 'deck.xml' is not a valid Teuchos XML parameter list: "));
  EXPECT_THAT(parseError("<Foo/>"), HasSubstr("the root element is <Foo>, expected <ParameterList>"));
}

TEST(ParseDeck, ReadsWhatTeuchosReads) {
  const auto deck = ddc::parseDeck(deckWith(param("Number of Steps", "int", "+5") +
                                            param("Final Load Factor", "double", "2.5e-1") +
                                            param("Name", "string", " a b ") + param("On", "bool", "true")) +
                                       "<!-- a comment -->",
                                   "deck.xml");
  const PL& ls = deck->sublist("Load Stepping");
  EXPECT_EQ(ls.get<int>("Number of Steps"), 5);
  EXPECT_EQ(ls.get<double>("Final Load Factor"), 0.25);
  EXPECT_EQ(ls.get<std::string>("Name"), " a b ");
  EXPECT_TRUE(ls.get<bool>("On"));
}

// Every deck of the repository reads as Teuchos reads it, except the
// malformed one and the negative decks of the strict rules
// (test/inputs/negative/xml_*.xml), which the strict reader refuses.
TEST(ParseDeck, RepositoryDecksReadAsTeuchosReadsThem) {
  int decks = 0, refused = 0;
  for (const char* dir : {"examples", "test/inputs", "test/inputs/negative", "test/benchmark"}) {
    for (const auto& e : fs::directory_iterator(fs::path(DDC_SOURCE_DIR) / dir)) {
      const std::string name = e.path().filename().string();
      if (e.path().extension() != ".xml" || name == "malformed.xml") continue;
      SCOPED_TRACE(e.path().string());
      if (name.rfind("xml_", 0) == 0) {
        EXPECT_THAT(inputErrorOf([&] { ddc::parseDeck(readText(e.path()), name); }),
                    StartsWith("input file '" + name + "': "));
        ++refused;
        continue;
      }
      if (name == "deck_utf16.xml") {  // refused, naming the encoding (Teuchos cannot read it either)
        EXPECT_THAT(inputErrorOf([&] { ddc::parseDeck(readText(e.path()), name); }),
                    StartsWith("input file '" + name + "' is UTF-16"));
        ++refused;
        continue;
      }
      const auto strict = ddc::parseDeck(readText(e.path()), e.path().string());
      // small_block.xml saved with a UTF-8 byte-order mark, which Teuchos
      // stumbles on: it reads as small_block.xml.
      const fs::path same = name == "deck_utf8_bom.xml" ? e.path().parent_path() / "small_block.xml" : e.path();
      const auto teuchos = Teuchos::getParametersFromXmlFile(same.string());
      if (name == "final_load_factor_nan.xml") {  // nan != nan: haveSameValues() cannot compare it
        EXPECT_TRUE(std::isnan(strict->sublist("Load Stepping").get<double>("Final Load Factor")));
        continue;
      }
      EXPECT_TRUE(Teuchos::haveSameValues(*strict, *teuchos));
      ++decks;
    }
  }
  EXPECT_GE(decks, 20);
  EXPECT_GE(refused, 7);
}

// parameters.xml (the validated parameters, written by Teuchos) reads back.
TEST(ParseDeck, WrittenParametersReadBack) {
  auto deck = ddc::parseDeck(readText(fs::path(DDC_SOURCE_DIR) / "test/inputs/small_block.xml"), "small_block.xml");
  deck->sublist("Output").set("Progress", false);
  ddc::Analysis a(worldComm(), *deck);
  std::ostringstream xml;
  Teuchos::writeParameterListToXmlOStream(a.parameters(), xml);
  const auto back = ddc::parseDeck(xml.str(), "parameters.xml");
  EXPECT_TRUE(Teuchos::haveSameValues(*back, a.parameters()));
  EXPECT_EQ(back->sublist("Load Stepping").get<double>("Final Load Factor"), 1.0);
}

// --------------------------------------------------------------- nesting

TEST(MaxElementDepth, SkipsCommentsCdataInstructionsAndQuotedValues) {
  EXPECT_EQ(ddc::maxElementDepth("", 32).depth, 0);
  EXPECT_EQ(ddc::maxElementDepth("<a><b/><c></c></a>", 32).depth, 2);
  const std::string tricky =
      "<?xml version=\"1.0\"?>\n<!DOCTYPE a>\n<a>\n<!-- <b><b><b> -->\n<![CDATA[<b><b><b>]]>\n"
      "<b x=\"/>\" y='>'><c z=\"<d>\"/></b>\n<?pi <b><b> ?>\n</a>";
  const auto d = ddc::maxElementDepth(tricky, 32);
  EXPECT_EQ(d.depth, 3);
  EXPECT_EQ(d.line, 6);
  // Stops at the first element beyond the limit.
  const auto deep = ddc::maxElementDepth("<a>\n<b>\n<c>\n<d></d></c></b></a>", 2);
  EXPECT_EQ(deep.depth, 3);
  EXPECT_EQ(deep.line, 3);
}

TEST(ParseDeck, NestingIsLimited) {
  // The parameter of nested(31) inside the root is at level 33.
  EXPECT_NO_THROW(ddc::parseDeck("<ParameterList name=\"D\">" + nested(30) + "</ParameterList>", "deck.xml"));
  EXPECT_EQ(parseError("<ParameterList name=\"D\">\n" + nested(31) + "</ParameterList>"),
            "input file 'deck.xml': elements nest more than 32 levels deep (line 2); a deck may nest at most 32 "
            "levels");
  // Far beyond: refused before Teuchos builds (and would recursively
  // convert and destroy) the tree.
  const int levels = 200000;
  std::string deep = "<ParameterList name=\"D\">";
  deep.reserve(static_cast<std::size_t>(levels) * 45);
  for (int i = 0; i < levels; ++i) deep += "<ParameterList name=\"a\">";
  for (int i = 0; i < levels; ++i) deep += "</ParameterList>";
  deep += "</ParameterList>";
  EXPECT_THAT(parseError(deep), HasSubstr("elements nest more than 32 levels deep"));
}

// ------------------------------------------------------------ collective

TEST(ReadDeck, RankZeroReadsAndEveryRankGetsTheDeck) {
  // Only rank 0 opens the file: the others may name one they cannot see.
  const std::string deck = std::string(DDC_SOURCE_DIR) + "/test/inputs/small_block.xml";
  const auto params = ddc::readDeck(*worldComm(), worldComm()->getRank() == 0 ? deck : "/no/such/deck.xml");
  const auto teuchos = Teuchos::getParametersFromXmlFile(deck);
  EXPECT_TRUE(Teuchos::haveSameValues(*params, *teuchos));
}

TEST(ReadDeck, ErrorsOnRankZeroReachEveryRank) {
  const fs::path dir = scratch("errors");
  // Rank 0's names, as every rank has them in ddcontact.
  const std::string rootDir = ddc::broadcastStrings(*worldComm(), {dir.string()}).front();
  const std::string missing = rootDir + "/does_not_exist.xml";
  std::string msg = inputErrorOf([&] { ddc::readDeck(*worldComm(), missing); });
  EXPECT_EQ(msg, "input file '" + missing + "' does not exist");
  expectSameOnEveryRank(msg);
  msg = inputErrorOf([&] { ddc::readDeck(*worldComm(), rootDir); });
  EXPECT_EQ(msg, "input file '" + rootDir + "' is a directory, expected a Teuchos XML parameter file");
  expectSameOnEveryRank(msg);
  // A value error found on rank 0.
  const std::string bad = (dir / "bad.xml").string();
  if (worldComm()->getRank() == 0) std::ofstream(bad) << deckWith(param("Number of Steps", "int", "3abc"));
  const std::string badOnRoot = ddc::broadcastStrings(*worldComm(), {bad}).front();
  msg = inputErrorOf([&] { ddc::readDeck(*worldComm(), badOnRoot); });
  EXPECT_THAT(msg, HasSubstr("bad.xml': parameter 'Load Stepping/Number of Steps' expects an integer, got '3abc'"));
  expectSameOnEveryRank(msg);
  worldComm()->barrier();
  fs::remove_all(dir);
}

TEST(BroadcastStrings, RankZerosStringsEverywhere) {
  const bool root = worldComm()->getRank() == 0;
  const std::vector<std::string> mine =
      root ? std::vector<std::string>{"a.xml", "", "--set", "X=1"} : std::vector<std::string>{"other.xml"};
  EXPECT_EQ(ddc::broadcastStrings(*worldComm(), mine), (std::vector<std::string>{"a.xml", "", "--set", "X=1"}));
  EXPECT_TRUE(ddc::broadcastStrings(*worldComm(), root ? std::vector<std::string>{} : mine).empty());
}

TEST(NamedInputFiles, ResolvesAsTheReadersDo) {
  PL p;
  PL& g = p.sublist("Mesh").sublist("Bodies").sublist("Ring");
  g.set("Generator", std::string("Gmsh"));
  g.sublist("Gmsh").set("File", std::string("ring.msh"));
  PL& r = p.sublist("Mesh").sublist("Bodies").sublist("Block");
  r.set("Generator", std::string("Rectangle"));
  r.sublist("Gmsh").set("File", std::string("unused.msh"));  // not the body's generator
  p.sublist("Partition").set("Method", std::string("Element Map File"));
  p.sublist("Partition").set("Element Map File", std::string("/abs/parts.map"));
  using Files = std::vector<std::pair<std::string, std::string>>;
  EXPECT_EQ(ddc::namedInputFiles(p, "decks"),
            (Files{{"Mesh/Bodies/Ring/Gmsh/File", "decks/ring.msh"}, {"Partition/Element Map File", "/abs/parts.map"}}));
  p.sublist("Partition").set("Method", std::string("METIS"));
  EXPECT_EQ(ddc::namedInputFiles(p, "decks/"), (Files{{"Mesh/Bodies/Ring/Gmsh/File", "decks/ring.msh"}}));
}

TEST(RequireSameFilesOnEveryRank, FilesMissingOrDifferentOnSomeRanksFailEveryRank) {
  const int rank = worldComm()->getRank();
  const int size = worldComm()->getSize();
  const fs::path dir = scratch("files");  // one per rank: what a rank-local file system looks like
  auto file = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  };
  // Readable and the same everywhere: fine.
  const std::string same = file("same.msh", "mesh");
  EXPECT_NO_THROW(ddc::requireSameFilesOnEveryRank(*worldComm(), {{"Mesh/Bodies/B/Gmsh/File", same}}));
  // Readable nowhere: left to the reader (its message is the same everywhere).
  EXPECT_NO_THROW(ddc::requireSameFilesOnEveryRank(*worldComm(), {{"P", (dir / "none.msh").string()}}));
  if (size > 1) {
    // Only on rank 0.
    const std::string some = rank == 0 ? file("some.msh", "mesh") : (dir / "some.msh").string();
    std::string msg = inputErrorOf([&] { ddc::requireSameFilesOnEveryRank(*worldComm(), {{"Mesh/Bodies/B/Gmsh/File", some}}); });
    EXPECT_THAT(msg, HasSubstr("'Mesh/Bodies/B/Gmsh/File' = '"));
    EXPECT_THAT(msg, HasSubstr("': the file can be read on 1 of " + std::to_string(size) +
                               " ranks but not on rank 1; every rank reads it"));
    // Different contents per rank.
    const std::string differs = file("differs.map", "0 0 " + std::to_string(rank));
    msg = inputErrorOf([&] { ddc::requireSameFilesOnEveryRank(*worldComm(), {{"Partition/Element Map File", differs}}); });
    EXPECT_THAT(msg, HasSubstr("'Partition/Element Map File' = '"));
    EXPECT_THAT(msg, HasSubstr("': the file differs between ranks"));
  }
  worldComm()->barrier();
  fs::remove_all(dir);
}

// ------------------------------------------------------------ the sweep

/// Paths of int/double entries of `valid` without a NumberValidator, except
/// in the third-party lists MueLu and FROSch validate themselves.
void uncheckedNumbers(const PL& valid, const std::string& path, std::vector<std::string>& out) {
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::string& name = valid.name(it);
    const auto& e = valid.entry(it);
    if (e.isList()) {
      if (name != "MueLu" && name != "FROSch") uncheckedNumbers(valid.sublist(name), ddc::joinPath(path, name), out);
      continue;
    }
    const bool number = e.isType<int>() || e.isType<double>();
    const bool ranged = !Teuchos::rcp_dynamic_cast<const ddc::NumberRuleValidator>(e.validator()).is_null();
    if (number && !ranged) out.push_back(ddc::joinPath(path, name));
  }
}

TEST(ValidParameters, EveryNumberHasItsRangeAndItsDefaultObeysIt) {
  const auto valid = ddc::Analysis::getValidParameters();
  std::vector<std::string> unchecked;
  uncheckedNumbers(*valid, "", unchecked);
  EXPECT_TRUE(unchecked.empty()) << ::testing::PrintToString(unchecked);
  // Every default passes its own validator.
  std::function<void(const PL&, const std::string&)> defaults = [&](const PL& v, const std::string& path) {
    for (auto it = v.begin(); it != v.end(); ++it) {
      const auto& e = v.entry(it);
      if (e.isList()) {
        defaults(v.sublist(v.name(it)), ddc::joinPath(path, v.name(it)));
      } else if (auto rule = Teuchos::rcp_dynamic_cast<const ddc::NumberRuleValidator>(e.validator()); rule.get()) {
        EXPECT_EQ(rule->violation(e), "") << ddc::joinPath(path, v.name(it));
      }
    }
  };
  defaults(*valid, "");
}

}  // namespace
