// Element factory: names -> creators taking a validated Teuchos::ParameterList.
//
// Modelled on Belos::SolverFactory: an explicit object (no hidden global
// registry a test cannot reset); host codes add their own element types with
// add(); create() throws an InputError naming the unknown type and listing
// the known ones.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "DDC_Element.hpp"

namespace ddc {

/// Element types by name (depth (a) of doc/embedding.md): what a body's
/// Element/Type may say. withBuiltins() has the continuum elements; a host
/// adds its own with add(), and the contact package registers the contact
/// elements (Entry::contact).
class ElementFactory {
 public:
  /// Builds an element from its parameter list (already validated against
  /// validParameters, defaults filled in).
  using Creator = std::function<std::shared_ptr<Element>(const Teuchos::ParameterList&)>;

  /// One registered element type.
  struct Entry {
    /// Makes the element from its validated parameters: the body's whole
    /// Element sublist, "Type" included, defaults filled in.
    Creator create;
    /// Valid parameters of this element type, each with default and doc
    /// string (the "Type" entry itself is added by the factory).
    Teuchos::RCP<const Teuchos::ParameterList> validParameters;
    /// One-line description for --print-parameters.
    std::string description;
    /// Number of nodes; with dim it selects the mesh cell type (4 nodes
    /// in 2-D: Quad4, in 3-D: Tet4; ...).
    int numNodes = 4;
    /// Space dimension of the element (Element::dim()).
    int dim = 2;
    /// A contact element (the contact component creates it for a pair),
    /// not a body element type: listed apart in messages and not offered
    /// as a body's Element/Type.
    bool contact = false;
  };

  /// An empty factory.
  ElementFactory() = default;
  /// A factory with every built-in element type registered, one continuum
  /// element (total Lagrangian) per element cell type: "Quad4", "Quad9"
  /// (plane strain), "Hex8", "Hex20", "Hex27", "Tet4", "Tet10".
  static ElementFactory withBuiltins();

  /// Register (or replace) an element type.
  void add(const std::string& typeName, Entry entry);
  /// Whether `typeName` is registered.
  bool has(const std::string& typeName) const { return entries_.count(typeName) != 0; }
  /// Every registered name, sorted.
  std::vector<std::string> names() const;
  /// names() of the body element types (Entry::contact false).
  std::vector<std::string> bodyNames() const;
  /// names() of the contact elements (Entry::contact true).
  std::vector<std::string> contactNames() const;
  /// \throws InputError naming `typeName` and listing known types.
  const Entry& entry(const std::string& typeName, const std::string& where = "") const;

  /// Create an element. `params` is the "Element" sublist: it must hold
  /// "Type" and otherwise the type's valid parameters; it is validated
  /// (misspelt names are errors) and defaults are filled in.
  /// \param params the "Element" sublist (validated and filled in place)
  /// \param where parameter path used in error messages, e.g.
  ///        "Mesh/Bodies/Upper Ring/Element".
  /// \throws InputError for an unknown or missing Type or a misspelt or
  ///         out-of-range parameter, naming its path.
  std::shared_ptr<Element> create(Teuchos::ParameterList& params, const std::string& where) const;

  /// The complete valid list create() checks an "Element" sublist of
  /// this type against: "Type" (doc string lists the known types) plus the
  /// entry's validParameters. For --print-parameters.
  /// \throws InputError if `typeName` is not registered.
  Teuchos::RCP<const Teuchos::ParameterList> validParametersFor(const std::string& typeName) const;

 private:
  std::map<std::string, Entry> entries_;
};

}  // namespace ddc
