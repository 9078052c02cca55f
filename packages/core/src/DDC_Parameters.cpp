#include "DDC_Parameters.hpp"

#include <Teuchos_StrUtils.hpp>
#include <cstdlib>
#include <sstream>

#include "DDC_Error.hpp"

namespace ddc {

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
    if (ve->validator().get()) {
      try {
        ve->validator()->validate(ue, n, user.name());
      } catch (const std::exception& ex) {
        // Teuchos' message is long; keep its essence but lead with our path.
        std::ostringstream os;
        os << "invalid value for parameter '" << joinPath(path, n) << "'";
        if (auto sv = Teuchos::rcp_dynamic_cast<const Teuchos::StringValidator>(ve->validator());
            sv.get() || ve->validator()->validStringValues().get()) {
          os << ": '" << ue.getAny(false) << "'; valid values are";
          auto vals = ve->validator()->validStringValues();
          for (size_t i = 0; vals.get() && i < vals->size(); ++i) os << (i ? ", '" : " '") << (*vals)[i] << "'";
        } else {
          os << ": " << ex.what();
        }
        throw InputError(os.str());
      }
    } else {
      DDC_INPUT_REQUIRE(ue.getAny(false).type() == ve->getAny(false).type(),
                        "parameter '" << joinPath(path, n) << "' must be of type " << typeName(*ve)
                                      << ", got " << typeName(ue) << " (value '" << ue.getAny(false)
                                      << "')");
    }
  }
  // Fill defaults for missing parameters (not sublists).
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::string& n = valid.name(it);
    const Teuchos::ParameterEntry& ve = valid.entry(it);
    if (ve.isList() || user.isParameter(n)) continue;
    user.setEntry(n, ve);
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

template <class T>
bool parseNumber(const std::string& s, T& v) {
  std::istringstream is(s);
  is >> v;
  return !is.fail() && is.eof();
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
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    DDC_INPUT_REQUIRE(!list->isParameter(parts[i]) || list->isSublist(parts[i]),
                      "--set: '" << parts[i] << "' in '" << path << "' is a parameter, not a sublist");
    list = &list->sublist(parts[i]);
  }
  const std::string& name = parts.back();
  const Teuchos::ParameterEntry* typed = list->getEntryPtr(name);
  if (!typed) typed = findValid(&valid, parts);
  DDC_INPUT_REQUIRE(!(typed && typed->isList()), "--set: '" << path << "' is a sublist, not a parameter");
  const std::string type = typed ? typed->getAny(false).typeName() : std::string();
  int iv;
  double dv;
  if (type == "int" || (type.empty() && parseNumber(value, iv))) {
    DDC_INPUT_REQUIRE(parseNumber(value, iv), "--set: parameter '" << path << "' expects an integer, got '"
                                                                   << value << "'");
    list->set(name, iv);
  } else if (type == "double" || (type.empty() && parseNumber(value, dv))) {
    DDC_INPUT_REQUIRE(parseNumber(value, dv), "--set: parameter '" << path << "' expects a number, got '"
                                                                   << value << "'");
    list->set(name, dv);
  } else if (type == "bool" || (type.empty() && (value == "true" || value == "false"))) {
    DDC_INPUT_REQUIRE(value == "true" || value == "false",
                      "--set: parameter '" << path << "' expects true or false, got '" << value << "'");
    list->set(name, value == "true");
  } else {
    DDC_INPUT_REQUIRE(type.empty() || type == "string",
                      "--set: parameter '" << path << "' has type " << type << ", which --set cannot parse");
    list->set(name, value);
  }
}

void printParameterDoc(const Teuchos::ParameterList& valid, std::ostream& os, const std::string& path,
                       int level) {
  bool any = false;
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const auto& e = valid.entry(it);
    if (e.isList()) continue;
    if (!any) {
      os << "| parameter | type | default | description |\n| --- | --- | --- | --- |\n";
      any = true;
    }
    std::string doc = e.docString();
    for (auto& c : doc)
      if (c == '\n' || c == '|') c = ' ';
    std::ostringstream def;
    def << e.getAny(false);
    std::string vals;
    if (e.validator().get() && e.validator()->validStringValues().get()) {
      auto v = e.validator()->validStringValues();
      vals = " One of:";
      for (size_t i = 0; i < v->size(); ++i) vals += (i ? ", `" : " `") + (*v)[i] + "`";
      vals += ".";
    }
    os << "| `" << valid.name(it) << "` | " << e.getAny(false).typeName() << " | `" << def.str() << "` | "
       << doc << vals << " |\n";
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
