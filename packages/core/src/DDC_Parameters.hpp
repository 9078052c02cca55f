// Parameter validation with path-qualified messages.
//
// Every configurable class has a static getValidParameters() (default + doc
// string per entry) and validates its own sublist with validateLevel(): a
// misspelt name is an InputError naming the full path and listing the valid
// names, never silently ignored. Every int and double parameter carries a
// NumberValidator with its range, so that the range is checked in one place
// and printed by printParameterDoc() (ddcontact --print-parameters).
//
// Values given as text (an XML deck, --set) are parsed by parseValue(): the
// whole text must be a value of the declared type, or it is an InputError.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace ddc {

/// \brief A rule on the value of an int or double parameter, as a Teuchos
/// validator (the common interface of NumberValidator<int> and <double>).
///
/// validateLevel() reports a violation as
/// "parameter 'Load Stepping/Number of Steps' must be > 0, got 0": the path
/// from validateLevel(), the rest from violation().
class NumberRuleValidator : public Teuchos::ParameterEntryValidator {
 public:
  /// The rule in words: "> 0", ">= 0", "in (-1, 0.5)", "-1 or >= 1",
  /// "finite"; doubles must also be finite ("> 0 and finite").
  virtual std::string rule() const = 0;

  /// "" if `entry` holds a value of the validator's type that obeys the
  /// rule, else what is wrong, e.g. "must be > 0, got 0" or
  /// "must be of type int, got double (value '2.5')".
  virtual std::string violation(const Teuchos::ParameterEntry& entry) const = 0;

  /// Teuchos::ParameterEntryValidator: no list of valid strings.
  ValidStringsList validStringValues() const override { return Teuchos::null; }
};

/// \brief Range of an int or a double parameter.
///
/// A value is valid if it is one of `alsoAllowed` (e.g. -1 meaning "off"), or
/// if it lies within the bounds (each optional, inclusive or exclusive) and,
/// for doubles, is finite: NaN and +-inf are never valid, so every double
/// parameter with a NumberValidator is finite. Use the helpers below
/// (greaterThan(), atLeast(), between(), finiteNumber()) to make one.
/// \tparam T int or double (instantiated in DDC_Parameters.cpp).
template <class T>
class NumberValidator : public NumberRuleValidator {
 public:
  /// One end of the range.
  struct Bound {
    T value;         ///< the bound
    bool inclusive;  ///< true: the bound itself is valid (>=, <=)
  };

  /// \param lower, upper the bounds (std::nullopt: unbounded on that side).
  /// \param alsoAllowed values valid outside the bounds (e.g. {-1}).
  /// \throws std::invalid_argument if a bound is not finite or lower > upper.
  NumberValidator(std::optional<Bound> lower, std::optional<Bound> upper, std::vector<T> alsoAllowed = {});

  const std::optional<Bound>& lower() const { return lower_; }
  const std::optional<Bound>& upper() const { return upper_; }

  /// Whether `value` obeys the rule.
  bool accepts(T value) const;

  std::string rule() const override;
  std::string violation(const Teuchos::ParameterEntry& entry) const override;

  /// Teuchos::ParameterEntryValidator: "NumberValidator(int)" / "(double)".
  const std::string getXMLTypeName() const override;
  /// Teuchos::ParameterEntryValidator: the doc string and the rule.
  void printDoc(const std::string& docString, std::ostream& out) const override;
  /// Teuchos::ParameterEntryValidator (used by Teuchos' own
  /// validateParameters()).
  /// \throws Teuchos::Exceptions::InvalidParameterType for a value of another type,
  ///         Teuchos::Exceptions::InvalidParameterValue for a value outside the rule;
  ///         the message names `sublistName`/`paramName`, the rule and the value.
  void validate(const Teuchos::ParameterEntry& entry, const std::string& paramName,
                const std::string& sublistName) const override;

 private:
  std::optional<Bound> lower_, upper_;
  std::vector<T> alsoAllowed_;
};

/// Valid if > `lower` (and finite).
template <class T>
Teuchos::RCP<const NumberValidator<T>> greaterThan(T lower);

/// Valid if >= `lower` (and finite).
template <class T>
Teuchos::RCP<const NumberValidator<T>> atLeast(T lower);

/// How between() treats the ends of its interval.
enum class Interval { Closed, Open, LeftOpen, RightOpen };

/// Valid if in the interval from `lower` to `upper`; Interval::Closed is
/// [lower, upper], Open (lower, upper), LeftOpen (lower, upper], RightOpen
/// [lower, upper).
template <class T>
Teuchos::RCP<const NumberValidator<T>> between(T lower, T upper, Interval ends = Interval::Closed);

/// Any finite double (for coordinates, boundary values, angles).
Teuchos::RCP<const NumberValidator<double>> finiteNumber();

/// A finite double of magnitude at most `maxMagnitude` (closed interval
/// [-max, max], read and reported as "finite with magnitude at most max"):
/// for loads and prescribed values whose products in the element arithmetic
/// (a traction times an area, a displacement squared in a strain) would
/// overflow beyond it.
Teuchos::RCP<const NumberValidator<double>> finiteMagnitude(double maxMagnitude);

/// \brief Parse `text` strictly as a parameter value of type `type`.
///
/// The whole text must be the value (no surrounding blanks, no trailing
/// characters):
///  - "int": an optional sign and decimal digits, within the range of int
///    ("3abc", "2.9", "0x10" and "99999999999" are errors);
///  - "double": what std::strtod accepts as a whole string (decimal or
///    hexadecimal, "nan", "inf"; non-finite values are then refused by the
///    parameter's NumberValidator), not beyond the range of double;
///  - "bool": exactly "true" or "false" (as Teuchos writes them);
///  - "string": any text.
/// \param type "int", "double", "bool" or "string" (the Teuchos type name).
/// \param what how messages name the value, e.g. "--set: parameter 'Newton/Max Iterations'".
/// \return the value, of type int, double, bool or std::string.
/// \throws InputError "<what> expects an integer, got '3abc'" (plus the
///         reason for an out-of-range value); std::invalid_argument for
///         another `type`.
Teuchos::any parseValue(const std::string& type, const std::string& text, const std::string& what);

/// The types parseValue() reads: "int", "double", "bool", "string".
const std::vector<std::string>& parsableTypes();

/// Validate the entries of `user` (this level only) against `valid`:
///  - every entry name of `user` must exist in `valid` (typo -> InputError
///    "unknown parameter 'path/Name'; valid names here are ...");
///  - parameter types must match and validators accept the value: an
///    enumeration lists its names, a NumberValidator gives the rule
///    ("parameter 'Load Stepping/Number of Steps' must be > 0, got 0");
///  - a name that is a sublist in one and a parameter in the other is an error;
///  - missing parameters are set to their defaults (sublists are not created:
///    the component owning a sublist validates it). The defaults are copied
///    without their validators, so that `user` can be written with
///    Teuchos::writeParameterListToXmlFile() and read back as a deck.
/// A valid sublist whose only entry is a sublist named "<...>" (a template,
/// e.g. "Bodies/<Body Name>") accepts any sublist names; those are checked
/// by the caller against the template.
/// \param path parameter path for messages, e.g. "Load Stepping".
void validateLevel(Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                   const std::string& path);

/// Name of the template entry of a valid sublist, or "" if it is not one.
std::string templateName(const Teuchos::ParameterList& valid);

/// Join a parameter path: joinPath("Mesh", "Bodies") == "Mesh/Bodies".
std::string joinPath(const std::string& a, const std::string& b);

/// A file named in a deck as the readers resolve it: an absolute path as
/// given, a relative one against the deck's directory `baseDirectory` ("":
/// the current directory).
std::string resolveDeckFile(const std::string& file, const std::string& baseDirectory);

/// Add `list` as sublist `name` of `pl` with a doc string. (Teuchos'
/// ParameterList::set(name, list, doc) silently drops the doc string of a
/// sublist, so --print-parameters would lose it.)
void setSublist(Teuchos::ParameterList& pl, const std::string& name, const Teuchos::ParameterList& list,
                const std::string& doc);

/// Convenience: an enumeration validator over `names` (values are indices).
Teuchos::RCP<const Teuchos::ParameterEntryValidator> enumValidator(
    const std::vector<std::string>& names, const std::string& paramName);

/// Apply "--set PATH=VALUE": PATH is sublist names joined by '/'. The value
/// is parsed by parseValue() with the type of the existing entry in `user`,
/// else of the entry in `valid` (following "<...>" templates), else guessed
/// (int, double, bool, string). Creates missing sublists, except below a
/// template: a name there must already be in `user` (a body, a boundary
/// condition, a contact pair), so a misspelt one is an error, not a new one.
/// \throws InputError naming the path when the value does not parse, and
///         "--set: no body 'Blok' in 'Mesh/Bodies'; bodies are 'Block'" for
///         a name missing below a template (the noun from its "<Body Name>").
void applyOverride(Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                   const std::string& assignment);

/// Write every valid parameter (type, default, valid values, doc string) as
/// Markdown, one section per sublist. Valid values are the NumberValidator
/// rule of a number ("> 0", "in (-1, 0.5)") or the names of an enumeration.
void printParameterDoc(const Teuchos::ParameterList& valid, std::ostream& os,
                       const std::string& path = "", int level = 2);

}  // namespace ddc
