// The whole reader of a Gmsh body (readGmshFile()): the file parsed on one
// rank, the body built whole. The checks it shares with the reader in ranges
// are GmshBody's (DDC_GmshFile.hpp).
#include "DDC_Gmsh.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <unordered_map>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_GmshFile.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

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

GmshBodyFile gmshBodyFile(Teuchos::ParameterList& params, const std::string& bodyName, CellType type,
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
  return {resolveDeckFile(file, baseDirectory), params.get<std::string>(used)};
}

void throwForBody(const InputError& e, const std::string& bodyName, const std::string& path) {
  // Lead with the parameter path so the user finds the deck entry.
  DDC_THROW(InputError, "'" << joinPath(path, "File") << "' (body '" << bodyName << "'): " << e.what());
}

int readGmshBody(Mesh& mesh, const std::string& bodyName, CellType type, Teuchos::ParameterList& params,
                 const std::string& path, const std::string& baseDirectory) {
  const GmshBodyFile in = gmshBodyFile(params, bodyName, type, path, baseDirectory);
  try {
    return readGmshFile(mesh, bodyName, type, in.file, in.group);
  } catch (const InputError& e) {
    throwForBody(e, bodyName, path);
  }
}

namespace {

/// One body read whole from the parsed file by readGmshFile(), in the
/// steps of read(). Nothing touches the mesh before commit(), so an error
/// leaves it intact.
class GmshBodyReader : public gmsh::GmshBody {
 public:
  using GmshBody::GmshBody;

  /// Reads the body into `mesh`; returns its index.
  int read(Mesh& mesh) {
    selectBodyGroup();
    collectBodyBlocks();
    numberNodes();
    buildConnectivity();
    indexFacets();
    readSideSets([this](const gmsh::ElementBlock& b, size_t l) { return sideFacet(b, l); },
                 [this](const SideFacet& f, const std::vector<int>& phys, const gmsh::ElementBlock&, size_t) {
                   for (int pt : phys) {
                     const std::string name = gmsh::physicalName(d_, dim_ - 1, pt);
                     if (seen_[name].insert({f.element, f.facet}).second)
                       facetSets_[name].push_back({f.element, f.facet});
                   }
                 });
    readNodeSets();
    return commit(mesh);
  }

 private:
  using ElementFacet = std::pair<int, int>;  // (element, local facet)

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
      requireNode(used[k], it == d_.nodes.end() ? nullptr : &it->second);
      const auto& p = it->second;
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
          checkVolumeElement(*b, e, n, xyz_);
        else
          orientQuadrangle(*b, e, n, xyz_);
        conn_.insert(conn_.end(), n, n + nen_);
        elemEntity_.push_back(b->entity);
      }
    }
    ne_ = static_cast<int>(elemEntity_.size());
  }

  /// 5. Element facets: sorted corners -> (element, local facet).
  void indexFacets() {
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

  /// 6. Side set element `l` of block `b`: the element facet with its
  /// corners, and whether its other nodes are that facet's.
  SideFacet sideFacet(const gmsh::ElementBlock& b, size_t l) const {
    SideFacet f;
    const int nf = b.numNodes;
    std::vector<int> n(nf);
    f.inBody = true;
    for (int i = 0; i < nf && f.inBody; ++i) {
      auto it = local_.find(b.nodes[l * nf + i]);
      f.inBody = it != local_.end();
      n[i] = f.inBody ? it->second : -1;
    }
    if (!f.inBody) return f;
    std::vector<int> key(n.begin(), n.begin() + facetCorners_);
    std::sort(key.begin(), key.end());
    auto it = facets_.find(key);
    f.matches = it == facets_.end() ? 0 : int(it->second.size());
    if (f.matches != 1) return f;
    std::tie(f.element, f.facet) = it->second[0];
    const auto& fn = ref_.facets[f.facet].nodes;
    std::vector<int> mine(n.begin() + facetCorners_, n.end()), theirs;
    for (size_t i = facetCorners_; i < fn.size(); ++i)
      theirs.push_back(conn_[static_cast<size_t>(f.element) * nen_ + fn[i]]);
    std::sort(mine.begin(), mine.end());
    std::sort(theirs.begin(), theirs.end());
    f.sameHigherOrder = mine == theirs;
    return f;
  }

  /// 7. Physical points, curves (3-D) and surfaces / volumes -> node sets.
  void readNodeSets() {
    const auto used = [this](long long tag) { return local_.count(tag) != 0; };
    const auto add = [this](const std::string& name, const std::vector<long long>& tags) {
      auto& s = nodeSets_[name];
      for (long long t : tags) s.push_back(local_.at(t));
    };
    readPointNodeSets(used, add);
    if (solid_) readCurveNodeSets(used, add);
    for (int e = 0; e < ne_; ++e)
      for (int pt : gmsh::physicalsOf(d_, dim_, elemEntity_[e])) {
        auto& s = nodeSets_[gmsh::physicalName(d_, dim_, pt)];
        s.insert(s.end(), &conn_[static_cast<size_t>(e) * nen_], &conn_[static_cast<size_t>(e) * nen_] + nen_);
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

  std::unordered_map<long long, int> local_;  ///< node tag -> local node index
  std::vector<std::array<double, 3>> xyz_;
  std::vector<int> conn_;
  std::vector<int> elemEntity_;
  int ne_ = 0;
  std::map<std::vector<int>, std::vector<ElementFacet>> facets_;
  std::map<std::string, std::set<ElementFacet>> seen_;  ///< what each side set has, so that it lists a facet once
  std::map<std::string, std::vector<ElementFacet>> facetSets_;
  std::map<std::string, std::vector<int>> nodeSets_;
};

}  // namespace

int readGmshFile(Mesh& mesh, const std::string& bodyName, CellType type, const std::string& fileName,
                 const std::string& physicalGroup) {
  const gmsh::MshData d = gmsh::parseMsh(fileName);
  return GmshBodyReader(d, fileName, bodyName, type, physicalGroup).read(mesh);
}

}  // namespace ddc
