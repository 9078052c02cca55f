// Parameter validation with path-qualified messages.
//
// Every configurable class has a static getValidParameters() (default + doc
// string per entry) and validates its own sublist with validateLevel(): a
// misspelt name is an InputError naming the full path and listing the valid
// names, never silently ignored.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <ostream>
#include <string>
#include <vector>

namespace ddc {

/// Validate the entries of `user` (this level only) against `valid`:
///  - every entry name of `user` must exist in `valid` (typo -> InputError
///    "unknown parameter 'path/Name'; valid names here are ...");
///  - parameter types must match and validators (e.g. enumerations) accept
///    the value;
///  - a name that is a sublist in one and a parameter in the other is an error;
///  - missing parameters are set to their defaults (sublists are not created:
///    the component owning a sublist validates it).
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

/// Add `list` as sublist `name` of `pl` with a doc string. (Teuchos'
/// ParameterList::set(name, list, doc) silently drops the doc string of a
/// sublist, so --print-parameters would lose it.)
void setSublist(Teuchos::ParameterList& pl, const std::string& name, const Teuchos::ParameterList& list,
                const std::string& doc);

/// Convenience: an enumeration validator over `names` (values are indices).
Teuchos::RCP<const Teuchos::ParameterEntryValidator> enumValidator(
    const std::vector<std::string>& names, const std::string& paramName);

/// Apply "--set PATH=VALUE": PATH is sublist names joined by '/'. The value
/// is parsed with the type of the existing entry in `user`, else of the
/// entry in `valid` (following "<...>" templates), else guessed
/// (int, double, bool, string). Creates missing sublists.
/// \throws InputError naming the path when the value does not parse.
void applyOverride(Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                   const std::string& assignment);

/// Write every valid parameter (type, default, doc string) as Markdown,
/// one section per sublist.
void printParameterDoc(const Teuchos::ParameterList& valid, std::ostream& os,
                       const std::string& path = "", int level = 2);

}  // namespace ddc
