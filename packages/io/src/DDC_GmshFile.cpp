// Parsing a Gmsh MSH 4.1 file, whole or what a rank keeps of it, and the
// checks of one body that both readers make (DDC_GmshFile.hpp).
#include "DDC_GmshFile.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_Parameters.hpp"

namespace ddc::gmsh {

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
  d.groupsAfterElements = d.groupsAfterElements || d.hasElements;
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
  d.groupsAfterElements = d.groupsAfterElements || d.hasElements;
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

/// A tag that appears twice: thrown in a whole read; in a read in ranges
/// only the tag's owner sees both, so it notes the first and reads on.
void duplicateNode(MshLines& in, MshData& d, const MshKeep* keep, long long tag) {
  const std::string msg = "node tag " + std::to_string(tag) + " appears twice in section $Nodes";
  if (!keep) in.fail(msg);
  if (d.faultLine != 0) return;
  try {
    in.fail(msg);
  } catch (const InputError& e) {
    d.faultLine = in.lineNumber();
    d.fault = e.what();
  }
}

void parseNodes(MshLines& in, MshData& d, const MshKeep* keep) {
  const auto h = in.tokens("Nodes", 4, "'numEntityBlocks numNodes minNodeTag maxNodeTag'");
  const int nb = in.toCount(h[0], "number of entity blocks");
  const int total = in.toCount(h[1], "number of nodes");
  if (!d.hasNodes) {
    d.minNodeTag = in.toInt(h[2], "(minimum node tag)");
    d.maxNodeTag = in.toInt(h[3], "(maximum node tag)");
  }
  d.hasNodes = true;
  d.nodes.reserve(keep ? total / keep->ranks + 1 : total);
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
      if (keep && nodeOwner(d, tags[k], keep->ranks) != keep->rank) continue;
      if (!d.nodes.emplace(tags[k], p).second) duplicateNode(in, d, keep, tags[k]);
    }
    if (dim == 0) d.pointNodes[entity].insert(d.pointNodes[entity].end(), tags.begin(), tags.end());
    read += n;
  }
  if (read != total)
    in.fail("section $Nodes announces " + std::to_string(total) + " nodes but its blocks hold " +
            std::to_string(read));
  in.expectEnd("Nodes");
}

/// Which elements of a block a rank keeps: [from, to) of its `count`;
/// `bodyIndex` counts the body's elements before the block.
std::pair<long long, long long> keptElements(const MshData& d, const MshKeep* keep, const ElementBlock& blk,
                                             long long count, long long& bodyIndex) {
  if (!keep || blk.dim < keep->bodyDim) return {0, count};
  if (blk.dim > keep->bodyDim) return {0, 0};
  if (!keep->group.empty()) {
    int tag = -1;
    for (const auto& kv : d.physicalNames)
      if (kv.first.first == blk.dim && kv.second == keep->group) tag = kv.first.second;
    const auto& ph = physicalsOf(d, blk.dim, blk.entity);
    if (tag < 0 || std::find(ph.begin(), ph.end(), tag) == ph.end()) return {0, 0};
  }
  const long long first = bodyIndex;
  bodyIndex += count;
  const long long from = std::clamp(keep->first - first, 0LL, count);
  return {from, std::clamp(keep->last - first, from, count)};
}

void parseElements(MshLines& in, MshData& d, const MshKeep* keep) {
  d.hasElements = true;
  const auto h = in.tokens("Elements", 4, "'numEntityBlocks numElements minElementTag maxElementTag'");
  const int nb = in.toCount(h[0], "number of entity blocks");
  const int total = in.toCount(h[1], "number of elements");
  int read = 0;
  long long bodyIndex = 0;
  for (int b = 0; b < nb; ++b) {
    const auto t = in.tokens("Elements", 4, "'entityDim entityTag elementType numElementsInBlock'");
    ElementBlock blk;
    blk.dim = static_cast<int>(in.toInt(t[0], "(entity dimension)"));
    blk.entity = static_cast<int>(in.toInt(t[1], "(entity tag)"));
    blk.type = static_cast<int>(in.toInt(t[2], "(element type)"));
    const int n = in.toCount(t[3], "number of elements in block");
    blk.line = in.lineNumber();
    blk.numNodes = gmshNumNodes(blk.type);
    blk.count = n;
    // Element types we cannot use are counted, their connectivity not kept:
    // the caller decides (from the body's selection) whether they are an error.
    const auto [from, to] = keptElements(d, keep, blk, n, bodyIndex);
    blk.keptFrom = blk.numNodes < 0 ? 0 : from;
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
      const long long tag = in.toInt(e[0], "(element tag)");
      std::array<long long, 27> nodes;
      for (int i = 1; i <= blk.numNodes; ++i) nodes[i - 1] = in.toInt(e[i], "(node tag)");
      if (k < from || k >= to) continue;
      blk.tags.push_back(tag);
      blk.lines.push_back(in.lineNumber());
      blk.nodes.insert(blk.nodes.end(), nodes.begin(), nodes.begin() + blk.numNodes);
    }
    d.blocks.push_back(std::move(blk));
    read += n;
  }
  if (read != total)
    in.fail("section $Elements announces " + std::to_string(total) + " elements but its blocks hold " +
            std::to_string(read));
  in.expectEnd("Elements");
}

void parseSections(MshLines& in, MshData& d, const MshKeep* keep) {
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
      parseNodes(in, d, keep);
    } else if (sec == "Elements") {
      parseElements(in, d, keep);
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

MshData parseMsh(const std::string& fileName, const MshKeep* keep) {
  MshLines in(fileName);
  DDC_INPUT_REQUIRE(in.isOpen(), "cannot open Gmsh file '" << fileName << "' (missing or unreadable)");
  MshData d;
  if (!keep) {
    parseSections(in, d, keep);
    return d;
  }
  try {
    parseSections(in, d, keep);
  } catch (const InputError& e) {
    // This fault comes after a noted duplicate tag, if any: the first stays.
    if (d.faultLine == 0) {
      d.faultLine = std::max(1, in.lineNumber());
      d.fault = e.what();
    }
  }
  return d;
}

int nodeOwner(const MshData& d, long long tag, int ranks) {
  const long long span = d.maxNodeTag - d.minNodeTag + 1;
  if (span <= 0 || tag < d.minNodeTag) return 0;
  if (tag > d.maxNodeTag) return ranks - 1;
  // The last rank r whose share starts at or before the tag.
  const long long i = tag - d.minNodeTag;
  int r = int(std::min<long long>(ranks - 1, (i * ranks) / span));
  while (r + 1 < ranks && evenShareStart(span, r + 1, ranks) <= i) ++r;
  while (r > 0 && evenShareStart(span, r, ranks) > i) --r;
  return r;
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

GmshBody::GmshBody(const MshData& d, const std::string& fileName, const std::string& bodyName, CellType type,
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
      facetCorners_(referenceCell(facetType_).numCorners),
      groupWord_(std::string("physical ") + kEntityWord[dim_]),
      facetGroupWord_(std::string("physical ") + kEntityWord[dim_ - 1]),
      facetWord_(solid_ ? "face element " : "line element "),
      dimWord_(std::to_string(dim_) + "-D") {}

void GmshBody::fail(const std::string& msg) const {
  DDC_THROW(InputError, "Gmsh file '" << fileName_ << "': " << msg);
}

void GmshBody::failAt(int line, const std::string& msg) const {
  DDC_THROW(InputError, "Gmsh file '" << fileName_ << "', line " << line << ": " << msg);
}

void GmshBody::failSideSet(const ElementBlock& b, size_t l, const std::string& msg) const {
  if (solid_) failAt(b.lines[l], msg);
  fail(msg);
}

void GmshBody::selectBodyGroup() {
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

bool GmshBody::selected(const ElementBlock& b) const {
  if (b.dim != dim_) return false;
  if (selectedTag_ < 0) return true;
  const auto& ph = physicalsOf(d_, dim_, b.entity);
  return std::find(ph.begin(), ph.end(), selectedTag_) != ph.end();
}

/// 2. The blocks of the body's elements, type-checked.
void GmshBody::collectBodyBlocks() {
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
  for (const auto* b : bodyBlocks_) numElems_ += b->count;
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
void GmshBody::checkElementType(const ElementBlock& b) const {
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

/// A block of a side set whose elements are not the body's facets.
void GmshBody::failSideSetType(const ElementBlock& b, const std::string& firstName) const {
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

void GmshBody::requireNode(long long tag, const std::array<double, 3>* p) const {
  if (!p) fail("an element references node tag " + std::to_string(tag) + ", which is not in $Nodes");
  const double scale = std::max({1.0, std::abs((*p)[0]), std::abs((*p)[1])});
  if (!solid_ && std::abs((*p)[2]) > 1e-10 * scale) {
    std::ostringstream os;
    os << "node " << tag << " has z = " << (*p)[2] << "; only planar meshes in the plane z = 0 are supported";
    fail(os.str());
  }
}

/// Gmsh writes positively oriented volume elements; anything else was
/// edited or written by another tool, and is not guessed at.
void GmshBody::checkVolumeElement(const ElementBlock& b, size_t e, const int* n,
                                  const std::vector<std::array<double, 3>>& xyz) const {
  std::array<std::array<double, 3>, 8> corners;
  for (int i = 0; i < ref_.numCorners; ++i) corners[i] = xyz[n[i]];
  const CornerJacobian j = cornerJacobian(type_, corners.data());
  if (j.verdict != CornerJacobian::Verdict::Valid)
    failAt(b.lines[e], "element " + std::to_string(b.tags[e]) + " (volume " + std::to_string(b.entity) +
                           ") of body '" + bodyName_ + "' is " + describeCornerJacobian(type_, j));
}

void GmshBody::orientQuadrangle(const ElementBlock& b, size_t e, int* n,
                                const std::vector<std::array<double, 3>>& xyz) const {
  const double a2 = twiceArea(xyz, type_, n);
  double h2 = 0.0;  // squared longest corner-to-corner distance, for scale
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      h2 = std::max(h2, std::pow(xyz[n[i]][0] - xyz[n[j]][0], 2) + std::pow(xyz[n[i]][1] - xyz[n[j]][1], 2));
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

void GmshBody::readSideSets(const SideVerdict& verdict, const AddSide& add) const {
  for (const auto& b : d_.blocks) {
    if (b.dim != dim_ - 1) continue;
    const auto& phys = physicalsOf(d_, dim_ - 1, b.entity);
    if (phys.empty()) continue;
    const std::string firstName = physicalName(d_, dim_ - 1, phys[0]);
    if (b.type != wantFacet_) failSideSetType(b, firstName);
    if (!b.countError.empty()) failAt(b.countErrorLine, b.countError);
    for (size_t l = 0; l < b.tags.size(); ++l) {
      const SideFacet f = verdict(b, l);
      const std::string what =
          facetWord_ + std::to_string(b.tags[l]) + " of " + facetGroupWord_ + " '" + firstName + "'";
      if (!f.inBody) {
        if (selectedTag_ >= 0) continue;  // a facet of another body
        failSideSet(b, l, what + " has a node that belongs to no " + dimWord_ + " element");
      }
      if (f.matches == 0)
        failSideSet(b, l,
                    what + (solid_ ? " is not on the boundary of any element (its corners are not the corners of "
                                     "an element face)"
                                   : " is not on the boundary of any element (its end nodes are not the corners of "
                                     "an element side)"));
      if (f.matches != 1)
        failSideSet(b, l,
                    what + (solid_ ? " lies inside the body (on a face shared by two elements)"
                                   : " lies inside the body (on a side shared by two elements)") +
                        "; side sets must lie on the boundary");
      // Higher-order nodes: the same as the element facet's (as a set: the
      // facet's orientation comes from the element, not from the file).
      if (!f.sameHigherOrder)
        failSideSet(b, l,
                    solid_ ? "the mid-edge / centre nodes of " + what + " are not those of the element face it lies on"
                           : "the middle node of " + what + " is not the mid-side node of the element side it lies on");
      add(f, phys, b, l);
    }
  }
}

void GmshBody::readPointNodeSets(const UsedTag& used, const AddNodes& add) const {
  std::map<int, std::vector<long long>> pointNodes = d_.pointNodes;
  for (const auto& b : d_.blocks)
    if (b.dim == 0 && b.type == 15)
      pointNodes[b.entity].insert(pointNodes[b.entity].end(), b.nodes.begin(), b.nodes.end());
  for (const auto& kv : pointNodes) {
    std::vector<std::string> names;
    for (int pt : physicalsOf(d_, 0, kv.first)) names.push_back(physicalName(d_, 0, pt));
    if (names.empty()) continue;
    std::vector<long long> tags;
    for (long long tag : kv.second) {
      if (used(tag)) {
        tags.push_back(tag);
        continue;
      }
      if (selectedTag_ >= 0) continue;  // a point of another body
      fail("physical point '" + names[0] + "' (node " + std::to_string(tag) + ") belongs to no " + dimWord_ +
           " element");
    }
    for (const auto& name : names) add(name, tags);
  }
}

void GmshBody::readCurveNodeSets(const UsedTag& used, const AddNodes& add) const {
  for (const auto& b : d_.blocks) {
    if (b.dim != 1) continue;
    const auto& phys = physicalsOf(d_, 1, b.entity);
    if (phys.empty()) continue;
    const std::string firstName = physicalName(d_, 1, phys[0]);
    if (b.type != 1 && b.type != 8)
      failAt(b.line, "physical curve '" + firstName + "' (curve " + std::to_string(b.entity) + ") has " +
                         gmshTypeText(b.type) + "; expected 2-node lines (type 1) or 3-node lines (type 8)");
    for (size_t l = 0; l < b.tags.size(); ++l) {
      const std::vector<long long> tags(b.nodes.begin() + l * b.numNodes, b.nodes.begin() + (l + 1) * b.numNodes);
      if (!std::all_of(tags.begin(), tags.end(), used)) {
        if (selectedTag_ >= 0) continue;  // a line of another body
        failAt(b.lines[l], "line element " + std::to_string(b.tags[l]) + " of physical curve '" + firstName +
                               "' has a node that belongs to no 3-D element");
      }
      for (int pt : phys) add(physicalName(d_, 1, pt), tags);
    }
  }
}

}  // namespace ddc::gmsh
