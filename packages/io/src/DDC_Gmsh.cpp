#include "DDC_Gmsh.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

/// Line-oriented reader of an MSH file with error messages that name the
/// file, the line and the section.
class MshLines {
 public:
  explicit MshLines(const std::string& file) : file_(file), in_(file) {}
  bool isOpen() const { return static_cast<bool>(in_); }
  const std::string& file() const { return file_; }
  int lineNumber() const { return line_; }

  /// Next non-empty line, or false at end of file.
  bool next(std::string& line) {
    while (std::getline(in_, line)) {
      ++line_;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.find_first_not_of(" \t") != std::string::npos) return true;
    }
    return false;
  }
  /// Next non-empty line inside `section`; a missing line means truncation.
  std::string nextIn(const std::string& section) {
    std::string line;
    if (!next(line))
      fail("unexpected end of file in section $" + section + " (the file is truncated; expected $End" +
           section + ")");
    if (line[0] == '$')
      fail("section $" + section + " ends early: found '" + line + "' where more data was expected "
           "(the section is truncated or its counts are wrong)");
    return line;
  }
  /// Next line, tokenised, with at least `minTokens` tokens.
  std::vector<std::string> tokens(const std::string& section, size_t minTokens, const char* what) {
    std::vector<std::string> t = split(nextIn(section));
    if (t.size() < minTokens) {
      std::ostringstream os;
      os << "in section $" << section << " expected " << what << " (" << minTokens << " values), found "
         << t.size() << " value(s)";
      fail(os.str());
    }
    return t;
  }
  void expectEnd(const std::string& section) {
    std::string line;
    if (!next(line)) fail("unexpected end of file: missing $End" + section);
    if (trim(line) != "$End" + section)
      fail("expected $End" + section + ", found '" + line +
           "' (the counts in the section do not match its contents)");
  }
  /// Skip an unsupported section up to its end marker.
  void skipSection(const std::string& section) {
    std::string line;
    while (next(line))
      if (trim(line) == "$End" + section) return;
    fail("unexpected end of file in section $" + section + " (missing $End" + section + ")");
  }

  [[noreturn]] void fail(const std::string& msg) const {
    DDC_THROW(InputError, "Gmsh file '" << file_ << "', line " << line_ << ": " << msg);
  }

  long long toInt(const std::string& s, const char* what) const {
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(s.c_str(), &end, 10);
    if (s.empty() || *end != '\0' || errno != 0) fail(std::string("expected an integer ") + what + ", found '" + s + "'");
    return v;
  }
  /// Coordinate `axis` of node `tag`: a number within the coordinate limit
  /// Mesh::kMaxCoordinate (doc/user-guide.md, "Checks of a mesh file").
  double toCoordinate(const std::string& s, char axis, long long tag) const {
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0') fail(std::string("expected a number (") + axis + "), found '" + s + "'");
    if (!Mesh::admissibleCoordinate(v)) {
      std::ostringstream os;
      os << "node " << tag << " has " << axis << " = " << s << "; every coordinate must be a finite number within +-"
         << Mesh::kMaxCoordinate
         << " (the coordinate limit: lengths this large overflow in the element arithmetic): fix the node or "
            "choose other length units";
      fail(os.str());
    }
    if (errno == ERANGE) fail(std::string("expected a number (") + axis + "), found '" + s + "'");
    return v;
  }
  int toCount(const std::string& s, const char* what) const {
    const long long v = toInt(s, what);
    if (v < 0 || v > 2000000000LL) fail(std::string("invalid ") + what + " '" + s + "'");
    return static_cast<int>(v);
  }

  static std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out;
    size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i >= line.size()) break;
      size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
      out.push_back(line.substr(i, j - i));
      i = j;
    }
    return out;
  }
  static std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos) return "";
    const auto e = s.find_last_not_of(" \t");
    return s.substr(b, e - b + 1);
  }

 private:
  std::string file_;
  std::ifstream in_;
  int line_ = 0;
};

/// A Gmsh element type: its number of nodes, dimension and a name for
/// messages (gmsh.info, "MSH file format", element types).
struct GmshType {
  int type, numNodes, dim;
  const char* name;  ///< plural, as in "has 8-node hexahedra (type 5)"
};

/// The element types the reader knows by name; nullptr for others.
const GmshType* gmshType(int type) {
  static const GmshType table[] = {
      {1, 2, 1, "2-node lines"},          {2, 3, 2, "3-node triangles"},     {3, 4, 2, "4-node quadrangles"},
      {4, 4, 3, "4-node tetrahedra"},     {5, 8, 3, "8-node hexahedra"},     {6, 6, 3, "6-node prisms"},
      {7, 5, 3, "5-node pyramids"},       {8, 3, 1, "3-node lines"},         {9, 6, 2, "6-node triangles"},
      {10, 9, 2, "9-node quadrangles"},   {11, 10, 3, "10-node tetrahedra"}, {12, 27, 3, "27-node hexahedra"},
      {13, 18, 3, "18-node prisms"},      {14, 14, 3, "14-node pyramids"},   {15, 1, 0, "points"},
      {16, 8, 2, "8-node quadrangles"},   {17, 20, 3, "20-node hexahedra"},  {18, 15, 3, "15-node prisms"},
      {19, 13, 3, "13-node pyramids"},    {26, 4, 1, "4-node lines"},        {29, 20, 3, "20-node tetrahedra"},
      {92, 64, 3, "64-node hexahedra"},   {93, 125, 3, "125-node hexahedra"}};
  for (const auto& t : table)
    if (t.type == type) return &t;
  return nullptr;
}

/// "8-node hexahedra (type 5)", or "elements of type 42 (unknown to
/// DDContact)".
std::string gmshTypeText(int type) {
  const GmshType* t = gmshType(type);
  return t ? std::string(t->name) + " (type " + std::to_string(type) + ")"
           : "elements of type " + std::to_string(type) + " (unknown to DDContact)";
}

/// The Gmsh type of a DDContact cell type (Gmsh and DDContact share the
/// node order, DDC_ReferenceCell.hpp).
int gmshTypeOf(CellType t) {
  switch (t) {
    case CellType::Line2: return 1;
    case CellType::Tri3: return 2;
    case CellType::Quad4: return 3;
    case CellType::Tet4: return 4;
    case CellType::Hex8: return 5;
    case CellType::Line3: return 8;
    case CellType::Tri6: return 9;
    case CellType::Quad9: return 10;
    case CellType::Tet10: return 11;
    case CellType::Hex27: return 12;
    case CellType::Quad8: return 16;
    case CellType::Hex20: return 17;
  }
  return -1;
}

/// Number of nodes of the Gmsh element types whose connectivity the reader
/// keeps: the cells and facets of DDContact's cell types, and points.
int gmshNumNodes(int type) {
  for (CellType t : {CellType::Line2, CellType::Line3, CellType::Tri3, CellType::Tri6, CellType::Quad4, CellType::Quad8,
                     CellType::Quad9, CellType::Hex8, CellType::Hex20, CellType::Hex27, CellType::Tet4, CellType::Tet10})
    if (gmshTypeOf(t) == type) return numCellNodes(t);
  return type == 15 ? 1 : -1;  // points; -1: not needed (rejected or skipped)
}

/// How to make Gmsh write elements of cell type t.
const char* gmshOptionsFor(CellType t) {
  switch (t) {
    case CellType::Hex20: return "Mesh.ElementOrder=2, Mesh.SecondOrderIncomplete=1";
    case CellType::Hex27:
    case CellType::Quad9: return "Mesh.ElementOrder=2, Mesh.SecondOrderIncomplete=0";
    case CellType::Tet10: return "Mesh.ElementOrder=2";
    default: return "Mesh.ElementOrder=1";
  }
}

bool isTriangle(int type) {
  // 3, 6, 9, 10, 12, 15 (incomplete and complete), 21, 28, 36, 45, 55, 66 node triangles
  static const std::set<int> tri{2, 9, 20, 21, 22, 23, 24, 25, 42, 43, 44, 45, 46, 52, 53, 54, 55, 56};
  return tri.count(type) != 0;
}

using EntityKey = std::pair<int, int>;  // (dimension, entity tag)

struct ElementBlock {
  int dim = 0, entity = 0, type = 0;
  int line = 0;                  // line of the block header
  std::vector<long long> tags;   // element tags
  std::vector<int> lines;        // line of each element
  std::vector<long long> nodes;  // node tags, numNodes per element
  int numNodes = 0;
  // The first element with a wrong node count in a block whose check is
  // left to the body that reads it (parseElements), if any.
  std::string countError;
  int countErrorLine = 0;
};

struct MshData {
  std::map<EntityKey, std::string> physicalNames;   // (dim, physical tag) -> name
  std::map<EntityKey, std::vector<int>> entityPhysicals;  // (dim, entity tag) -> physical tags
  bool hasEntities = false;
  bool hasNodes = false, hasElements = false;
  std::unordered_map<long long, std::array<double, 3>> nodes;  // tag -> x, y, z
  std::map<int, std::vector<long long>> pointNodes;           // point entity -> node tags
  std::vector<ElementBlock> blocks;                            // 0-D to 3-D blocks
};

void parseMeshFormat(MshLines& in) {
  const auto t = in.tokens("MeshFormat", 3, "'version file-type data-size'");
  const std::string& version = t[0];
  if (version != "4.1")
    in.fail("MSH version " + version + " is not supported; expected version 4.1 (save with "
            "Mesh.MshFileVersion=4.1 or 'gmsh -format msh41')");
  if (t[1] != "0")
    in.fail("binary MSH files are not supported (file-type " + t[1] + "); save as ASCII (Mesh.Binary=0)");
  in.expectEnd("MeshFormat");
}

void parsePhysicalNames(MshLines& in, MshData& d) {
  const int n = in.toCount(in.tokens("PhysicalNames", 1, "the number of physical names")[0], "count");
  for (int k = 0; k < n; ++k) {
    const std::string line = in.nextIn("PhysicalNames");
    const auto t = MshLines::split(line);
    const auto q0 = line.find('"'), q1 = line.rfind('"');
    if (t.size() < 3 || q0 == std::string::npos || q1 == q0)
      in.fail("expected 'dimension physicalTag \"name\"' in section $PhysicalNames, found '" + line + "'");
    const int dim = static_cast<int>(in.toInt(t[0], "(dimension)"));
    const int tag = static_cast<int>(in.toInt(t[1], "(physical tag)"));
    d.physicalNames[{dim, std::abs(tag)}] = line.substr(q0 + 1, q1 - q0 - 1);
  }
  in.expectEnd("PhysicalNames");
}

void parseEntities(MshLines& in, MshData& d) {
  d.hasEntities = true;
  const auto c = in.tokens("Entities", 4, "'numPoints numCurves numSurfaces numVolumes'");
  int count[4];
  for (int k = 0; k < 4; ++k) count[k] = in.toCount(c[k], "entity count");
  for (int dim = 0; dim < 4; ++dim) {
    // points: tag x y z nPhys phys...; others: tag 6 bounding-box values nPhys phys... nBound bound...
    const size_t first = dim == 0 ? 4 : 7;
    for (int k = 0; k < count[dim]; ++k) {
      const auto t = in.tokens("Entities", first + 1, dim == 0 ? "a point entity" : "a curve/surface/volume entity");
      const int tag = static_cast<int>(in.toInt(t[0], "(entity tag)"));
      const int np = in.toCount(t[first], "number of physical tags");
      if (t.size() < first + 1 + np) in.fail("entity " + t[0] + " lists fewer physical tags than announced");
      std::vector<int> phys;
      for (int p = 0; p < np; ++p)
        phys.push_back(std::abs(static_cast<int>(in.toInt(t[first + 1 + p], "(physical tag)"))));
      if (!phys.empty()) d.entityPhysicals[{dim, tag}] = phys;
    }
  }
  in.expectEnd("Entities");
}

void parseNodes(MshLines& in, MshData& d) {
  d.hasNodes = true;
  const auto h = in.tokens("Nodes", 4, "'numEntityBlocks numNodes minNodeTag maxNodeTag'");
  const int nb = in.toCount(h[0], "number of entity blocks");
  const int total = in.toCount(h[1], "number of nodes");
  d.nodes.reserve(total);
  int read = 0;
  for (int b = 0; b < nb; ++b) {
    const auto t = in.tokens("Nodes", 4, "'entityDim entityTag parametric numNodesInBlock'");
    const int dim = static_cast<int>(in.toInt(t[0], "(entity dimension)"));
    const int entity = static_cast<int>(in.toInt(t[1], "(entity tag)"));
    const bool parametric = in.toInt(t[2], "(parametric flag)") != 0;
    const int n = in.toCount(t[3], "number of nodes in block");
    std::vector<long long> tags(n);
    for (int k = 0; k < n; ++k) tags[k] = in.toInt(in.tokens("Nodes", 1, "a node tag")[0], "(node tag)");
    // Parametric blocks add u (curves) or u v (surfaces) after x y z.
    const size_t nc = 3 + (parametric ? static_cast<size_t>(std::max(0, std::min(dim, 2))) : 0);
    for (int k = 0; k < n; ++k) {
      const auto x = in.tokens("Nodes", nc, "node coordinates 'x y z'");
      const std::array<double, 3> p{in.toCoordinate(x[0], 'x', tags[k]), in.toCoordinate(x[1], 'y', tags[k]),
                                    in.toCoordinate(x[2], 'z', tags[k])};
      if (!d.nodes.emplace(tags[k], p).second)
        in.fail("node tag " + std::to_string(tags[k]) + " appears twice in section $Nodes");
    }
    if (dim == 0) d.pointNodes[entity].insert(d.pointNodes[entity].end(), tags.begin(), tags.end());
    read += n;
  }
  if (read != total)
    in.fail("section $Nodes announces " + std::to_string(total) + " nodes but its blocks hold " +
            std::to_string(read));
  in.expectEnd("Nodes");
}

void parseElements(MshLines& in, MshData& d) {
  d.hasElements = true;
  const auto h = in.tokens("Elements", 4, "'numEntityBlocks numElements minElementTag maxElementTag'");
  const int nb = in.toCount(h[0], "number of entity blocks");
  const int total = in.toCount(h[1], "number of elements");
  int read = 0;
  for (int b = 0; b < nb; ++b) {
    const auto t = in.tokens("Elements", 4, "'entityDim entityTag elementType numElementsInBlock'");
    ElementBlock blk;
    blk.dim = static_cast<int>(in.toInt(t[0], "(entity dimension)"));
    blk.entity = static_cast<int>(in.toInt(t[1], "(entity tag)"));
    blk.type = static_cast<int>(in.toInt(t[2], "(element type)"));
    const int n = in.toCount(t[3], "number of elements in block");
    blk.line = in.lineNumber();
    blk.numNodes = gmshNumNodes(blk.type);
    // Element types we cannot use are kept without their connectivity: the
    // caller decides (from the body's selection) whether they are an error.
    for (int k = 0; k < n; ++k) {
      const auto e = in.tokens("Elements", 1, "an element 'tag nodeTags...'");
      if (blk.numNodes < 0) continue;
      if (e.size() != static_cast<size_t>(blk.numNodes) + 1) {
        const std::string msg = "element " + e[0] + " of type " + std::to_string(blk.type) + " must list " +
                                std::to_string(blk.numNodes) + " node tags, found " + std::to_string(e.size() - 1);
        // The types a 2-D body reads are checked here; the others (3-D cells,
        // triangles, 8-node quadrangles) when a body reads them, after it
        // has rejected them if it cannot use them at all.
        if (blk.type == 1 || blk.type == 3 || blk.type == 8 || blk.type == 10 || blk.type == 15) in.fail(msg);
        if (blk.countError.empty()) {
          blk.countError = msg;
          blk.countErrorLine = in.lineNumber();
        }
        continue;
      }
      blk.tags.push_back(in.toInt(e[0], "(element tag)"));
      blk.lines.push_back(in.lineNumber());
      for (int i = 1; i <= blk.numNodes; ++i) blk.nodes.push_back(in.toInt(e[i], "(node tag)"));
    }
    if (blk.numNodes < 0) blk.tags.assign(n, 0);  // remember the count only
    d.blocks.push_back(std::move(blk));
    read += n;
  }
  if (read != total)
    in.fail("section $Elements announces " + std::to_string(total) + " elements but its blocks hold " +
            std::to_string(read));
  in.expectEnd("Elements");
}

MshData parseMsh(const std::string& fileName) {
  MshLines in(fileName);
  DDC_INPUT_REQUIRE(in.isOpen(), "cannot open Gmsh file '" << fileName << "' (missing or unreadable)");
  MshData d;
  std::string line;
  bool first = true;
  while (in.next(line)) {
    const std::string name = MshLines::trim(line);
    if (first && name != "$MeshFormat") in.fail("not a Gmsh MSH file: expected '$MeshFormat' on the first line");
    if (first) {
      parseMeshFormat(in);
      first = false;
      continue;
    }
    if (name.empty() || name[0] != '$') in.fail("expected a section header '$Name', found '" + line + "'");
    const std::string sec = name.substr(1);
    if (sec == "PhysicalNames") {
      parsePhysicalNames(in, d);
    } else if (sec == "Entities") {
      parseEntities(in, d);
    } else if (sec == "Nodes") {
      parseNodes(in, d);
    } else if (sec == "Elements") {
      parseElements(in, d);
    } else if (sec == "PartitionedEntities") {
      in.fail("partitioned MSH files are not supported; save the unpartitioned mesh "
              "(DDContact partitions it itself)");
    } else if (sec.compare(0, 3, "End") == 0) {
      in.fail("unexpected '" + line + "' outside its section");
    } else {
      in.skipSection(sec);  // $Periodic, $NodeData, ... carry nothing we use
    }
  }
  if (first) in.fail("empty file: expected '$MeshFormat'");
  if (!d.hasNodes) in.fail("no $Nodes section");
  if (!d.hasElements) in.fail("no $Elements section");
  return d;
}

std::string physicalName(const MshData& d, int dim, int tag) {
  auto it = d.physicalNames.find({dim, tag});
  return it != d.physicalNames.end() ? it->second : std::to_string(tag);
}

const std::vector<int>& physicalsOf(const MshData& d, int dim, int entity) {
  static const std::vector<int> none;
  auto it = d.entityPhysicals.find({dim, entity});
  return it != d.entityPhysicals.end() ? it->second : none;
}

/// Twice the signed area of the corner polygon of a 2-D element.
double twiceArea(const std::vector<std::array<double, 3>>& xy, CellType type, const int* n) {
  double a = 0.0;
  for (const auto& side : referenceCell(type).facets) {
    const auto& p = xy[n[side.nodes[0]]];
    const auto& q = xy[n[side.nodes[1]]];
    a += p[0] * q[1] - q[0] * p[1];
  }
  return a;
}

const char* const kEntityWord[4] = {"point", "curve", "surface", "volume"};

/// The DDContact element cell types of dimension dim, for messages.
std::string supportedVolumeTypes() {
  std::ostringstream os;
  bool first = true;
  for (CellType t : elementCellTypes())
    if (cellDimension(t) == 3) {
      os << (first ? "" : ", ") << gmshTypeText(gmshTypeOf(t)) << " for " << cellTypeName(t);
      first = false;
    }
  return os.str();
}

}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> GmshReader::getValidParameters() {
  static Teuchos::RCP<const Teuchos::ParameterList> valid;
  if (valid.is_null()) {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("Gmsh"));
    pl->set("File", std::string(""),
            "Gmsh MSH 4.1 ASCII file (required); a relative path is resolved against the directory "
            "of the input deck");
    pl->set("Physical Surface", std::string(""),
            "2-D bodies: name of the physical surface whose 2-D elements form this body; empty: every 2-D "
            "element of the file");
    pl->set("Physical Volume", std::string(""),
            "3-D bodies: name of the physical volume whose 3-D elements form this body; empty: every 3-D "
            "element of the file");
    valid = pl;
  }
  return valid;
}

int readGmshBody(Mesh& mesh, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                 const std::string& path, const std::string& baseDirectory) {
  validateLevel(params, *GmshReader::getValidParameters(), path);
  const std::string file = params.get<std::string>("File");
  DDC_INPUT_REQUIRE(!file.empty(), "parameter '" << joinPath(path, "File")
                                                 << "' is required: the Gmsh .msh file of body '" << bodyName
                                                 << "'");
  // The selecting group has the body's dimension; the other parameter is a
  // mistake (a 3-D body's physical surfaces are its side sets).
  const bool solid = cellDimension(type) == 3;
  const std::string used = solid ? "Physical Volume" : "Physical Surface";
  const std::string other = solid ? "Physical Surface" : "Physical Volume";
  DDC_INPUT_REQUIRE(params.get<std::string>(other).empty(),
                    "parameter '" << joinPath(path, other) << "' does not apply to body '" << bodyName
                                  << "': its element type " << cellTypeName(type) << " is "
                                  << cellDimension(type) << "-D, so '" << used << "' selects its elements"
                                  << (solid ? " (its physical surfaces become side sets)" : ""));
  const std::string resolved = resolveDeckFile(file, baseDirectory);
  try {
    return readGmshFile(mesh, bodyName, type, resolved, params.get<std::string>(used));
  } catch (const InputError& e) {
    // Lead with the parameter path so the user finds the deck entry.
    DDC_THROW(InputError, "'" << joinPath(path, "File") << "' (body '" << bodyName << "'): " << e.what());
  }
}

namespace {

/// One body read from the parsed file by readGmshFile(), in the steps of
/// read(). Every check fails with an InputError naming the file (and the
/// line where the check has one); nothing touches the mesh before commit(),
/// so an error leaves it intact.
class GmshBodyReader {
 public:
  GmshBodyReader(const MshData& d, const std::string& fileName, const std::string& bodyName, CellType type,
                 const std::string& physicalGroup)
      : d_(d),
        fileName_(fileName),
        bodyName_(bodyName),
        physicalGroup_(physicalGroup),
        type_(type),
        ref_(referenceCell(type)),
        dim_(ref_.dim),
        solid_(dim_ == 3),
        quad9_(type == CellType::Quad9),
        wantElement_(gmshTypeOf(type)),
        facetType_(ref_.facets[0].type),
        wantFacet_(gmshTypeOf(facetType_)),
        nen_(ref_.numNodes),
        groupWord_(std::string("physical ") + kEntityWord[dim_]),
        facetGroupWord_(std::string("physical ") + kEntityWord[dim_ - 1]),
        facetWord_(solid_ ? "face element " : "line element "),
        dimWord_(std::to_string(dim_) + "-D") {}

  /// Reads the body into `mesh`; returns its index.
  int read(Mesh& mesh) {
    selectBodyGroup();
    collectBodyBlocks();
    numberNodes();
    buildConnectivity();
    indexFacets();
    readSideSets();
    readNodeSets();
    return commit(mesh);
  }

 private:
  using ElementFacet = std::pair<int, int>;  // (element, local facet)

  [[noreturn]] void fail(const std::string& msg) const {
    DDC_THROW(InputError, "Gmsh file '" << fileName_ << "': " << msg);
  }
  [[noreturn]] void failAt(int line, const std::string& msg) const {
    DDC_THROW(InputError, "Gmsh file '" << fileName_ << "', line " << line << ": " << msg);
  }
  /// A bad element `l` of a side set block: 3-D messages name its line.
  [[noreturn]] void failSideSet(const ElementBlock& b, size_t l, const std::string& msg) const {
    if (solid_) failAt(b.lines[l], msg);
    fail(msg);
  }

  /// 1. The tag of the physical surface (2-D) / volume (3-D) selecting the
  /// body's elements; -1 without a selection.
  void selectBodyGroup() {
    if (physicalGroup_.empty()) return;
    std::set<std::string> groups;
    for (const auto& kv : d_.physicalNames)
      if (kv.first.first == dim_) {
        groups.insert(kv.second);
        if (kv.second == physicalGroup_) selectedTag_ = kv.first.second;
      }
    if (selectedTag_ < 0) {
      std::string hint;
      for (const auto& kv : d_.physicalNames)
        if (kv.second == physicalGroup_ && kv.first.first != dim_)
          hint = " ('" + physicalGroup_ + "' is a physical " + kEntityWord[kv.first.first] + ")";
      fail("no " + groupWord_ + " named '" + physicalGroup_ + "'; " + groupWord_ + "s are " + quotedNames(groups) +
           hint);
    }
    if (!d_.hasEntities) fail("a $Entities section is needed to select " + groupWord_ + " '" + physicalGroup_ + "'");
  }

  bool selected(const ElementBlock& b) const {
    if (b.dim != dim_) return false;
    if (selectedTag_ < 0) return true;
    const auto& ph = physicalsOf(d_, dim_, b.entity);
    return std::find(ph.begin(), ph.end(), selectedTag_) != ph.end();
  }

  /// 2. The blocks of the body's elements, type-checked.
  void collectBodyBlocks() {
    for (const auto& b : d_.blocks) {
      if (b.dim == 3 && !solid_)
        failAt(b.line, "3-D elements (type " + std::to_string(b.type) + ", volume " + std::to_string(b.entity) +
                           ") are not supported in body '" + bodyName_ + "' of 2-D element type " +
                           cellTypeName(type_) + "; a 3-D mesh needs a 3-D element type (Hex8, Hex20, Hex27, Tet4, "
                           "Tet10)");
      if (selected(b)) bodyBlocks_.push_back(&b);
    }
    if (solid_)
      for (const auto* b : bodyBlocks_)
        if (b->type != bodyBlocks_.front()->type)
          failAt(b->line, "mixed element types in one body: volume " + std::to_string(bodyBlocks_.front()->entity) +
                              " (line " + std::to_string(bodyBlocks_.front()->line) + ") has " +
                              gmshTypeText(bodyBlocks_.front()->type) + ", volume " + std::to_string(b->entity) +
                              " has " + gmshTypeText(b->type) + "; body '" + bodyName_ +
                              "' has one element type: give each element type its own physical volume and body");
    for (const auto* b : bodyBlocks_) checkElementType(*b);
    for (const auto* b : bodyBlocks_) numElems_ += b->tags.size();
    if (numElems_ == 0) {
      if (!physicalGroup_.empty()) fail(groupWord_ + " '" + physicalGroup_ + "' has no " + dimWord_ + " elements");
      if (solid_)
        fail("no 3-D elements found (expected " + gmshTypeText(wantElement_) + "). Note: once physical groups "
             "exist, Gmsh saves only their elements: define a Physical Volume for the body or set Mesh.SaveAll=1");
      fail("no 2-D elements found (expected quadrangles). Note: once physical groups exist, Gmsh saves only "
           "their elements: define a Physical Surface for the body or set Mesh.SaveAll=1");
    }
  }

  /// A block of the body has the body's element type with every node count
  /// right, or the read fails saying what was expected.
  void checkElementType(const ElementBlock& b) const {
    if (b.type == wantElement_) {
      if (!b.countError.empty()) failAt(b.countErrorLine, b.countError);
      return;
    }
    std::ostringstream os;
    if (solid_) {
      os << "volume " << b.entity << " has " << gmshTypeText(b.type);
      const GmshType* t = gmshType(b.type);
      if (gmshNumNodes(b.type) > 0 && t->dim == 3)
        os << " but body '" << bodyName_ << "' has element type " << cellTypeName(type_) << "; expected "
           << gmshTypeText(wantElement_) << " (" << gmshOptionsFor(type_) << ")";
      else
        os << ", which DDContact does not support; a 3-D body reads " << supportedVolumeTypes();
      failAt(b.line, os.str());
    }
    os << "surface " << b.entity << " has elements of type " << b.type;
    if (isTriangle(b.type))
      os << ": triangles are not supported; mesh with quadrangles (Mesh.RecombineAll=1)";
    else if (b.type == 16)
      os << " (8-node quadrangles): not supported; use complete 9-node quadrangles "
            "(Mesh.SecondOrderIncomplete=0) with element type Quad9";
    else if (b.type == 3 || b.type == 10)
      os << " (" << (b.type == 3 ? "4" : "9") << "-node quadrangles) but body '" << bodyName_
         << "' has element type " << cellTypeName(type_) << "; expected "
         << (quad9_ ? "9-node quadrangles (type 10; Mesh.ElementOrder=2, Mesh.SecondOrderIncomplete=0)"
                    : "4-node quadrangles (type 3; Mesh.ElementOrder=1)");
    else
      os << ": not supported; expected " << (quad9_ ? "9" : "4") << "-node quadrangles (type " << wantElement_
         << ")";
    fail(os.str());
  }

  /// 3. Compact node numbering: the used nodes in increasing tag order.
  void numberNodes() {
    std::vector<long long> used;
    for (const auto* b : bodyBlocks_) used.insert(used.end(), b->nodes.begin(), b->nodes.end());
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    local_.reserve(used.size());
    xyz_.resize(used.size());
    for (size_t k = 0; k < used.size(); ++k) {
      auto it = d_.nodes.find(used[k]);
      if (it == d_.nodes.end())
        fail("an element references node tag " + std::to_string(used[k]) + ", which is not in $Nodes");
      const auto& p = it->second;
      const double scale = std::max({1.0, std::abs(p[0]), std::abs(p[1])});
      if (!solid_ && std::abs(p[2]) > 1e-10 * scale) {
        std::ostringstream os;
        os << "node " << used[k] << " has z = " << p[2] << "; only planar meshes in the plane z = 0 are supported";
        fail(os.str());
      }
      local_[used[k]] = static_cast<int>(k);
      xyz_[k] = {p[0], p[1], solid_ ? p[2] : 0.0};
    }
  }

  /// 4. Connectivity (local node indices): 2-D counter-clockwise, 3-D valid.
  void buildConnectivity() {
    conn_.reserve(numElems_ * nen_);
    for (const auto* b : bodyBlocks_) {
      for (size_t e = 0; e < b->tags.size(); ++e) {
        int n[27];
        for (int i = 0; i < nen_; ++i) n[i] = local_.at(b->nodes[e * nen_ + i]);
        if (solid_)
          checkVolumeElement(*b, e, n);
        else
          orientQuadrangle(*b, e, n);
        conn_.insert(conn_.end(), n, n + nen_);
        elemEntity_.push_back(b->entity);
      }
    }
    ne_ = static_cast<int>(elemEntity_.size());
  }

  /// Gmsh writes positively oriented volume elements; anything else was
  /// edited or written by another tool, and is not guessed at.
  void checkVolumeElement(const ElementBlock& b, size_t e, const int* n) const {
    std::array<std::array<double, 3>, 8> corners;
    for (int i = 0; i < ref_.numCorners; ++i) corners[i] = xyz_[n[i]];
    const CornerJacobian j = cornerJacobian(type_, corners.data());
    if (j.verdict != CornerJacobian::Verdict::Valid)
      failAt(b.lines[e], "element " + std::to_string(b.tags[e]) + " (volume " + std::to_string(b.entity) +
                             ") of body '" + bodyName_ + "' is " + describeCornerJacobian(type_, j));
  }

  /// A quadrangle with non-zero area, counter-clockwise (reordered if not).
  void orientQuadrangle(const ElementBlock& b, size_t e, int* n) const {
    const double a2 = twiceArea(xyz_, type_, n);
    double h2 = 0.0;  // squared longest corner-to-corner distance, for scale
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        h2 = std::max(h2, std::pow(xyz_[n[i]][0] - xyz_[n[j]][0], 2) + std::pow(xyz_[n[i]][1] - xyz_[n[j]][1], 2));
    if (!(std::abs(a2) > 1e-12 * h2))
      fail("element " + std::to_string(b.tags[e]) + " has zero area (degenerate quadrangle)");
    if (a2 < 0) {
      // Clockwise (surface normal -z): reverse to 0 3 2 1; the mid-side
      // nodes follow their sides: (0-3)=7, (3-2)=6, (2-1)=5, (1-0)=4.
      static const int perm4[4] = {0, 3, 2, 1};
      static const int perm9[9] = {0, 3, 2, 1, 7, 6, 5, 4, 8};
      int m[9];
      for (int i = 0; i < nen_; ++i) m[i] = n[quad9_ ? perm9[i] : perm4[i]];
      std::copy(m, m + nen_, n);
    }
  }

  /// 5. Element facets: sorted corners -> (element, local facet).
  void indexFacets() {
    facetCorners_ = referenceCell(facetType_).numCorners;
    for (int e = 0; e < ne_; ++e) {
      const int* n = &conn_[static_cast<size_t>(e) * nen_];
      for (int f = 0; f < static_cast<int>(ref_.facets.size()); ++f) {
        std::vector<int> key(facetCorners_);
        for (int i = 0; i < facetCorners_; ++i) key[i] = n[ref_.facets[f].nodes[i]];
        std::sort(key.begin(), key.end());
        facets_[key].push_back({e, f});
      }
    }
  }

  /// 6. Physical curves (2-D) / surfaces (3-D) -> side sets (element, local facet).
  void readSideSets() {
    std::map<std::string, std::set<ElementFacet>> seen;
    for (const auto& b : d_.blocks) {
      if (b.dim != dim_ - 1) continue;
      const auto& phys = physicalsOf(d_, dim_ - 1, b.entity);
      if (phys.empty()) continue;
      const std::string firstName = physicalName(d_, dim_ - 1, phys[0]);
      if (b.type != wantFacet_) failSideSetType(b, firstName);
      if (!b.countError.empty()) failAt(b.countErrorLine, b.countError);
      readSideSetBlock(b, phys, firstName, seen);
    }
  }

  /// A block of a side set whose elements are not the body's facets.
  [[noreturn]] void failSideSetType(const ElementBlock& b, const std::string& firstName) const {
    std::ostringstream os;
    os << facetGroupWord_ << " '" << firstName << "' (" << kEntityWord[dim_ - 1] << " " << b.entity
       << ") has elements of type " << b.type;
    if (!solid_) {
      os << "; body '" << bodyName_ << "' (" << cellTypeName(type_) << ") expects "
         << (quad9_ ? "3-node lines (type 8)" : "2-node lines (type 1)");
      fail(os.str());
    }
    const GmshType* t = gmshType(b.type);
    if (t && t->dim != 2)
      os << " (" << t->name << ", " << t->dim << "-D): a side set of a 3-D body is made of 2-D faces";
    else
      os << " (" << (t ? t->name : "unknown to DDContact") << ") but the faces of body '" << bodyName_ << "' ("
         << cellTypeName(type_) << ") are " << cellTypeName(facetType_);
    os << "; expected " << gmshTypeText(wantFacet_);
    failAt(b.line, os.str());
  }

  /// The facets of one side set block into the side sets of its physical
  /// groups (`seen`: what each set has, so that it lists a facet once).
  void readSideSetBlock(const ElementBlock& b, const std::vector<int>& phys, const std::string& firstName,
                        std::map<std::string, std::set<ElementFacet>>& seen) {
    const int nf = b.numNodes;
    for (size_t l = 0; l < b.tags.size(); ++l) {
      std::vector<int> n(nf);
      bool inBody = true;
      for (int i = 0; i < nf; ++i) {
        auto it = local_.find(b.nodes[l * nf + i]);
        inBody = inBody && it != local_.end();
        n[i] = inBody ? it->second : -1;
      }
      const std::string what =
          facetWord_ + std::to_string(b.tags[l]) + " of " + facetGroupWord_ + " '" + firstName + "'";
      if (!inBody) {
        if (selectedTag_ >= 0) continue;  // a facet of another body
        failSideSet(b, l, what + " has a node that belongs to no " + dimWord_ + " element");
      }
      const ElementFacet es = boundaryFacetOf(b, l, n, what);
      for (int pt : phys) {
        const std::string name = physicalName(d_, dim_ - 1, pt);
        if (seen[name].insert(es).second) facetSets_[name].push_back(es);
      }
    }
  }

  /// The element facet that side set element `l` (local nodes `n`) is: on
  /// the boundary, with the same higher-order nodes.
  ElementFacet boundaryFacetOf(const ElementBlock& b, size_t l, const std::vector<int>& n,
                               const std::string& what) const {
    std::vector<int> key(n.begin(), n.begin() + facetCorners_);
    std::sort(key.begin(), key.end());
    auto it = facets_.find(key);
    if (it == facets_.end())
      failSideSet(b, l,
                  what + (solid_ ? " is not on the boundary of any element (its corners are not the corners of an "
                                   "element face)"
                                 : " is not on the boundary of any element (its end nodes are not the corners of an "
                                   "element side)"));
    if (it->second.size() != 1)
      failSideSet(b, l,
                  what + (solid_ ? " lies inside the body (on a face shared by two elements)"
                                 : " lies inside the body (on a side shared by two elements)") +
                      "; side sets must lie on the boundary");
    const auto es = it->second[0];
    // Higher-order nodes: the same as the element facet's (as a set: the
    // facet's orientation comes from the element, not from the file).
    const auto& fn = ref_.facets[es.second].nodes;
    std::vector<int> mine(n.begin() + facetCorners_, n.end()), theirs;
    for (size_t i = facetCorners_; i < fn.size(); ++i)
      theirs.push_back(conn_[static_cast<size_t>(es.first) * nen_ + fn[i]]);
    std::sort(mine.begin(), mine.end());
    std::sort(theirs.begin(), theirs.end());
    if (mine != theirs)
      failSideSet(b, l,
                  solid_ ? "the mid-edge / centre nodes of " + what + " are not those of the element face it lies on"
                         : "the middle node of " + what + " is not the mid-side node of the element side it lies on");
    return es;
  }

  /// 7. Physical points, curves (3-D) and surfaces / volumes -> node sets.
  void readNodeSets() {
    readPointNodeSets();
    if (solid_) readCurveNodeSets();
    for (int e = 0; e < ne_; ++e)
      for (int pt : physicalsOf(d_, dim_, elemEntity_[e])) {
        auto& s = nodeSets_[physicalName(d_, dim_, pt)];
        s.insert(s.end(), &conn_[static_cast<size_t>(e) * nen_], &conn_[static_cast<size_t>(e) * nen_] + nen_);
      }
  }

  void readPointNodeSets() {
    std::map<int, std::vector<long long>> pointNodes = d_.pointNodes;
    for (const auto& b : d_.blocks)
      if (b.dim == 0 && b.type == 15)
        pointNodes[b.entity].insert(pointNodes[b.entity].end(), b.nodes.begin(), b.nodes.end());
    for (const auto& kv : pointNodes) {
      const auto& phys = physicalsOf(d_, 0, kv.first);
      for (long long tag : kv.second) {
        auto it = local_.find(tag);
        for (int pt : phys) {
          const std::string name = physicalName(d_, 0, pt);
          if (it == local_.end()) {
            if (selectedTag_ >= 0) continue;
            fail("physical point '" + name + "' (node " + std::to_string(tag) + ") belongs to no " + dimWord_ +
                 " element");
          }
          nodeSets_[name].push_back(it->second);
        }
      }
    }
  }

  /// Physical curves of a 3-D body: edges, e.g. for a line support.
  void readCurveNodeSets() {
    for (const auto& b : d_.blocks) {
      if (b.dim != 1) continue;
      const auto& phys = physicalsOf(d_, 1, b.entity);
      if (phys.empty()) continue;
      const std::string firstName = physicalName(d_, 1, phys[0]);
      if (b.type != 1 && b.type != 8)
        failAt(b.line, "physical curve '" + firstName + "' (curve " + std::to_string(b.entity) + ") has " +
                           gmshTypeText(b.type) + "; expected 2-node lines (type 1) or 3-node lines (type 8)");
      for (size_t l = 0; l < b.tags.size(); ++l) {
        std::vector<int> n;
        for (int i = 0; i < b.numNodes; ++i) {
          auto it = local_.find(b.nodes[l * b.numNodes + i]);
          if (it != local_.end()) n.push_back(it->second);
        }
        if (static_cast<int>(n.size()) != b.numNodes) {
          if (selectedTag_ >= 0) continue;  // a line of another body
          failAt(b.lines[l], "line element " + std::to_string(b.tags[l]) + " of physical curve '" + firstName +
                                 "' has a node that belongs to no 3-D element");
        }
        for (int pt : phys) {
          auto& s = nodeSets_[physicalName(d_, 1, pt)];
          s.insert(s.end(), n.begin(), n.end());
        }
      }
    }
  }

  /// 8. Commit: the body, its nodes, elements and sets into the mesh.
  int commit(Mesh& mesh) {
    const int body = mesh.beginBody(bodyName_, type_);
    const int firstNode = mesh.numNodes();
    const int firstElement = mesh.numElements();
    for (const auto& p : xyz_) mesh.addNode(p[0], p[1], p[2]);
    for (int e = 0; e < ne_; ++e) {
      int n[27];
      for (int i = 0; i < nen_; ++i) n[i] = firstNode + conn_[static_cast<size_t>(e) * nen_ + i];
      mesh.addElement(n);
    }
    for (const auto& kv : facetSets_) {
      std::vector<Segment> segs;
      for (const auto& es : kv.second) segs.push_back(mesh.makeSegment(firstElement + es.first, es.second));
      mesh.addSideSet(body, kv.first, std::move(segs));
    }
    for (auto& kv : nodeSets_) {
      for (int& n : kv.second) n += firstNode;
      mesh.addNodeSet(body, kv.first, std::move(kv.second));
    }
    return body;
  }

  // the input and what follows from the body's element type
  const MshData& d_;
  const std::string& fileName_;
  const std::string& bodyName_;
  const std::string& physicalGroup_;
  const CellType type_;
  const ReferenceCell& ref_;
  const int dim_;
  const bool solid_;
  const bool quad9_;
  const int wantElement_;
  const CellType facetType_;
  const int wantFacet_;
  const int nen_;
  const std::string groupWord_;       ///< selects the body
  const std::string facetGroupWord_;  ///< side sets
  const std::string facetWord_;
  const std::string dimWord_;
  // what the steps find, in their order
  int selectedTag_ = -1;
  std::vector<const ElementBlock*> bodyBlocks_;
  size_t numElems_ = 0;
  std::unordered_map<long long, int> local_;  ///< node tag -> local node index
  std::vector<std::array<double, 3>> xyz_;
  std::vector<int> conn_;
  std::vector<int> elemEntity_;
  int ne_ = 0;
  int facetCorners_ = 0;
  std::map<std::vector<int>, std::vector<ElementFacet>> facets_;
  std::map<std::string, std::vector<ElementFacet>> facetSets_;
  std::map<std::string, std::vector<int>> nodeSets_;
};

}  // namespace

int readGmshFile(Mesh& mesh, const std::string& bodyName, CellType type, const std::string& fileName,
                 const std::string& physicalGroup) {
  const MshData d = parseMsh(fileName);
  return GmshBodyReader(d, fileName, bodyName, type, physicalGroup).read(mesh);
}

}  // namespace ddc
