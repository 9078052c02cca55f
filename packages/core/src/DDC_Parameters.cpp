#include "DDC_Parameters.hpp"

#include <Teuchos_StrUtils.hpp>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <typeinfo>

#include "DDC_Error.hpp"

namespace ddc {

std::string resolveDeckFile(const std::string& file, const std::string& baseDirectory) {
  if (file.empty() || file[0] == '/' || baseDirectory.empty()) return file;
  return baseDirectory + (baseDirectory.back() == '/' ? "" : "/") + file;
}

std::string joinPath(const std::string& a, const std::string& b) {
  if (a.empty()) return b;
  return a + "/" + b;
}

std::string templateName(const Teuchos::ParameterList& valid) {
  if (valid.numParams() != 1) return "";
  auto it = valid.begin();
  const std::string& n = valid.name(it);
  if (n.size() >= 2 && n.front() == '<' && n.back() == '>' && valid.isSublist(n)) return n;
  return "";
}

// ------------------------------------------------------------ NumberValidator

namespace {

/// Shortest text that reads back as the same value ("0.3", "1e-10", "-1").
std::string formatNumber(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string formatNumber(int v) { return std::to_string(v); }

template <class T>
bool isFiniteValue(T v) {
  if constexpr (std::is_floating_point<T>::value) {
    return std::isfinite(v);
  } else {
    (void)v;
    return true;
  }
}

}  // namespace

template <class T>
NumberValidator<T>::NumberValidator(std::optional<Bound> lower, std::optional<Bound> upper, std::vector<T> alsoAllowed)
    : lower_(lower), upper_(upper), alsoAllowed_(std::move(alsoAllowed)) {
  // Programming errors of a getValidParameters(), not user input.
  if ((lower_ && !isFiniteValue(lower_->value)) || (upper_ && !isFiniteValue(upper_->value)))
    throw std::invalid_argument("NumberValidator: the bounds must be finite");
  if (lower_ && upper_ && !(lower_->value < upper_->value || (lower_->value == upper_->value && lower_->inclusive &&
                                                               upper_->inclusive)))
    throw std::invalid_argument("NumberValidator: empty range");
}

template <class T>
bool NumberValidator<T>::accepts(T value) const {
  if (!isFiniteValue(value)) return false;
  for (const T a : alsoAllowed_)
    if (value == a) return true;
  if (lower_ && !(lower_->inclusive ? value >= lower_->value : value > lower_->value)) return false;
  if (upper_ && !(upper_->inclusive ? value <= upper_->value : value < upper_->value)) return false;
  return true;
}

namespace {
/// A closed interval symmetric about 0 (finiteMagnitude()).
template <class T, class B>
bool symmetric(const std::optional<B>& lower, const std::optional<B>& upper, bool noExtra) {
  return noExtra && lower && upper && lower->inclusive && upper->inclusive && lower->value == -upper->value &&
         upper->value > T(0);
}
}  // namespace

template <class T>
std::string NumberValidator<T>::rule() const {
  if (symmetric<T>(lower_, upper_, alsoAllowed_.empty()))
    return "finite with magnitude at most " + formatNumber(upper_->value);
  std::string r;
  for (const T a : alsoAllowed_) r += formatNumber(a) + " or ";
  if (lower_ && upper_) {
    r += std::string("in ") + (lower_->inclusive ? "[" : "(") + formatNumber(lower_->value) + ", " +
         formatNumber(upper_->value) + (upper_->inclusive ? "]" : ")");
  } else if (lower_) {
    r += (lower_->inclusive ? ">= " : "> ") + formatNumber(lower_->value);
  } else if (upper_) {
    r += (upper_->inclusive ? "<= " : "< ") + formatNumber(upper_->value);
  }
  // A one-sided or no bound does not exclude +-inf: say so for doubles.
  if (std::is_floating_point<T>::value && !(lower_ && upper_)) r += (lower_ || upper_) ? " and finite" : "finite";
  return r;
}

template <class T>
std::string NumberValidator<T>::violation(const Teuchos::ParameterEntry& entry) const {
  const std::string type = Teuchos::TypeNameTraits<T>::name();
  if (entry.isList()) return "must be a " + type + ", not a sublist";
  const Teuchos::any& a = entry.getAny(false);
  if (a.type() != typeid(T)) {
    std::ostringstream os;
    os << "must be of type " << type << ", got " << a.typeName() << " (value '" << a << "')";
    return os.str();
  }
  const T v = Teuchos::any_cast<T>(a);
  if (accepts(v)) return "";
  if (symmetric<T>(lower_, upper_, alsoAllowed_.empty()))
    return std::string("must be ") + (isFiniteValue(v) ? rule() : std::string("finite")) + ", got " + formatNumber(v);
  // "must lie in [0, 0.3]" reads better than "must be in [0, 0.3]".
  const bool interval = lower_ && upper_ && alsoAllowed_.empty();
  return std::string("must ") + (interval ? "lie " : "be ") + rule() + ", got " + formatNumber(v);
}

template <class T>
const std::string NumberValidator<T>::getXMLTypeName() const {
  return "NumberValidator(" + Teuchos::TypeNameTraits<T>::name() + ")";
}

template <class T>
void NumberValidator<T>::printDoc(const std::string& docString, std::ostream& out) const {
  Teuchos::StrUtils::printLines(out, "# ", docString);
  out << "#   Valid values: " << rule() << "\n";
}

template <class T>
void NumberValidator<T>::validate(const Teuchos::ParameterEntry& entry, const std::string& paramName,
                                  const std::string& sublistName) const {
  const std::string why = violation(entry);
  if (why.empty()) return;
  const std::string msg = "parameter '" + paramName + "' in list '" + sublistName + "' " + why;
  if (entry.isList() || entry.getAny(false).type() != typeid(T))
    throw Teuchos::Exceptions::InvalidParameterType(msg);
  throw Teuchos::Exceptions::InvalidParameterValue(msg);
}

template class NumberValidator<int>;
template class NumberValidator<double>;

template <class T>
Teuchos::RCP<const NumberValidator<T>> greaterThan(T lower) {
  return Teuchos::rcp(new NumberValidator<T>(typename NumberValidator<T>::Bound{lower, false}, std::nullopt));
}

template <class T>
Teuchos::RCP<const NumberValidator<T>> atLeast(T lower) {
  return Teuchos::rcp(new NumberValidator<T>(typename NumberValidator<T>::Bound{lower, true}, std::nullopt));
}

template <class T>
Teuchos::RCP<const NumberValidator<T>> between(T lower, T upper, Interval ends) {
  const bool lowerIn = ends == Interval::Closed || ends == Interval::RightOpen;
  const bool upperIn = ends == Interval::Closed || ends == Interval::LeftOpen;
  return Teuchos::rcp(new NumberValidator<T>(typename NumberValidator<T>::Bound{lower, lowerIn},
                                             typename NumberValidator<T>::Bound{upper, upperIn}));
}

template Teuchos::RCP<const NumberValidator<int>> greaterThan<int>(int);
template Teuchos::RCP<const NumberValidator<double>> greaterThan<double>(double);
template Teuchos::RCP<const NumberValidator<int>> atLeast<int>(int);
template Teuchos::RCP<const NumberValidator<double>> atLeast<double>(double);
template Teuchos::RCP<const NumberValidator<int>> between<int>(int, int, Interval);
template Teuchos::RCP<const NumberValidator<double>> between<double>(double, double, Interval);

Teuchos::RCP<const NumberValidator<double>> finiteNumber() {
  return Teuchos::rcp(new NumberValidator<double>(std::nullopt, std::nullopt));
}

Teuchos::RCP<const NumberValidator<double>> finiteMagnitude(double maxMagnitude) {
  using B = NumberValidator<double>::Bound;
  return Teuchos::rcp(new NumberValidator<double>(B{-maxMagnitude, true}, B{maxMagnitude, true}));
}

// ------------------------------------------------------------- strict parsing

const std::vector<std::string>& parsableTypes() {
  static const std::vector<std::string> types{"int", "double", "bool", "string"};
  return types;
}

Teuchos::any parseValue(const std::string& type, const std::string& text, const std::string& what) {
  const char* const begin = text.c_str();
  const char* const end = begin + text.size();
  if (type == "int") {
    // std::from_chars: decimal digits with an optional '-', no blanks, no
    // base prefix; a leading '+' is allowed here as in C.
    const char* first = begin;
    if (first != end && *first == '+' && first + 1 != end && std::isdigit(static_cast<unsigned char>(first[1])))
      ++first;
    int v = 0;
    const auto r = std::from_chars(first, end, v);
    if (r.ec == std::errc::result_out_of_range && r.ptr == end)
      DDC_THROW(InputError, what << " expects an integer, got '" << text
                                 << "': out of range, integers are between " << INT_MIN << " and " << INT_MAX);
    DDC_INPUT_REQUIRE(r.ec == std::errc() && r.ptr == end && first != end,
                      what << " expects an integer, got '" << text << "'");
    return Teuchos::any(v);
  }
  if (type == "double") {
    // std::strtod skips leading blanks; the whole text must be the number.
    const bool blank = !text.empty() && std::isspace(static_cast<unsigned char>(text.front()));
    char* stop = nullptr;
    errno = 0;
    const double v = std::strtod(begin, &stop);
    DDC_INPUT_REQUIRE(!text.empty() && !blank && stop == end, what << " expects a number, got '" << text << "'");
    // ERANGE with a finite result is an underflow to (nearly) zero: the
    // value strtod gives is the nearest double, keep it.
    if (errno == ERANGE && std::isinf(v))
      DDC_THROW(InputError, what << " expects a number, got '" << text << "': out of range, numbers are between "
                                 << formatNumber(-std::numeric_limits<double>::max()) << " and "
                                 << formatNumber(std::numeric_limits<double>::max()));
    return Teuchos::any(v);
  }
  if (type == "bool") {
    DDC_INPUT_REQUIRE(text == "true" || text == "false", what << " expects true or false, got '" << text << "'");
    return Teuchos::any(text == "true");
  }
  if (type == "string") return Teuchos::any(text);
  throw std::invalid_argument("parseValue: cannot parse type '" + type + "'");
}

namespace {

std::string validNames(const Teuchos::ParameterList& valid) {
  std::ostringstream os;
  bool first = true;
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    os << (first ? "" : ", ") << "'" << valid.name(it) << "'";
    first = false;
  }
  if (first) os << "(none)";
  return os.str();
}

std::string typeName(const Teuchos::ParameterEntry& e) {
  if (e.isList()) return "sublist";
  return e.getAny(false).typeName();
}

}  // namespace

void validateLevel(Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                   const std::string& path) {
  const std::string where = path.empty() ? std::string("the top level") : "'" + path + "'";
  if (!templateName(valid).empty()) {
    for (auto it = user.begin(); it != user.end(); ++it) {
      const std::string& n = user.name(it);
      DDC_INPUT_REQUIRE(user.isSublist(n), "parameter '" << joinPath(path, n)
                                                         << "' must be a sublist (" << templateName(valid)
                                                         << ")");
    }
    return;
  }
  for (auto it = user.begin(); it != user.end(); ++it) {
    const std::string& n = user.name(it);
    const Teuchos::ParameterEntry* ve = valid.getEntryPtr(n);
    DDC_INPUT_REQUIRE(ve != nullptr, "unknown parameter '" << joinPath(path, n) << "'; valid names in "
                                                           << where << " are " << validNames(valid));
    const Teuchos::ParameterEntry& ue = user.entry(it);
    DDC_INPUT_REQUIRE(ue.isList() == ve->isList(),
                      "parameter '" << joinPath(path, n) << "' must be a " << typeName(*ve) << ", not a "
                                    << typeName(ue));
    if (ue.isList()) continue;
    if (auto rule = Teuchos::rcp_dynamic_cast<const NumberRuleValidator>(ve->validator()); rule.get()) {
      const std::string why = rule->violation(ue);
      DDC_INPUT_REQUIRE(why.empty(), "parameter '" << joinPath(path, n) << "' " << why);
    } else if (ve->validator().get()) {
      try {
        ve->validator()->validate(ue, n, user.name());
      } catch (const std::exception& ex) {
        // Teuchos' message is long; keep its essence but lead with our path.
        std::ostringstream os;
        os << "invalid value for parameter '" << joinPath(path, n) << "'";
        if (auto sv = Teuchos::rcp_dynamic_cast<const Teuchos::StringValidator>(ve->validator());
            sv.get() || ve->validator()->validStringValues().get()) {
          std::ostringstream value;
          value << ue.getAny(false);
          os << ": '" << echoed(value.str()) << "'; valid values are";
          auto vals = ve->validator()->validStringValues();
          for (size_t i = 0; vals.get() && i < vals->size(); ++i) os << (i ? ", '" : " '") << (*vals)[i] << "'";
        } else {
          os << ": " << ex.what();
        }
        throw InputError(os.str());
      }
    } else {
      if (ue.getAny(false).type() != ve->getAny(false).type()) {
        std::ostringstream value;
        value << ue.getAny(false);
        DDC_THROW(InputError, "parameter '" << joinPath(path, n) << "' must be of type " << typeName(*ve) << ", got "
                                            << typeName(ue) << " (value '" << echoed(value.str()) << "')");
      }
    }
  }
  // Fill defaults for missing parameters (not sublists).
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::string& n = valid.name(it);
    const Teuchos::ParameterEntry& ve = valid.entry(it);
    if (ve.isList() || user.isParameter(n)) continue;
    user.setEntry(n, ve);
    // The validator stays with the valid list: Teuchos can write a list with
    // our own validators only with an XML converter for them, and the user's
    // list is written as parameters.xml.
    user.getEntryPtr(n)->setValidator(Teuchos::null);
    user.getEntryPtr(n)->getAny(true);  // not "unused"
  }
}

void setSublist(Teuchos::ParameterList& pl, const std::string& name, const Teuchos::ParameterList& list,
                const std::string& doc) {
  pl.set(name, list);
  pl.getEntryPtr(name)->setDocString(doc);
}

Teuchos::RCP<const Teuchos::ParameterEntryValidator> enumValidator(const std::vector<std::string>& names,
                                                                   const std::string& paramName) {
  Teuchos::Array<std::string> strs(names.begin(), names.end());
  return Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(strs, paramName));
}

namespace {

std::vector<std::string> splitPath(const std::string& p) {
  std::vector<std::string> parts;
  std::string cur;
  for (char c : p) {
    if (c == '/') {
      parts.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  parts.push_back(cur);
  return parts;
}

const Teuchos::ParameterEntry* findValid(const Teuchos::ParameterList* valid,
                                         const std::vector<std::string>& parts) {
  for (size_t i = 0; valid && i < parts.size(); ++i) {
    const std::string t = templateName(*valid);
    const std::string key = t.empty() ? parts[i] : t;
    const Teuchos::ParameterEntry* e = valid->getEntryPtr(key);
    if (!e) return nullptr;
    if (i + 1 == parts.size()) return e;
    if (!e->isList()) return nullptr;
    valid = &Teuchos::getValue<Teuchos::ParameterList>(*e);
  }
  return nullptr;
}

/// "<Body Name>" -> "body", "<Condition Name>" -> "condition".
std::string templateNoun(const std::string& templ) {
  std::string n = templ.substr(1, templ.size() - 2);
  const std::string suffix = " Name";
  if (n.size() > suffix.size() && n.compare(n.size() - suffix.size(), suffix.size(), suffix) == 0)
    n.erase(n.size() - suffix.size());
  for (auto& c : n) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return n;
}

/// "body" -> "bodies", "pair" -> "pairs".
std::string plural(const std::string& noun) {
  if (noun.size() > 1 && noun.back() == 'y' && std::string("aeiou").find(noun[noun.size() - 2]) == std::string::npos)
    return noun.substr(0, noun.size() - 1) + "ies";
  if (!noun.empty() && (noun.back() == 's' || noun.back() == 'x')) return noun + "es";
  return noun + "s";
}

/// The sublist names of `list`, quoted: "'Block', 'Base'".
std::string sublistNames(const Teuchos::ParameterList& list) {
  std::string out;
  for (auto it = list.begin(); it != list.end(); ++it)
    if (list.isSublist(list.name(it))) out += (out.empty() ? "'" : ", '") + list.name(it) + "'";
  return out;
}

/// The type --set guesses for a path no valid list knows.
std::string guessType(const std::string& value) {
  for (const char* t : {"int", "double", "bool"}) {
    try {
      parseValue(t, value, "");
      return t;
    } catch (const InputError&) {
    }
  }
  return "string";
}

void setValue(Teuchos::ParameterList& list, const std::string& name, const Teuchos::any& v) {
  if (v.type() == typeid(int))
    list.set(name, Teuchos::any_cast<int>(v));
  else if (v.type() == typeid(double))
    list.set(name, Teuchos::any_cast<double>(v));
  else if (v.type() == typeid(bool))
    list.set(name, Teuchos::any_cast<bool>(v));
  else
    list.set(name, Teuchos::any_cast<std::string>(v));
}

}  // namespace

void applyOverride(Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                   const std::string& assignment) {
  const auto eq = assignment.find('=');
  DDC_INPUT_REQUIRE(eq != std::string::npos && eq > 0,
                    "--set expects PATH=VALUE, got '" << assignment << "'");
  const std::string path = assignment.substr(0, eq);
  const std::string value = assignment.substr(eq + 1);
  const auto parts = splitPath(path);
  for (const auto& p : parts)
    DDC_INPUT_REQUIRE(!p.empty(), "--set: empty name in parameter path '" << path << "'");
  Teuchos::ParameterList* list = &user;
  const Teuchos::ParameterList* validList = &valid;  // null once off the valid tree
  std::string walked;
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& part = parts[i];
    const std::string templ = validList ? templateName(*validList) : std::string();
    if (!templ.empty()) {
      // Below a template every name is the user's own (a body, a condition,
      // a pair): a missing one is a misspelling, not a new entity to create.
      const std::string noun = templateNoun(templ);
      const std::string names = sublistNames(*list);
      DDC_INPUT_REQUIRE(list->isSublist(part), "--set: no " << noun << " '" << part << "' in '" << walked << "'; "
                                                            << (names.empty() ? "there are no " + plural(noun)
                                                                              : plural(noun) + " are " + names));
    }
    DDC_INPUT_REQUIRE(!list->isParameter(part) || list->isSublist(part),
                      "--set: '" << part << "' in '" << path << "' is a parameter, not a sublist");
    list = &list->sublist(part);
    const std::string key = templ.empty() ? part : templ;
    validList = validList && validList->isSublist(key) ? &validList->sublist(key) : nullptr;
    walked = joinPath(walked, part);
  }
  const std::string& name = parts.back();
  const Teuchos::ParameterEntry* typed = list->getEntryPtr(name);
  if (!typed) typed = findValid(&valid, parts);
  DDC_INPUT_REQUIRE(!(typed && typed->isList()), "--set: '" << path << "' is a sublist, not a parameter");
  const std::string type = typed ? typed->getAny(false).typeName() : guessType(value);
  const auto& types = parsableTypes();
  DDC_INPUT_REQUIRE(std::find(types.begin(), types.end(), type) != types.end(),
                    "--set: parameter '" << path << "' has type " << type << ", which --set cannot parse");
  setValue(*list, name, parseValue(type, value, "--set: parameter '" + path + "'"));
}

void printParameterDoc(const Teuchos::ParameterList& valid, std::ostream& os, const std::string& path,
                       int level) {
  bool any = false;
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const auto& e = valid.entry(it);
    if (e.isList()) continue;
    if (!any) {
      os << "| parameter | type | default | valid values | description |\n| --- | --- | --- | --- | --- |\n";
      any = true;
    }
    std::string doc = e.docString();
    for (auto& c : doc)
      if (c == '\n' || c == '|') c = ' ';
    std::ostringstream def;
    def << e.getAny(false);
    // Valid values: the range of a number, the names of an enumeration.
    std::string vals;
    if (auto rule = Teuchos::rcp_dynamic_cast<const NumberRuleValidator>(e.validator()); rule.get()) {
      vals = "`" + rule->rule() + "`";
    } else if (e.validator().get() && e.validator()->validStringValues().get()) {
      auto v = e.validator()->validStringValues();
      for (size_t i = 0; i < v->size(); ++i) vals += (i ? ", `" : "`") + (*v)[i] + "`";
    }
    os << "| `" << valid.name(it) << "` | " << e.getAny(false).typeName() << " | `" << def.str() << "` | " << vals
       << " | " << doc << " |\n";
  }
  if (any) os << "\n";
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const auto& e = valid.entry(it);
    if (!e.isList()) continue;
    const std::string sub = joinPath(path, valid.name(it));
    os << std::string(level, '#') << " `" << sub << "`\n\n";
    const auto& sl = Teuchos::getValue<Teuchos::ParameterList>(e);
    if (!e.docString().empty()) os << e.docString() << "\n\n";
    printParameterDoc(sl, os, sub, std::min(level + 1, 6));
  }
}

}  // namespace ddc
