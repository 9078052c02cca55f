// What the two Exodus II mesh readers share (DDC_ExodusMesh.hpp): the open
// file and its header checked for one body - the file's sizes, the element
// block that is the body - and the checks of the entities read from it,
// each with the message that names the file and the entity. The reader of
// the whole body (readExodusBody()) and the reader of a range of its
// elements (readExodusBodyInRange()) give the same message for the same
// fault. The Exodus II library's header stays inside the .cpp files.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "DDC_Mesh.hpp"

namespace ddc {

/// An Exodus II file open for reading, closed on scope exit.
class ExodusFile {
 public:
  /// Opens `name`; a classic netCDF file must hold all the data its header
  /// declares (doc/user-guide.md, "Checks of a mesh file").
  /// \param context what names the file in messages: "'<parameter>' (body '<name>')"
  /// \throws InputError "<context>: Exodus II file '<name>': <what>"
  ExodusFile(const std::string& name, const std::string& context);
  ~ExodusFile();
  ExodusFile(const ExodusFile&) = delete;
  ExodusFile& operator=(const ExodusFile&) = delete;
  /// The library's file id.
  int id() const { return id_; }
  /// Throws InputError: "<context>: Exodus II file '<name>': <what>".
  [[noreturn]] void fail(const std::string& what) const;
  /// Checks a library call's status (< 0: "cannot read <what>: ...").
  void check(int status, const std::string& what) const;
  /// The kinds of numbered objects of a file.
  enum class Objects { ElementBlocks, NodeSets, SideSets };
  /// Ids of the objects of a kind.
  std::vector<int> ids(Objects kind, const char* what) const;
  /// Names of the objects of a kind ("" where the file has none).
  std::vector<std::string> names(Objects kind, int count, const char* what) const;

 private:
  void requireWholeClassicFile() const;
  enum class Format { Classic, Hdf5, Other };
  Format format() const;
  double bytes() const;

  std::string name_, context_;
  int id_ = -1;
};

/// The file's header as one body reads it: the file's sizes and the element
/// block that is the body, checked in the order the readers check them.
class ExodusBodyHeader {
 public:
  /// Reads the sizes (the file's dimension must be the body's, or 3 for a
  /// 2-D body) and chooses the block: `wantedBlock` by name or id, or the
  /// file's only block.
  /// \param path the body's "Exodus" parameter path, for messages
  ExodusBodyHeader(const ExodusFile& ex, const std::string& bodyName, CellType type, const std::string& path,
                   const std::string& wantedBlock);
  /// The block's elements are of the body's type, and there are some.
  void checkBlock() const;

  int fileDim() const { return dim_; }
  int fileNodes() const { return numNodes_; }
  int fileElements() const { return numElems_; }
  int blockId() const { return ids_[block_]; }
  int blockSize() const { return size_[block_]; }
  /// 0-based file element number of the block's first element (elements
  /// are numbered across the blocks in block order).
  int firstFileElement() const { return firstElem_; }
  /// "element block '<name or id>'".
  const std::string& blockLabel() const { return blockLabel_; }

  /// \name The entity checks, each with the whole reader's message
  ///@{
  /// Connectivity entry `n` (1-based file node number) exists.
  void requireFileNode(int n) const;
  /// Node n (0-based) of the block has admissible coordinates: a 2-D body's
  /// nodes lie in z = 0, every coordinate within Mesh::kMaxCoordinate.
  void requireAdmissibleNode(int n, const std::array<double, 3>& x) const;
  /// Element e of the block (0-based), with these corners, is valid by
  /// cornerJacobian().
  void requireValidElement(int e, const std::array<std::array<double, 3>, 8>& corners) const;
  /// Entry `v` of node set `name` is a node of the file.
  void requireSetNode(const std::string& name, int v) const;
  /// The facet of the block's element of entry (elem, side) of side set
  /// `name` (file numbers, 1-based): -1 if the element is of another block.
  /// \return the facet in referenceCell(type).facets
  int sideSetFacet(const std::string& name, int elem, int side) const;
  ///@}

  /// The name a set is given: its name in the file, or "nodeset_<id>" /
  /// "sideset_<id>".
  static std::string setName(ExodusFile::Objects kind, const std::string& name, int id);

 private:
  const ExodusFile& ex_;
  std::string bodyName_;
  CellType type_;
  int bodyDim_, nen_;
  int dim_ = 0, numNodes_ = 0, numElems_ = 0;  ///< of the file
  std::vector<int> ids_, size_, nodesPerElement_;
  std::vector<std::string> names_, type_names_;  ///< type names upper case
  int block_ = -1;
  std::string blockLabel_;
  int firstElem_ = 0;
};

/// The file of an Exodus II body, open: `params` (the body's "Exodus"
/// sublist) validated against ExodusMeshReader::getValidParameters(), its
/// "File" required and resolved against `baseDirectory`.
/// \throws InputError naming the parameter or the file
std::unique_ptr<ExodusFile> openExodusBodyFile(Teuchos::ParameterList& params, const std::string& bodyName,
                                               const std::string& path, const std::string& baseDirectory);

}  // namespace ddc
