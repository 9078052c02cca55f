#include "DDC_ExodusCells.hpp"

#include <exodusII.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

namespace ddc {

namespace {

/// An Exodus II node as the average of corners of the cell (0-based corner
/// indices; corners are numbered alike in the mesh's order and Exodus').
using CornerGroup = std::vector<int>;

/// The Exodus II nodes of each element type, in Exodus order (SAND92-2137;
/// SEACAS "Element types"): corners, then edge middles, then for HEX27 the
/// centroid and the face middles of faces 5, 6, 4, 2, 1, 3.
const std::vector<CornerGroup>& exodusNodes(CellType t) {
  static const std::map<CellType, std::vector<CornerGroup>> table = [] {
    std::map<CellType, std::vector<CornerGroup>> m;
    const std::vector<CornerGroup> quad4 = {{0}, {1}, {2}, {3}};
    m[CellType::Quad4] = quad4;
    auto quad9 = quad4;
    quad9.insert(quad9.end(), {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 1, 2, 3}});
    m[CellType::Quad9] = quad9;
    const std::vector<CornerGroup> hex8 = {{0}, {1}, {2}, {3}, {4}, {5}, {6}, {7}};
    m[CellType::Hex8] = hex8;
    auto hex20 = hex8;
    hex20.insert(hex20.end(), {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 5}, {2, 6}, {3, 7}, {4, 5}, {5, 6},
                               {6, 7}, {7, 4}});
    m[CellType::Hex20] = hex20;
    auto hex27 = hex20;
    hex27.insert(hex27.end(), {{0, 1, 2, 3, 4, 5, 6, 7},
                               {0, 1, 2, 3},    // face 5 (z = -1)
                               {4, 5, 6, 7},    // face 6 (z = +1)
                               {0, 3, 7, 4},    // face 4 (x = -1)
                               {1, 2, 6, 5},    // face 2 (x = +1)
                               {0, 1, 5, 4},    // face 1 (y = -1)
                               {2, 3, 7, 6}});  // face 3 (y = +1)
    m[CellType::Hex27] = hex27;
    const std::vector<CornerGroup> tet4 = {{0}, {1}, {2}, {3}};
    m[CellType::Tet4] = tet4;
    auto tet10 = tet4;
    tet10.insert(tet10.end(), {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}});
    m[CellType::Tet10] = tet10;
    return m;
  }();
  const auto it = table.find(t);
  if (it == table.end())
    throw std::invalid_argument(std::string("Exodus II output: no element type for cell ") + cellTypeName(t));
  return it->second;
}

/// The corners of each Exodus II side, side 1 first.
const std::vector<std::set<int>>& exodusSides(CellType t) {
  static const std::vector<std::set<int>> quad = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  static const std::vector<std::set<int>> hex = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6},
                                                 {0, 4, 7, 3}, {0, 3, 2, 1}, {4, 5, 6, 7}};
  static const std::vector<std::set<int>> tet = {{0, 1, 3}, {1, 2, 3}, {0, 2, 3}, {0, 1, 2}};
  switch (t) {
    case CellType::Quad4:
    case CellType::Quad9:
      return quad;
    case CellType::Hex8:
    case CellType::Hex20:
    case CellType::Hex27:
      return hex;
    case CellType::Tet4:
    case CellType::Tet10:
      return tet;
    default:
      throw std::invalid_argument(std::string("Exodus II output: no sides for cell ") + cellTypeName(t));
  }
}

}  // namespace

const std::vector<int>& exodusNodeOrder(CellType t) {
  static const std::map<CellType, std::vector<int>> table = [] {
    std::map<CellType, std::vector<int>> m;
    for (CellType type : {CellType::Quad4, CellType::Quad9, CellType::Hex8, CellType::Hex20, CellType::Hex27,
                          CellType::Tet4, CellType::Tet10}) {
      const ReferenceCell& cell = referenceCell(type);
      std::vector<int> order;
      for (const CornerGroup& g : exodusNodes(type)) {
        std::array<double, 3> x{{0, 0, 0}};
        for (int c : g)
          for (int k = 0; k < 3; ++k) x[k] += cell.nodes[c][k] / double(g.size());
        int found = -1;
        for (int i = 0; i < cell.numNodes; ++i) {
          double d = 0;
          for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(cell.nodes[i][k] - x[k]));
          if (d < 1e-12) found = i;
        }
        if (found < 0 || int(exodusNodes(type).size()) != cell.numNodes)
          throw std::logic_error(std::string("Exodus II node table does not match the reference cell ") + cell.name);
        order.push_back(found);
      }
      m[type] = order;
    }
    return m;
  }();
  const auto it = table.find(t);
  if (it == table.end())
    throw std::invalid_argument(std::string("Exodus II output: no element type for cell ") + cellTypeName(t));
  return it->second;
}

int exodusSideNumber(CellType t, int f) {
  const ReferenceCell& cell = referenceCell(t);
  if (f < 0 || f >= int(cell.facets.size()))
    throw std::invalid_argument("exodusSideNumber: no facet " + std::to_string(f) + " on " + cell.name);
  const ReferenceFacet& facet = cell.facets[f];
  const int corners = referenceCell(facet.type).numCorners;
  const std::set<int> ours(facet.nodes.begin(), facet.nodes.begin() + corners);
  const auto& sides = exodusSides(t);
  for (size_t s = 0; s < sides.size(); ++s)
    if (sides[s] == ours) return int(s) + 1;
  throw std::logic_error(std::string("Exodus II side table does not match facet ") + std::to_string(f) + " of " +
                         cell.name);
}

const char* exodusElementType(CellType t) {
  switch (t) {
    case CellType::Quad4: return "QUAD4";
    case CellType::Quad9: return "QUAD9";
    case CellType::Hex8: return "HEX8";
    case CellType::Hex20: return "HEX20";
    case CellType::Hex27: return "HEX27";
    case CellType::Tet4: return "TETRA";  // "TETRA4" is not read by every reader (meshio 5)
    case CellType::Tet10: return "TETRA10";
    default:
      throw std::invalid_argument(std::string("Exodus II output: no element type for cell ") + cellTypeName(t));
  }
}


int exodusFacetOfSide(CellType t, int side) {
  const ReferenceCell& cell = referenceCell(t);
  for (int f = 0; f < int(cell.facets.size()); ++f)
    if (exodusSideNumber(t, f) == side) return f;
  return -1;
}

std::string exodusLibraryError(int status) {
  const char *msg = nullptr, *func = nullptr;
  int code = 0;
  ex_get_err(&msg, &func, &code);
  std::string why = msg && *msg ? msg : "error " + std::to_string(status);
  if (func && *func) why += std::string(" (in ") + func + ")";
  return why;
}

std::vector<std::string> exodusElementTypeNames(CellType t) {
  switch (t) {
    case CellType::Quad4: return {"QUAD", "QUAD4"};
    case CellType::Quad9: return {"QUAD9"};
    case CellType::Hex8: return {"HEX", "HEX8", "HEXAHEDRON"};
    case CellType::Hex20: return {"HEX20"};
    case CellType::Hex27: return {"HEX27"};
    case CellType::Tet4: return {"TETRA", "TETRA4", "TET4", "TET"};
    case CellType::Tet10: return {"TETRA10", "TET10"};
    default: return {};
  }
}

}  // namespace ddc
