// Parameter validation (DDC_Parameters.hpp): NumberValidator ranges and
// their messages, the strict value parser shared by --set and the deck
// reader, --set below templates, and the valid values printed by
// printParameterDoc().
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Teuchos_XMLParameterListHelpers.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"
#include "DDC_TestErrors.hpp"

using ddc::InputError;
using ::testing::HasSubstr;
using ::testing::Not;
using PL = Teuchos::ParameterList;

namespace {

using ddc::test::inputErrorOf;

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

/// A valid list with one parameter of each kind of rule.
PL validList() {
  PL v("Load Stepping");
  v.set("Number of Steps", 10, "steps", ddc::greaterThan(0));
  v.set("Max Bisections", 6, "halvings", ddc::atLeast(0));
  v.set("Final Load Factor", 1.0, "end", ddc::greaterThan(0.0));
  v.set("Poisson's Ratio", 0.3, "nu", ddc::between(-1.0, 0.5, ddc::Interval::Open));
  v.set("Distortion", 0.0, "d", ddc::between(0.0, 0.3));
  v.set("Value X", 0.0, "any finite", ddc::finiteNumber());
  v.set("Output Frequency", -1, "-1 or >= 1",
        Teuchos::rcp(new ddc::NumberValidator<int>(ddc::NumberValidator<int>::Bound{1, true}, std::nullopt, {-1})));
  v.set("Name", std::string("x"), "no validator");
  return v;
}

/// validateLevel()'s message for one user entry.
template <class T>
std::string messageFor(const std::string& name, T value) {
  PL user;
  user.set(name, value);
  return inputErrorOf([&] { ddc::validateLevel(user, validList(), "Load Stepping"); });
}

TEST(NumberValidator, RulesInWords) {
  EXPECT_EQ(ddc::greaterThan(0)->rule(), "> 0");
  EXPECT_EQ(ddc::atLeast(0)->rule(), ">= 0");
  EXPECT_EQ(ddc::greaterThan(0.0)->rule(), "> 0 and finite");
  EXPECT_EQ(ddc::between(-1.0, 0.5, ddc::Interval::Open)->rule(), "in (-1, 0.5)");
  EXPECT_EQ(ddc::between(0.0, 0.3)->rule(), "in [0, 0.3]");
  EXPECT_EQ(ddc::between(0, 2, ddc::Interval::LeftOpen)->rule(), "in (0, 2]");
  EXPECT_EQ(ddc::finiteNumber()->rule(), "finite");
  EXPECT_EQ(ddc::NumberValidator<int>(ddc::NumberValidator<int>::Bound{1, true}, std::nullopt, {-1}).rule(),
            "-1 or >= 1");
}

TEST(NumberValidator, AcceptsExactlyItsRange) {
  EXPECT_TRUE(ddc::greaterThan(0)->accepts(1));
  EXPECT_FALSE(ddc::greaterThan(0)->accepts(0));
  EXPECT_TRUE(ddc::atLeast(0)->accepts(0));
  EXPECT_FALSE(ddc::atLeast(0)->accepts(-1));
  const auto nu = ddc::between(-1.0, 0.5, ddc::Interval::Open);
  EXPECT_TRUE(nu->accepts(-0.999));
  EXPECT_TRUE(nu->accepts(0.4999));
  EXPECT_FALSE(nu->accepts(0.5));
  EXPECT_FALSE(nu->accepts(-1.0));
  EXPECT_TRUE(ddc::between(0.0, 0.3)->accepts(0.3));
  EXPECT_FALSE(ddc::between(0.0, 0.3)->accepts(0.30000000000000004));
  // Doubles are finite whatever the bounds.
  for (const auto& v : {ddc::greaterThan(0.0), ddc::atLeast(0.0), ddc::finiteNumber()}) {
    EXPECT_FALSE(v->accepts(kNan));
    EXPECT_FALSE(v->accepts(kInf));
    EXPECT_FALSE(v->accepts(-kInf));
  }
  EXPECT_TRUE(ddc::finiteNumber()->accepts(-1e300));
  const ddc::NumberValidator<int> freq(ddc::NumberValidator<int>::Bound{1, true}, std::nullopt, {-1});
  EXPECT_TRUE(freq.accepts(-1));
  EXPECT_TRUE(freq.accepts(1));
  EXPECT_FALSE(freq.accepts(0));
  EXPECT_FALSE(freq.accepts(-2));
}

TEST(NumberValidator, RejectsBadBounds) {
  using V = ddc::NumberValidator<double>;
  EXPECT_THROW(V(V::Bound{1.0, true}, V::Bound{0.0, true}), std::invalid_argument);
  EXPECT_THROW(V(V::Bound{1.0, false}, V::Bound{1.0, true}), std::invalid_argument);
  EXPECT_THROW(V(V::Bound{kNan, true}, std::nullopt), std::invalid_argument);
  EXPECT_NO_THROW(V(V::Bound{1.0, true}, V::Bound{1.0, true}));
}

// The message carries the full path, the rule and the value; these are the
// texts the negative system tests look for.
TEST(ValidateLevel, ViolationNamesPathRuleAndValue) {
  EXPECT_EQ(messageFor("Number of Steps", 0), "parameter 'Load Stepping/Number of Steps' must be > 0, got 0");
  EXPECT_EQ(messageFor("Max Bisections", -1), "parameter 'Load Stepping/Max Bisections' must be >= 0, got -1");
  EXPECT_EQ(messageFor("Final Load Factor", 0.0),
            "parameter 'Load Stepping/Final Load Factor' must be > 0 and finite, got 0");
  EXPECT_EQ(messageFor("Final Load Factor", -2.5),
            "parameter 'Load Stepping/Final Load Factor' must be > 0 and finite, got -2.5");
  EXPECT_EQ(messageFor("Final Load Factor", kNan),
            "parameter 'Load Stepping/Final Load Factor' must be > 0 and finite, got nan");
  EXPECT_EQ(messageFor("Final Load Factor", kInf),
            "parameter 'Load Stepping/Final Load Factor' must be > 0 and finite, got inf");
  EXPECT_EQ(messageFor("Poisson's Ratio", 0.5), "parameter 'Load Stepping/Poisson's Ratio' must lie in (-1, 0.5), got 0.5");
  EXPECT_EQ(messageFor("Distortion", 0.31), "parameter 'Load Stepping/Distortion' must lie in [0, 0.3], got 0.31");
  EXPECT_EQ(messageFor("Value X", -kInf), "parameter 'Load Stepping/Value X' must be finite, got -inf");
  EXPECT_EQ(messageFor("Output Frequency", 0), "parameter 'Load Stepping/Output Frequency' must be -1 or >= 1, got 0");
  // The value is printed so that it reads back exactly.
  EXPECT_THAT(messageFor("Poisson's Ratio", 0.50000000000000011), HasSubstr("got 0.5000000000000001"));
}

TEST(ValidateLevel, WrongTypeNamesBothTypes) {
  EXPECT_EQ(messageFor("Final Load Factor", 2),
            "parameter 'Load Stepping/Final Load Factor' must be of type double, got int (value '2')");
  EXPECT_EQ(messageFor("Number of Steps", 2.5),
            "parameter 'Load Stepping/Number of Steps' must be of type int, got double (value '2.5')");
  PL user;
  user.sublist("Number of Steps");
  EXPECT_THAT(inputErrorOf([&] { ddc::validateLevel(user, validList(), "Load Stepping"); }),
              HasSubstr("'Load Stepping/Number of Steps' must be a int, not a sublist"));
}

TEST(ValidateLevel, ValidValuesPassAndDefaultsComeWithoutValidators) {
  PL user;
  user.set("Number of Steps", 1);
  user.set("Poisson's Ratio", -0.99);
  user.set("Output Frequency", -1);
  EXPECT_NO_THROW(ddc::validateLevel(user, validList(), "Load Stepping"));
  EXPECT_EQ(user.get<int>("Max Bisections"), 6);
  // Filled defaults carry no validator, so the list can be written as XML
  // (Teuchos has no converter for NumberValidator) and read back.
  EXPECT_TRUE(user.getEntry("Max Bisections").validator().is_null());
  std::ostringstream xml;
  EXPECT_NO_THROW(Teuchos::writeParameterListToXmlOStream(user, xml));
  EXPECT_THAT(xml.str(), Not(HasSubstr("NumberValidator")));
}

// Teuchos' own validateParameters() works with the validator too.
TEST(NumberValidator, WorksInTeuchosValidateParameters) {
  PL user;
  user.set("Number of Steps", 0);
  try {
    user.validateParameters(validList(), 0);
    FAIL() << "no exception";
  } catch (const Teuchos::Exceptions::InvalidParameterValue& e) {
    EXPECT_THAT(e.what(), HasSubstr("'Number of Steps'"));
    EXPECT_THAT(e.what(), HasSubstr("must be > 0, got 0"));
  }
  PL wrong;
  wrong.set("Number of Steps", 1.5);
  EXPECT_THROW(wrong.validateParameters(validList(), 0), Teuchos::Exceptions::InvalidParameterType);
}

// ------------------------------------------------------------- parseValue

std::string parseError(const std::string& type, const std::string& text) {
  return inputErrorOf([&] { ddc::parseValue(type, text, "P"); });
}

TEST(ParseValue, IntegersAreWholeDecimalNumbersInRange) {
  EXPECT_EQ(Teuchos::any_cast<int>(ddc::parseValue("int", "42", "P")), 42);
  EXPECT_EQ(Teuchos::any_cast<int>(ddc::parseValue("int", "-7", "P")), -7);
  EXPECT_EQ(Teuchos::any_cast<int>(ddc::parseValue("int", "+7", "P")), 7);
  EXPECT_EQ(Teuchos::any_cast<int>(ddc::parseValue("int", "2147483647", "P")), 2147483647);
  EXPECT_EQ(Teuchos::any_cast<int>(ddc::parseValue("int", "-2147483648", "P")), -2147483647 - 1);
  for (const char* bad : {"3abc", "2.9", "abc", "", " 3", "3 ", "0x10", "1e3", "+", "-", "+-3", "3\n"})
    EXPECT_EQ(parseError("int", bad), std::string("P expects an integer, got '") + bad + "'") << bad;
  for (const char* big : {"99999999999", "2147483648", "-2147483649"})
    EXPECT_EQ(parseError("int", big), std::string("P expects an integer, got '") + big +
                                          "': out of range, integers are between -2147483648 and 2147483647");
}

TEST(ParseValue, DoublesAreWhatStrtodReadsAsAWhole) {
  EXPECT_EQ(Teuchos::any_cast<double>(ddc::parseValue("double", "1.5", "P")), 1.5);
  EXPECT_EQ(Teuchos::any_cast<double>(ddc::parseValue("double", "-2e-3", "P")), -2e-3);
  EXPECT_EQ(Teuchos::any_cast<double>(ddc::parseValue("double", "3", "P")), 3.0);
  EXPECT_EQ(Teuchos::any_cast<double>(ddc::parseValue("double", "0x1p3", "P")), 8.0);
  // As Teuchos writes them (17 digits, scientific).
  EXPECT_EQ(Teuchos::any_cast<double>(ddc::parseValue("double", "2.99999999999999989e-01", "P")), 0.3);
  // nan and inf parse; the parameters' validators refuse them.
  EXPECT_TRUE(std::isnan(Teuchos::any_cast<double>(ddc::parseValue("double", "nan", "P"))));
  EXPECT_EQ(Teuchos::any_cast<double>(ddc::parseValue("double", "-inf", "P")), -kInf);
  // Underflow gives the nearest double (0 or subnormal), not an error.
  EXPECT_GE(Teuchos::any_cast<double>(ddc::parseValue("double", "1e-400", "P")), 0.0);
  for (const char* bad : {"abc", "", "1.5x", " 1.5", "1.5 ", "1,5", "--1"})
    EXPECT_EQ(parseError("double", bad), std::string("P expects a number, got '") + bad + "'") << bad;
  EXPECT_THAT(parseError("double", "1e999"), HasSubstr("P expects a number, got '1e999': out of range"));
}

TEST(ParseValue, BoolsAreTrueOrFalseAsTeuchosWritesThem) {
  EXPECT_TRUE(Teuchos::any_cast<bool>(ddc::parseValue("bool", "true", "P")));
  EXPECT_FALSE(Teuchos::any_cast<bool>(ddc::parseValue("bool", "false", "P")));
  for (const char* bad : {"TRUE", "yes", "1", "0", "", "true "})
    EXPECT_EQ(parseError("bool", bad), std::string("P expects true or false, got '") + bad + "'") << bad;
  EXPECT_EQ(Teuchos::any_cast<std::string>(ddc::parseValue("string", " any text ", "P")), " any text ");
  EXPECT_THROW(ddc::parseValue("float", "1", "P"), std::invalid_argument);
}

// --------------------------------------------------------------- --set

/// Valid parameters with a template level, as Analysis has them.
PL validWithTemplates() {
  PL valid("DDContact");
  PL body("<Body Name>");
  body.sublist("Rectangle").set("Refinement", 1, "r", ddc::atLeast(1));
  PL bodies("Bodies");
  bodies.set("<Body Name>", body);
  valid.sublist("Mesh").set("Bodies", bodies);
  PL bcs("Boundary Conditions");
  PL bc("<Condition Name>");
  bc.set("Value X", 0.0);
  bcs.set("<Condition Name>", bc);
  valid.set("Boundary Conditions", bcs);
  valid.set("Load Stepping", validList());
  return valid;
}

PL userDeck() {
  PL user("DDContact");
  user.sublist("Mesh").sublist("Bodies").sublist("Block").sublist("Rectangle").set("Refinement", 2);
  user.sublist("Mesh").sublist("Bodies").sublist("Base");
  return user;
}

TEST(ApplyOverride, ParsesWithTheDeclaredType) {
  PL user = userDeck();
  const PL valid = validWithTemplates();
  ddc::applyOverride(user, valid, "Mesh/Bodies/Block/Rectangle/Refinement=4");
  EXPECT_EQ(user.sublist("Mesh").sublist("Bodies").sublist("Block").sublist("Rectangle").get<int>("Refinement"), 4);
  ddc::applyOverride(user, valid, "Load Stepping/Final Load Factor=2.5");
  EXPECT_EQ(user.sublist("Load Stepping").get<double>("Final Load Factor"), 2.5);
  ddc::applyOverride(user, valid, "Load Stepping/Final Load Factor=3");  // an int text for a double
  EXPECT_EQ(user.sublist("Load Stepping").get<double>("Final Load Factor"), 3.0);
  EXPECT_EQ(inputErrorOf([&] { ddc::applyOverride(user, valid, "Load Stepping/Number of Steps=two"); }),
            "--set: parameter 'Load Stepping/Number of Steps' expects an integer, got 'two'");
  EXPECT_EQ(inputErrorOf([&] { ddc::applyOverride(user, valid, "Load Stepping/Number of Steps=2.9"); }),
            "--set: parameter 'Load Stepping/Number of Steps' expects an integer, got '2.9'");
  EXPECT_EQ(inputErrorOf([&] { ddc::applyOverride(user, valid, "Load Stepping/Number of Steps=99999999999"); }),
            "--set: parameter 'Load Stepping/Number of Steps' expects an integer, got '99999999999': out of range, "
            "integers are between -2147483648 and 2147483647");
  EXPECT_EQ(inputErrorOf([&] { ddc::applyOverride(user, valid, "Load Stepping/Final Load Factor=abc"); }),
            "--set: parameter 'Load Stepping/Final Load Factor' expects a number, got 'abc'");
}

TEST(ApplyOverride, MisspeltTemplateNameIsAnErrorNamingTheKnownOnes) {
  PL user = userDeck();
  const PL valid = validWithTemplates();
  EXPECT_EQ(inputErrorOf([&] { ddc::applyOverride(user, valid, "Mesh/Bodies/Blok/Rectangle/Refinement=4"); }),
            "--set: no body 'Blok' in 'Mesh/Bodies'; bodies are 'Block', 'Base'");
  EXPECT_FALSE(user.sublist("Mesh").sublist("Bodies").isSublist("Blok")) << "no new body was created";
  EXPECT_EQ(inputErrorOf([&] { ddc::applyOverride(user, valid, "Boundary Conditions/Fixd/Value X=1"); }),
            "--set: no condition 'Fixd' in 'Boundary Conditions'; there are no conditions");
  // Outside templates missing sublists are still created (validation names
  // a misspelt one later).
  EXPECT_EQ(inputErrorOf([&] { ddc::applyOverride(user, valid, "Load Steping/Number of Steps=2"); }), ddc::test::kNoInputError);
  EXPECT_TRUE(user.isSublist("Load Steping"));
}

// -------------------------------------------------------- printParameterDoc

TEST(PrintParameterDoc, ShowsRangesAndEnumerations) {
  PL valid = validList();
  valid.set("Method", std::string("A"), "how", ddc::enumValidator({"A", "B"}, "Method"));
  std::ostringstream os;
  ddc::printParameterDoc(valid, os);
  const std::string doc = os.str();
  EXPECT_THAT(doc, HasSubstr("| parameter | type | default | valid values | description |"));
  EXPECT_THAT(doc, HasSubstr("| `Number of Steps` | int | `10` | `> 0` | steps |"));
  EXPECT_THAT(doc, HasSubstr("| `Poisson's Ratio` | double | `0.3` | `in (-1, 0.5)` | nu |"));
  EXPECT_THAT(doc, HasSubstr("| `Method` | string | `A` | `A`, `B` | how |"));
  EXPECT_THAT(doc, HasSubstr("| `Name` | string | `x` |  | no validator |"));
}

}  // namespace
