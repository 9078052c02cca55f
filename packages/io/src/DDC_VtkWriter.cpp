#include "DDC_VtkWriter.hpp"

#include <algorithm>
#include <cstdio>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include <Teuchos_CommHelpers.hpp>

#include "DDC_Error.hpp"
#include "DDC_OutputDirectory.hpp"
#include "DDC_ReferenceCell.hpp"
#include "DDC_ResultFile.hpp"

namespace fs = std::filesystem;

namespace ddc {

namespace {

/// Number of nodes of the supported VTK cell types, -1 if unsupported: a
/// vertex and the VTK types of DDContact's reference cells.
int nodesPerCell(unsigned char type) {
  if (type == 1) return 1;  // VTK_VERTEX
  for (int t = 0; t <= static_cast<int>(CellType::Quad8); ++t) {
    const ReferenceCell& c = referenceCell(static_cast<CellType>(t));
    if (c.vtkType == type) return c.numNodes;
  }
  return -1;
}

/// The supported VTK cell types, for messages.
std::string supportedCellTypes() {
  std::vector<int> types{1};
  for (int t = 0; t <= static_cast<int>(CellType::Quad8); ++t)
    types.push_back(referenceCell(static_cast<CellType>(t)).vtkType);
  std::sort(types.begin(), types.end());
  std::ostringstream os;
  for (std::size_t i = 0; i < types.size(); ++i) os << (i ? ", " : "") << types[i];
  return os.str();
}

/// Components as written: 2-D vectors are padded to 3.
int writtenComponents(int components) { return components == 2 ? 3 : components; }

std::string xmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string pieceLabel(int step, const VtkPiece& p, int rank) {
  std::ostringstream os;
  os << "VtkWriter: step " << step << ", piece " << p.id << " (rank " << rank << "): ";
  return os.str();
}

std::string validateFields(const std::vector<VtkField>& fields, const char* kind, long count,
                           const char* countName) {
  std::set<std::string> names;
  for (const VtkField& f : fields) {
    std::ostringstream os;
    if (f.name.empty() || f.name.find_first_of("\t\r\n") != std::string::npos) {
      os << kind << " field '" << f.name << "': invalid name (expected non-empty, no tab or line break)";
    } else if (!names.insert(f.name).second) {
      os << kind << " field '" << f.name << "' given twice";
    } else if (f.components < 1) {
      os << kind << " field '" << f.name << "': " << f.components << " components, expected >= 1";
    } else if (static_cast<long>(f.values.size()) != static_cast<long>(f.components) * count) {
      os << kind << " field '" << f.name << "' has " << f.values.size() << " values, expected "
         << f.components << " components x " << count << " " << countName << " = "
         << static_cast<long>(f.components) * count;
    }
    if (!os.str().empty()) return os.str();
  }
  return std::string();
}

/// "" if the piece is consistent, otherwise what is wrong (without label).
std::string validatePiece(const VtkPiece& p) {
  std::ostringstream os;
  if (p.id < 0) {
    os << "piece id must be >= 0";
    return os.str();
  }
  if (p.points.size() % 3 != 0) {
    os << p.points.size() << " point coordinates, expected 3 per point (x, y, z)";
    return os.str();
  }
  const long numPoints = static_cast<long>(p.points.size() / 3);
  const long numCells = static_cast<long>(p.types.size());
  if (p.offsets.size() != p.types.size()) {
    os << p.offsets.size() << " offsets but " << p.types.size()
       << " cell types, expected one of each per cell";
    return os.str();
  }
  long begin = 0;
  for (long c = 0; c < numCells; ++c) {
    const int n = nodesPerCell(p.types[c]);
    if (n < 0) {
      os << "cell " << c << ": unsupported VTK cell type " << static_cast<int>(p.types[c])
         << " (supported: " << supportedCellTypes() << ")";
      return os.str();
    }
    const long end = p.offsets[c];
    if (end - begin != n) {
      os << "cell " << c << " (VTK type " << static_cast<int>(p.types[c]) << ") has "
         << (end - begin) << " nodes by its offsets [" << begin << ", " << end << "), expected "
         << n;
      return os.str();
    }
    begin = end;
  }
  if (begin != static_cast<long>(p.connectivity.size())) {
    os << "the last offset is " << begin << " but connectivity has " << p.connectivity.size()
       << " entries";
    return os.str();
  }
  for (std::size_t i = 0; i < p.connectivity.size(); ++i) {
    if (p.connectivity[i] < 0 || p.connectivity[i] >= numPoints) {
      os << "connectivity[" << i << "] = " << p.connectivity[i] << " is not a point index in [0, "
         << numPoints << ")";
      return os.str();
    }
  }
  std::string e = validateFields(p.pointData, "point", numPoints, "points");
  if (e.empty()) e = validateFields(p.cellData, "cell", numCells, "cells");
  return e;
}

/// Field declarations of a piece, one line per field: "P|C \t name \t components".
std::string fieldSignature(const VtkPiece& p) {
  std::ostringstream os;
  for (const VtkField& f : p.pointData) os << "P\t" << f.name << '\t' << f.components << '\n';
  for (const VtkField& f : p.cellData) os << "C\t" << f.name << '\t' << f.components << '\n';
  return os.str();
}

struct FieldDecl {
  bool point;
  std::string name;
  int components;
};

std::vector<FieldDecl> parseSignature(const std::string& sig) {
  std::vector<FieldDecl> out;
  std::istringstream is(sig);
  std::string line;
  while (std::getline(is, line)) {
    const std::size_t a = line.find('\t');
    const std::size_t b = line.rfind('\t');
    if (a == std::string::npos || b == a) continue;
    out.push_back({line[0] == 'P', line.substr(a + 1, b - a - 1), std::stoi(line.substr(b + 1))});
  }
  return out;
}

std::string broadcastString(const Teuchos::Comm<int>& comm, int root, const std::string& s) {
  int length = comm.getRank() == root ? static_cast<int>(s.size()) : 0;
  Teuchos::broadcast<int, int>(comm, root, Teuchos::outArg(length));
  std::string out = comm.getRank() == root ? s : std::string(length, ' ');
  if (length > 0) Teuchos::broadcast<int, char>(comm, root, length, &out[0]);
  return out;
}

void writeValues(CheckedFile& f, const std::vector<double>& v, int components, int written) {
  const std::size_t n = components > 0 ? v.size() / components : 0;
  for (std::size_t i = 0; i < n; ++i) {
    f.write("         ");
    for (int c = 0; c < written; ++c) {
      const double x = c < components ? v[i * components + c] : 0.0;
      f.printf(c ? " %.17g" : "%.17g", x);
    }
    f.write("\n");
  }
}

void writeFieldArrays(CheckedFile& f, const std::vector<VtkField>& fields) {
  for (const VtkField& fd : fields) {
    const int w = writtenComponents(fd.components);
    f.printf("        <DataArray type=\"Float64\" Name=\"%s\" NumberOfComponents=\"%d\" "
                 "format=\"ascii\">\n",
                 xmlEscape(fd.name).c_str(), w);
    writeValues(f, fd.values, fd.components, w);
    f.write("        </DataArray>\n");
  }
}

void writeVtu(const std::string& path, const VtkPiece& p) {
  CheckedFile f(path);
  f.write("<?xml version=\"1.0\"?>\n");
  f.write("<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
  f.write("  <UnstructuredGrid>\n");
  f.printf("    <Piece NumberOfPoints=\"%d\" NumberOfCells=\"%d\">\n", p.numPoints(),
               p.numCells());
  f.write("      <PointData>\n");
  writeFieldArrays(f, p.pointData);
  f.write("      </PointData>\n");
  f.write("      <CellData>\n");
  writeFieldArrays(f, p.cellData);
  f.write("      </CellData>\n");
  f.write("      <Points>\n");
  f.write("        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  writeValues(f, p.points, 3, 3);
  f.write("        </DataArray>\n");
  f.write("      </Points>\n");
  f.write("      <Cells>\n");
  f.write("        <DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n");
  int begin = 0;
  for (int c = 0; c < p.numCells(); ++c) {
    f.write("         ");
    for (int k = begin; k < p.offsets[c]; ++k)
      f.printf(k > begin ? " %d" : "%d", p.connectivity[k]);
    f.write("\n");
    begin = p.offsets[c];
  }
  f.write("        </DataArray>\n");
  f.write("        <DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n");
  for (int c = 0; c < p.numCells(); ++c) f.printf("         %d\n", p.offsets[c]);
  f.write("        </DataArray>\n");
  f.write("        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (int c = 0; c < p.numCells(); ++c)
    f.printf("         %d\n", static_cast<int>(p.types[c]));
  f.write("        </DataArray>\n");
  f.write("      </Cells>\n");
  f.write("    </Piece>\n");
  f.write("  </UnstructuredGrid>\n");
  f.write("</VTKFile>\n");
  f.close();
}

void writePvtu(const std::string& path, int step, const std::vector<FieldDecl>& decls,
                      const std::vector<int>& pieceIds) {
  CheckedFile f(path);
  f.write("<?xml version=\"1.0\"?>\n");
  f.write("<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
  f.write("  <PUnstructuredGrid GhostLevel=\"0\">\n");
  for (int pass = 0; pass < 2; ++pass) {
    const bool point = pass == 0;
    f.write(point ? "    <PPointData>\n" : "    <PCellData>\n");
    for (const FieldDecl& d : decls) {
      if (d.point != point) continue;
      f.printf("      <PDataArray type=\"Float64\" Name=\"%s\" NumberOfComponents=\"%d\"/>\n",
                   xmlEscape(d.name).c_str(), writtenComponents(d.components));
    }
    f.write(point ? "    </PPointData>\n" : "    </PCellData>\n");
  }
  f.write("    <PPoints>\n");
  f.write("      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n");
  f.write("    </PPoints>\n");
  for (int id : pieceIds)
    f.printf("    <Piece Source=\"%s\"/>\n", VtkWriter::vtuFileName(step, id).c_str());
  f.write("  </PUnstructuredGrid>\n");
  f.write("</VTKFile>\n");
  f.close();
}

/// The time series is rewritten after every step, atomically: a reader (or
/// a crash) sees the previous complete series or the new one.
void writePvd(const std::string& path, const std::vector<std::pair<int, double>>& steps) {
  std::string text = "<?xml version=\"1.0\"?>\n"
                     "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                     "  <Collection>\n";
  char line[256];
  for (const auto& s : steps) {
    std::snprintf(line, sizeof line, "    <DataSet timestep=\"%.17g\" group=\"\" part=\"0\" file=\"%s\"/>\n",
                  s.second, VtkWriter::pvtuFileName(s.first).c_str());
    text += line;
  }
  text += "  </Collection>\n</VTKFile>\n";
  writeFileAtomically(path, text);
}

}  // namespace

VtkWriter::VtkWriter(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& directory,
                     const std::string& pvdName)
    : comm_(std::move(comm)), pvdName_(pvdName) {
  DDC_INPUT_REQUIRE(!comm_.is_null(), "VTK output in '" << directory << "': null communicator");
  DDC_INPUT_REQUIRE(!directory.empty(), "VTK output: the output directory path is empty");
  DDC_INPUT_REQUIRE(!pvdName_.empty() && pvdName_.find('/') == std::string::npos &&
                        pvdName_ != "." && pvdName_ != "..",
                    "VTK output: invalid time-series file name '"
                        << pvdName << "' (expected a file name such as 'solution.pvd')");
  if (pvdName_.size() < 4 || pvdName_.compare(pvdName_.size() - 4, 4, ".pvd") != 0)
    pvdName_ += ".pvd";
  vtkDir_ = (fs::path(directory) / "vtk").string();

  std::string error;
  if (comm_->getRank() == 0) {
    try {
      fs::create_directories(vtkDir_);
      if (!fs::is_directory(vtkDir_))
        error = "cannot create VTK output directory '" + vtkDir_ + "'";
    } catch (const fs::filesystem_error& e) {
      error = "cannot create VTK output directory '" + vtkDir_ + "': " + e.code().message();
    }
  }
  error = firstErrorOnAnyRank(*comm_, error);
  if (!error.empty()) throw InputError(error);
}

std::string VtkWriter::pvdPath() const { return (fs::path(vtkDir_) / pvdName_).string(); }

std::string VtkWriter::pvtuFileName(int step) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "step_%05d.pvtu", step);
  return buf;
}

std::string VtkWriter::vtuFileName(int step, int pieceId) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "step_%05d_piece_%04d.vtu", step, pieceId);
  return buf;
}

namespace {
/// The step number of a file name "step_SSSSS.pvtu" or
/// "step_SSSSS_piece_PPPP.vtu" (-1 for any other name).
int stepOfFileName(const std::string& name) {
  if (name.compare(0, 5, "step_") != 0) return -1;
  size_t end = 5;
  while (end < name.size() && std::isdigit(static_cast<unsigned char>(name[end]))) ++end;
  if (end == 5 || end - 5 > 9) return -1;
  const std::string rest = name.substr(end);
  if (rest != ".pvtu" && (rest.compare(0, 7, "_piece_") != 0 || rest.size() < 11 ||
                          rest.compare(rest.size() - 4, 4, ".vtu") != 0))
    return -1;
  return std::stoi(name.substr(5, end - 5));
}

std::string readWholeFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  if (!in.good() && !in.eof()) throw OutputError("cannot read '" + path.string() + "'");
  return os.str();
}
}  // namespace

std::vector<int> VtkWriter::adoptSteps(const std::string& sourceDirectory,
                                       const std::vector<std::pair<int, double>>& steps) {
  std::string error;
  std::vector<int> missing;
  std::vector<std::pair<int, double>> kept;
  if (comm_->getRank() == 0) {
    try {
      const fs::path source = fs::path(sourceDirectory) / "vtk", target(vtkDir_);
      std::error_code ec;
      const bool same = fs::equivalent(source, target, ec);
      std::set<int> wanted;
      for (const auto& [step, time] : steps) {
        if (fs::exists(source / pvtuFileName(step))) {
          wanted.insert(step);
          kept.emplace_back(step, time);
        } else {
          missing.push_back(step);
        }
      }
      std::vector<fs::path> files;
      if (fs::is_directory(source))
        for (const auto& entry : fs::directory_iterator(source)) files.push_back(entry.path());
      for (const fs::path& file : files) {
        const std::string name = file.filename().string();
        const int step = stepOfFileName(name);
        if (step < 0) continue;
        if (!wanted.count(step)) {
          if (same) fs::remove(file);  // written after the checkpoint
        } else if (!same) {
          writeFileAtomically((target / name).string(), readWholeFile(file));
        }
      }
      writePvd(pvdPath(), kept);
    } catch (const OutputError& e) {
      error = std::string("VtkWriter: continuing the series of '") + sourceDirectory + "': " + e.what();
    } catch (const fs::filesystem_error& e) {
      error = std::string("VtkWriter: continuing the series of '") + sourceDirectory + "': " + e.what();
    }
  }
  error = firstErrorOnAnyRank(*comm_, error);
  if (!error.empty()) throw OutputError(error);
  // Every rank keeps the list (writeStep() extends it).
  std::vector<double> flat;
  for (const auto& [step, time] : kept) flat.insert(flat.end(), {double(step), time});
  int n = int(flat.size());
  Teuchos::broadcast(*comm_, 0, Teuchos::outArg(n));
  flat.resize(n);
  if (n > 0) Teuchos::broadcast(*comm_, 0, n, flat.data());
  steps_.clear();
  for (int i = 0; i + 1 < n; i += 2) steps_.emplace_back(int(flat[i]), flat[i + 1]);
  int m = int(missing.size());
  Teuchos::broadcast(*comm_, 0, Teuchos::outArg(m));
  missing.resize(m);
  if (m > 0) Teuchos::broadcast(*comm_, 0, m, missing.data());
  return missing;
}

void VtkWriter::writeStep(int step, double time, const std::vector<VtkPiece>& localPieces) {
  const Teuchos::Comm<int>& comm = *comm_;
  const int rank = comm.getRank();
  const int size = comm.getSize();

  // 1. Local consistency of every piece.
  std::string error;
  if (step < 0) {
    std::ostringstream os;
    os << "VtkWriter: step must be >= 0, got " << step;
    error = os.str();
  }
  std::string localSig;
  std::set<int> localIds;
  for (std::size_t i = 0; i < localPieces.size() && error.empty(); ++i) {
    const VtkPiece& p = localPieces[i];
    std::string e = validatePiece(p);
    if (e.empty() && !localIds.insert(p.id).second) e = "piece id given twice on this rank";
    const std::string sig = fieldSignature(p);
    if (e.empty() && i > 0 && sig != localSig)
      e = "its point/cell fields differ from those of piece " + std::to_string(localPieces[0].id) +
          " (every piece must declare the same fields in the same order)";
    if (i == 0) localSig = sig;
    if (!e.empty()) error = pieceLabel(step, p, rank) + e;
  }
  error = firstErrorOnAnyRank(comm, error);
  if (!error.empty()) throw std::invalid_argument(error);

  // 2. Consistency across ranks: the same fields everywhere, unique piece ids.
  const int mine = localPieces.empty() ? size : rank;
  int sigRoot = size;
  Teuchos::reduceAll<int, int>(comm, Teuchos::REDUCE_MIN, mine, Teuchos::outArg(sigRoot));
  std::string sig;
  if (sigRoot < size) {
    sig = broadcastString(comm, sigRoot, localSig);
    if (!localPieces.empty() && localSig != sig) {
      std::ostringstream os;
      os << pieceLabel(step, localPieces[0], rank)
         << "its point/cell fields differ from those of the pieces on rank " << sigRoot
         << " (every piece must declare the same fields in the same order)";
      error = os.str();
    }
  }
  std::vector<int> ids;
  for (const VtkPiece& p : localPieces) ids.push_back(p.id);
  const int count = static_cast<int>(ids.size());
  std::vector<int> counts(size, 0);
  Teuchos::gather<int, int>(&count, 1, counts.data(), 1, 0, comm);
  std::vector<int> displs(size, 0);
  for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  const int total = rank == 0 ? displs[size - 1] + counts[size - 1] : 0;
  std::vector<int> allIds(std::max(total, 1), 0);
  std::vector<int> sendIds(ids);
  sendIds.push_back(0);  // never pass a null buffer
  Teuchos::gatherv<int, int>(sendIds.data(), count, allIds.data(), counts.data(), displs.data(), 0,
                             comm);
  allIds.resize(total);
  if (rank == 0 && error.empty()) {
    std::sort(allIds.begin(), allIds.end());
    const auto dup = std::adjacent_find(allIds.begin(), allIds.end());
    if (dup != allIds.end()) {
      std::ostringstream os;
      os << "VtkWriter: step " << step << ": piece id " << *dup
         << " is used on more than one rank (piece ids must be unique across ranks)";
      error = os.str();
    }
  }
  error = firstErrorOnAnyRank(comm, error);
  if (!error.empty()) throw std::invalid_argument(error);

  // 3. Every rank writes its pieces.
  try {
    for (const VtkPiece& p : localPieces) writeVtu((fs::path(vtkDir_) / vtuFileName(step, p.id)).string(), p);
  } catch (const OutputError& e) {
    error = std::string("VtkWriter: ") + e.what();
  }
  error = firstErrorOnAnyRank(comm, error);
  if (!error.empty()) throw OutputError(error);

  // 4. Rank 0 writes the step file and the time series.
  auto it = std::lower_bound(steps_.begin(), steps_.end(), std::make_pair(step, time),
                             [](const std::pair<int, double>& a, const std::pair<int, double>& b) {
                               return a.first < b.first;
                             });
  if (it != steps_.end() && it->first == step)
    it->second = time;
  else
    steps_.insert(it, std::make_pair(step, time));
  if (rank == 0) {
    try {
      writePvtu((fs::path(vtkDir_) / pvtuFileName(step)).string(), step, parseSignature(sig), allIds);
      writePvd(pvdPath(), steps_);
    } catch (const OutputError& e) {
      error = std::string("VtkWriter: ") + e.what();
    }
  }
  error = firstErrorOnAnyRank(comm, error);
  if (!error.empty()) throw OutputError(error);
}

}  // namespace ddc
