#include "DDC_ElementFactory.hpp"

#include <sstream>
#include <stdexcept>

#include "DDC_ContinuumElement.hpp"
#include "DDC_Error.hpp"
#include "DDC_Material.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

/// The registered type names for messages and doc strings: "'Quad4', 'Quad9'".
std::string knownNames(const std::vector<std::string>& names) { return quotedNames(names, "(none registered)"); }

/// Validate the sublists of `user` below one level against `valid`: the
/// "Material" sublist through createMaterial (so its value checks, E > 0 and
/// the range of nu, apply with the right path), any other sublist with
/// validateLevel recursively (host element types may have their own).
/// Missing sublists are created so their defaults show in an echo of the input.
void validateSublists(Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                      const std::string& path) {
  const std::string tmpl = templateName(valid);
  if (!tmpl.empty()) {
    // "<Name>" template: every user sublist follows the template.
    const auto& t = valid.sublist(tmpl);
    for (auto it = user.begin(); it != user.end(); ++it) {
      const std::string& n = user.name(it);
      Teuchos::ParameterList& sub = user.sublist(n);
      const std::string subPath = joinPath(path, n);
      validateLevel(sub, t, subPath);
      validateSublists(sub, t, subPath);
    }
    return;
  }
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    if (!valid.entry(it).isList()) continue;
    const std::string& n = valid.name(it);
    Teuchos::ParameterList& sub = user.sublist(n);
    const std::string subPath = joinPath(path, n);
    if (n == "Material") {
      createMaterial(sub, subPath);
    } else {
      const auto& vsub = valid.sublist(n);
      validateLevel(sub, vsub, subPath);
      validateSublists(sub, vsub, subPath);
    }
  }
}

/// Creator shared by the built-in continuum elements: the factory has
/// validated the list already, so the material path only matters for a
/// direct call of the creator.
ElementFactory::Creator continuumCreator(CellType cell) {
  return [cell](const Teuchos::ParameterList& p) -> std::shared_ptr<Element> {
    Teuchos::ParameterList m = p.isSublist("Material") ? p.sublist("Material") : Teuchos::ParameterList();
    return makeContinuumElement(cell, createMaterial(m, "Material"));
  };
}

/// One-line description of the built-in continuum element of a cell type.
const char* continuumDescription(CellType cell) {
  switch (cell) {
    case CellType::Quad4:
      return "Bilinear 4-node quadrilateral, plane strain, total Lagrangian, 2x2 Gauss.";
    case CellType::Quad9:
      return "Biquadratic 9-node Lagrange quadrilateral, plane strain, total Lagrangian, 3x3 Gauss.";
    case CellType::Hex8:
      return "Trilinear 8-node hexahedron, total Lagrangian, 2x2x2 Gauss.";
    case CellType::Hex20:
      return "Serendipity 20-node hexahedron (8-node faces), total Lagrangian, 3x3x3 Gauss.";
    case CellType::Hex27:
      return "Triquadratic 27-node Lagrange hexahedron, total Lagrangian, 3x3x3 Gauss.";
    case CellType::Tet4:
      return "Linear 4-node tetrahedron, total Lagrangian, 1 point (exact: F is constant).";
    case CellType::Tet10:
      return "Quadratic 10-node tetrahedron, total Lagrangian, 4-point degree-2 rule.";
    default:
      DDC_THROW(std::logic_error, "no continuum element for cell type " << cellTypeName(cell));
  }
}

}  // namespace

ElementFactory ElementFactory::withBuiltins() {
  ElementFactory f;
  for (CellType cell : elementCellTypes())
    f.add(cellTypeName(cell), Entry{continuumCreator(cell), ContinuumElement::getValidParameters(),
                                    continuumDescription(cell), numCellNodes(cell), cellDimension(cell)});
  return f;
}

void ElementFactory::add(const std::string& typeName, Entry entry) {
  // Registration mistakes are programming errors of the host code.
  if (typeName.empty()) throw std::invalid_argument("ElementFactory::add: empty type name");
  if (!entry.create) throw std::invalid_argument("ElementFactory::add('" + typeName + "'): no creator");
  if (entry.validParameters.is_null()) entry.validParameters = Teuchos::rcp(new Teuchos::ParameterList("Element"));
  if (entry.validParameters->isParameter("Type"))
    throw std::invalid_argument("ElementFactory::add('" + typeName +
                                "'): valid parameters must not contain 'Type' (the factory adds it)");
  entries_[typeName] = std::move(entry);
}

std::vector<std::string> ElementFactory::names() const {
  std::vector<std::string> n;
  n.reserve(entries_.size());
  for (const auto& e : entries_) n.push_back(e.first);
  return n;
}

std::vector<std::string> ElementFactory::bodyNames() const {
  std::vector<std::string> n;
  for (const auto& e : entries_)
    if (!e.second.contact) n.push_back(e.first);
  return n;
}

std::vector<std::string> ElementFactory::contactNames() const {
  std::vector<std::string> n;
  for (const auto& e : entries_)
    if (e.second.contact) n.push_back(e.first);
  return n;
}

namespace {
/// "known element types are 'Hex8', ...", and the contact elements apart.
std::string knownTypes(const ElementFactory& f) {
  std::string s = "known element types are " + knownNames(f.bodyNames());
  const auto contact = f.contactNames();
  if (!contact.empty()) s += " (and the contact elements, made by the contact component: " + knownNames(contact) + ")";
  return s;
}
}  // namespace

const ElementFactory::Entry& ElementFactory::entry(const std::string& typeName, const std::string& where) const {
  auto it = entries_.find(typeName);
  DDC_INPUT_REQUIRE(it != entries_.end(),
                    "unknown element type '" << typeName << "'"
                                             << (where.empty() ? std::string()
                                                               : " in parameter '" + joinPath(where, "Type") + "'")
                                             << "; " << knownTypes(*this));
  return it->second;
}

Teuchos::RCP<const Teuchos::ParameterList> ElementFactory::validParametersFor(const std::string& typeName) const {
  const Entry& e = entry(typeName);
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Element"));
  pl->set("Type", typeName,
          "Element type; one of " + knownNames(names()) + ". '" + typeName + "': " + e.description);
  pl->setParameters(*e.validParameters);
  return pl;
}

std::shared_ptr<Element> ElementFactory::create(Teuchos::ParameterList& params, const std::string& where) const {
  const std::string typePath = joinPath(where, "Type");
  DDC_INPUT_REQUIRE(params.isParameter("Type") && !params.isSublist("Type"),
                    "missing parameter '" << typePath << "'; " << knownTypes(*this));
  DDC_INPUT_REQUIRE(params.isType<std::string>("Type"),
                    "parameter '" << typePath << "' must be a string; " << knownTypes(*this));
  const std::string type = params.get<std::string>("Type");
  const Entry& e = entry(type, where);
  const auto valid = validParametersFor(type);
  validateLevel(params, *valid, where);
  validateSublists(params, *valid, where);
  std::shared_ptr<Element> el;
  try {
    el = e.create(params);
  } catch (const Teuchos::Exceptions::InvalidParameter& ex) {
    // The list was validated and its defaults filled: a parameter the
    // creator cannot read is one its entry does not declare (or declares
    // with another type) — a registration mistake of the host code.
    const std::string what = ex.what();
    const auto open = what.find('"'), close = open == std::string::npos ? open : what.find('"', open + 1);
    const std::string name = close == std::string::npos ? std::string("?") : what.substr(open + 1, close - open - 1);
    DDC_THROW(std::logic_error, "element type '" << type << "' (" << where << "): its creator read the parameter '"
                                                  << name << "' as a type its factory entry does not declare; every "
                                                             "parameter an element reads must be in the entry's "
                                                             "validParameters, with its type and default "
                                                             "(doc/embedding.md, 'An own element type')");
  }
  if (!el) DDC_THROW(std::logic_error, "element creator for '" << type << "' returned null");
  if (el->numNodes() != e.numNodes)
    DDC_THROW(std::logic_error, "element type '" << type << "' registered with " << e.numNodes
                                                 << " nodes creates elements with " << el->numNodes());
  if (el->dim() != e.dim)
    DDC_THROW(std::logic_error, "element type '" << type << "' registered as " << e.dim
                                                 << "-D creates " << el->dim() << "-D elements");
  return el;
}

}  // namespace ddc
