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
  double toDouble(const std::string& s, const char* what) const {
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
      fail(std::string("expected a number ") + what + ", found '" + s + "'");
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

/// Number of nodes of the Gmsh element types we accept in a physical group.
int gmshNumNodes(int type) {
  switch (type) {
    case 1: return 2;    // 2-node line
    case 3: return 4;    // 4-node quadrangle
    case 8: return 3;    // 3-node line
    case 10: return 9;   // 9-node quadrangle
    case 15: return 1;   // point
    default: return -1;  // not needed (rejected or skipped)
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
  std::vector<long long> tags;   // element tags
  std::vector<long long> nodes;  // node tags, numNodes per element
  int numNodes = 0;
};

struct MshData {
  std::map<EntityKey, std::string> physicalNames;   // (dim, physical tag) -> name
  std::map<EntityKey, std::vector<int>> entityPhysicals;  // (dim, entity tag) -> physical tags
  bool hasEntities = false;
  bool hasNodes = false, hasElements = false;
  std::unordered_map<long long, std::array<double, 3>> nodes;  // tag -> x, y, z
  std::map<int, std::vector<long long>> pointNodes;           // point entity -> node tags
  std::vector<ElementBlock> blocks;                            // 0-D, 1-D, 2-D blocks
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
      const std::array<double, 3> p{in.toDouble(x[0], "(x)"), in.toDouble(x[1], "(y)"), in.toDouble(x[2], "(z)")};
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
  for (int b = 0; b < nb; ++b) {
    const auto t = in.tokens("Elements", 4, "'entityDim entityTag elementType numElementsInBlock'");
    ElementBlock blk;
    blk.dim = static_cast<int>(in.toInt(t[0], "(entity dimension)"));
    blk.entity = static_cast<int>(in.toInt(t[1], "(entity tag)"));
    blk.type = static_cast<int>(in.toInt(t[2], "(element type)"));
    const int n = in.toCount(t[3], "number of elements in block");
    if (blk.dim == 3)
      in.fail("3-D elements (type " + std::to_string(blk.type) + ", volume " + std::to_string(blk.entity) +
              ") are not supported; DDContact reads 2-D meshes in the xy-plane");
    blk.numNodes = gmshNumNodes(blk.type);
    // Element types we cannot use are kept without their connectivity: the
    // caller decides (from the body's selection) whether they are an error.
    for (int k = 0; k < n; ++k) {
      const auto e = in.tokens("Elements", 1, "an element 'tag nodeTags...'");
      if (blk.numNodes < 0) continue;
      if (e.size() != static_cast<size_t>(blk.numNodes) + 1)
        in.fail("element " + e[0] + " of type " + std::to_string(blk.type) + " must list " +
                std::to_string(blk.numNodes) + " node tags, found " + std::to_string(e.size() - 1));
      blk.tags.push_back(in.toInt(e[0], "(element tag)"));
      for (int i = 1; i <= blk.numNodes; ++i) blk.nodes.push_back(in.toInt(e[i], "(node tag)"));
    }
    if (blk.numNodes < 0) blk.tags.assign(n, 0);  // remember the count only
    d.blocks.push_back(std::move(blk));
  }
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

std::string listNames(const std::set<std::string>& names) {
  std::ostringstream os;
  bool firstName = true;
  for (const auto& n : names) {
    os << (firstName ? "'" : ", '") << n << "'";
    firstName = false;
  }
  if (firstName) os << "(none)";
  return os.str();
}

/// Twice the signed area of the corner polygon of a 2-D element.
double twiceArea(const std::vector<std::array<double, 2>>& xy, CellType type, const int* n) {
  double a = 0.0;
  for (const auto& side : referenceCell(type).facets) {
    const auto& p = xy[n[side.nodes[0]]];
    const auto& q = xy[n[side.nodes[1]]];
    a += p[0] * q[1] - q[0] * p[1];
  }
  return a;
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
            "name of the physical surface whose 2-D elements form this body; empty: every 2-D "
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
  std::string resolved = file;
  if (file[0] != '/' && !baseDirectory.empty())
    resolved = baseDirectory + (baseDirectory.back() == '/' ? "" : "/") + file;
  try {
    return readGmshFile(mesh, bodyName, type, resolved, params.get<std::string>("Physical Surface"));
  } catch (const InputError& e) {
    // Lead with the parameter path so the user finds the deck entry.
    DDC_THROW(InputError, "'" << joinPath(path, "File") << "' (body '" << bodyName << "'): " << e.what());
  }
}

int readGmshFile(Mesh& mesh, const std::string& bodyName, CellType type, const std::string& fileName,
                 const std::string& physicalSurface) {
  const MshData d = parseMsh(fileName);
  auto fail = [&](const std::string& msg) -> void { DDC_THROW(InputError, "Gmsh file '" << fileName << "': " << msg); };
  const bool quad9 = type == CellType::Quad9;
  const int wantQuad = quad9 ? 10 : 3;
  const int wantLine = quad9 ? 8 : 1;
  const int nen = numCellNodes(type);

  // ---- 1. the physical surface selecting the body's elements
  int selectedTag = -1;
  if (!physicalSurface.empty()) {
    std::set<std::string> surfaces;
    for (const auto& kv : d.physicalNames)
      if (kv.first.first == 2) {
        surfaces.insert(kv.second);
        if (kv.second == physicalSurface) selectedTag = kv.first.second;
      }
    if (selectedTag < 0)
      fail("no physical surface named '" + physicalSurface + "'; physical surfaces are " + listNames(surfaces));
    if (!d.hasEntities) fail("a $Entities section is needed to select physical surface '" + physicalSurface + "'");
  }
  auto selected = [&](const ElementBlock& b) {
    if (b.dim != 2) return false;
    if (selectedTag < 0) return true;
    const auto& ph = physicalsOf(d, 2, b.entity);
    return std::find(ph.begin(), ph.end(), selectedTag) != ph.end();
  };

  // ---- 2. the 2-D elements, type-checked
  std::vector<const ElementBlock*> surfaceBlocks;
  for (const auto& b : d.blocks) {
    if (!selected(b)) continue;
    if (b.type != wantQuad) {
      std::ostringstream os;
      os << "surface " << b.entity << " has elements of type " << b.type;
      if (isTriangle(b.type))
        os << ": triangles are not supported; mesh with quadrangles (Mesh.RecombineAll=1)";
      else if (b.type == 16)
        os << " (8-node quadrangles): not supported; use complete 9-node quadrangles "
              "(Mesh.SecondOrderIncomplete=0) with element type Quad9";
      else if (b.type == 3 || b.type == 10)
        os << " (" << (b.type == 3 ? "4" : "9") << "-node quadrangles) but body '" << bodyName
           << "' has element type " << cellTypeName(type) << "; expected "
           << (quad9 ? "9-node quadrangles (type 10; Mesh.ElementOrder=2, Mesh.SecondOrderIncomplete=0)"
                     : "4-node quadrangles (type 3; Mesh.ElementOrder=1)");
      else
        os << ": not supported; expected " << (quad9 ? "9" : "4") << "-node quadrangles (type " << wantQuad << ")";
      fail(os.str());
    }
    surfaceBlocks.push_back(&b);
  }
  size_t numElems = 0;
  for (const auto* b : surfaceBlocks) numElems += b->tags.size();
  if (numElems == 0) {
    if (!physicalSurface.empty()) fail("physical surface '" + physicalSurface + "' has no 2-D elements");
    fail("no 2-D elements found (expected quadrangles). Note: once physical groups exist, Gmsh saves only "
         "their elements: define a Physical Surface for the body or set Mesh.SaveAll=1");
  }

  // ---- 3. compact node numbering: used nodes in increasing tag order
  std::vector<long long> used;
  for (const auto* b : surfaceBlocks) used.insert(used.end(), b->nodes.begin(), b->nodes.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::unordered_map<long long, int> local;
  local.reserve(used.size());
  std::vector<std::array<double, 2>> xy(used.size());
  for (size_t k = 0; k < used.size(); ++k) {
    auto it = d.nodes.find(used[k]);
    if (it == d.nodes.end()) fail("an element references node tag " + std::to_string(used[k]) + ", which is not in $Nodes");
    const auto& p = it->second;
    const double scale = std::max({1.0, std::abs(p[0]), std::abs(p[1])});
    if (std::abs(p[2]) > 1e-10 * scale) {
      std::ostringstream os;
      os << "node " << used[k] << " has z = " << p[2]
         << "; only planar meshes in the plane z = 0 are supported";
      fail(os.str());
    }
    local[used[k]] = static_cast<int>(k);
    xy[k] = {p[0], p[1]};
  }

  // ---- 4. connectivity (local node indices), counter-clockwise
  std::vector<int> conn;
  std::vector<int> elemEntity;
  conn.reserve(numElems * nen);
  for (const auto* b : surfaceBlocks) {
    for (size_t e = 0; e < b->tags.size(); ++e) {
      int n[9];
      for (int i = 0; i < nen; ++i) n[i] = local.at(b->nodes[e * nen + i]);
      const double a2 = twiceArea(xy, type, n);
      double h2 = 0.0;  // squared longest corner-to-corner distance, for scale
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
          h2 = std::max(h2, std::pow(xy[n[i]][0] - xy[n[j]][0], 2) + std::pow(xy[n[i]][1] - xy[n[j]][1], 2));
      if (!(std::abs(a2) > 1e-12 * h2))
        fail("element " + std::to_string(b->tags[e]) + " has zero area (degenerate quadrangle)");
      if (a2 < 0) {
        // Clockwise (surface normal -z): reverse to 0 3 2 1; the mid-side
        // nodes follow their sides: (0-3)=7, (3-2)=6, (2-1)=5, (1-0)=4.
        static const int perm4[4] = {0, 3, 2, 1};
        static const int perm9[9] = {0, 3, 2, 1, 7, 6, 5, 4, 8};
        int m[9];
        for (int i = 0; i < nen; ++i) m[i] = n[quad9 ? perm9[i] : perm4[i]];
        std::copy(m, m + nen, n);
      }
      conn.insert(conn.end(), n, n + nen);
      elemEntity.push_back(b->entity);
    }
  }
  const int ne = static_cast<int>(elemEntity.size());

  // ---- 5. element sides: corner pair -> (element, local side)
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> sides;
  for (int e = 0; e < ne; ++e) {
    const int* n = &conn[static_cast<size_t>(e) * nen];
    const auto& facets = referenceCell(type).facets;
    for (int s = 0; s < static_cast<int>(facets.size()); ++s) {
      const int p = n[facets[s].nodes[0]], q = n[facets[s].nodes[1]];
      sides[{std::min(p, q), std::max(p, q)}].push_back({e, s});
    }
  }

  // ---- 6. physical curves -> side sets (element, local side)
  std::map<std::string, std::vector<std::pair<int, int>>> curveSets;
  std::map<std::string, std::set<std::pair<int, int>>> seen;
  for (const auto& b : d.blocks) {
    if (b.dim != 1) continue;
    const auto& phys = physicalsOf(d, 1, b.entity);
    if (phys.empty()) continue;
    const std::string firstName = physicalName(d, 1, phys[0]);
    if (b.type != wantLine) {
      std::ostringstream os;
      os << "physical curve '" << firstName << "' (curve " << b.entity << ") has elements of type " << b.type
         << "; body '" << bodyName << "' (" << cellTypeName(type) << ") expects "
         << (quad9 ? "3-node lines (type 8)" : "2-node lines (type 1)");
      fail(os.str());
    }
    const int nl = b.numNodes;
    for (size_t l = 0; l < b.tags.size(); ++l) {
      int n[3];
      bool inBody = true;
      for (int i = 0; i < nl; ++i) {
        auto it = local.find(b.nodes[l * nl + i]);
        inBody = inBody && it != local.end();
        n[i] = inBody ? it->second : -1;
      }
      if (!inBody) {
        if (selectedTag >= 0) continue;  // a line of another body
        fail("line element " + std::to_string(b.tags[l]) + " of physical curve '" + firstName +
             "' has a node that belongs to no 2-D element");
      }
      auto it = sides.find({std::min(n[0], n[1]), std::max(n[0], n[1])});
      if (it == sides.end())
        fail("line element " + std::to_string(b.tags[l]) + " of physical curve '" + firstName +
             "' is not on the boundary of any element (its end nodes are not the corners of an element side)");
      if (it->second.size() != 1)
        fail("line element " + std::to_string(b.tags[l]) + " of physical curve '" + firstName +
             "' lies inside the body (on a side shared by two elements); side sets must lie on the boundary");
      const auto es = it->second[0];
      if (quad9 && conn[static_cast<size_t>(es.first) * nen + referenceCell(type).facets[es.second].nodes[2]] != n[2])
        fail("the middle node of line element " + std::to_string(b.tags[l]) + " of physical curve '" + firstName +
             "' is not the mid-side node of the element side it lies on");
      for (int pt : phys) {
        const std::string name = physicalName(d, 1, pt);
        if (seen[name].insert(es).second) curveSets[name].push_back(es);
      }
    }
  }

  // ---- 7. physical points and surfaces -> node sets
  std::map<std::string, std::vector<int>> nodeSets;
  std::map<int, std::vector<long long>> pointNodes = d.pointNodes;
  for (const auto& b : d.blocks)
    if (b.dim == 0 && b.type == 15) pointNodes[b.entity].insert(pointNodes[b.entity].end(), b.nodes.begin(), b.nodes.end());
  for (const auto& kv : pointNodes) {
    const auto& phys = physicalsOf(d, 0, kv.first);
    for (long long tag : kv.second) {
      auto it = local.find(tag);
      for (int pt : phys) {
        const std::string name = physicalName(d, 0, pt);
        if (it == local.end()) {
          if (selectedTag >= 0) continue;
          fail("physical point '" + name + "' (node " + std::to_string(tag) + ") belongs to no 2-D element");
        }
        nodeSets[name].push_back(it->second);
      }
    }
  }
  for (int e = 0; e < ne; ++e)
    for (int pt : physicalsOf(d, 2, elemEntity[e])) {
      auto& s = nodeSets[physicalName(d, 2, pt)];
      s.insert(s.end(), &conn[static_cast<size_t>(e) * nen], &conn[static_cast<size_t>(e) * nen] + nen);
    }

  // ---- 8. commit (nothing above touched the mesh, so errors leave it intact)
  const int body = mesh.beginBody(bodyName, type);
  const int firstNode = mesh.numNodes();
  const int firstElement = mesh.numElements();
  for (const auto& p : xy) mesh.addNode(p[0], p[1]);
  for (int e = 0; e < ne; ++e) {
    int n[9];
    for (int i = 0; i < nen; ++i) n[i] = firstNode + conn[static_cast<size_t>(e) * nen + i];
    mesh.addElement(n);
  }
  for (const auto& kv : curveSets) {
    std::vector<Segment> segs;
    for (const auto& es : kv.second) segs.push_back(mesh.makeSegment(firstElement + es.first, es.second));
    mesh.addSideSet(body, kv.first, std::move(segs));
  }
  for (auto& kv : nodeSets) {
    for (int& n : kv.second) n += firstNode;
    mesh.addNodeSet(body, kv.first, std::move(kv.second));
  }
  return body;
}

}  // namespace ddc
