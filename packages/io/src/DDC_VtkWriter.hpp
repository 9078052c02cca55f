// Parallel VTK XML output: one .vtu per piece (subdomain), one .pvtu per step,
// one .pvd time series (doc/user-guide.md, "The output directory", vtk/).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Teuchos_Comm.hpp>
#include <Teuchos_RCP.hpp>

namespace ddc {

/// One point or cell data array of a VtkPiece.
struct VtkField {
  std::string name;           ///< array name; non-empty, no tab or line break
  int components = 1;         ///< values per point / cell (>= 1)
  std::vector<double> values; ///< components × (number of points or cells), interleaved
};

/// \brief One unstructured-grid piece, e.g. the mesh of one subdomain.
///
/// Cell types and their node counts accepted: 1 VTK_VERTEX (1), 3 VTK_LINE
/// (2), 5 VTK_TRIANGLE (3), 9 VTK_QUAD (4), 21 VTK_QUADRATIC_EDGE (3),
/// 22 VTK_QUADRATIC_TRIANGLE (6), 23 VTK_QUADRATIC_QUAD (8),
/// 28 VTK_BIQUADRATIC_QUAD (9). VTK's node order for 28 is 4 corners,
/// 4 mid-edge nodes (edges 0-1, 1-2, 2-3, 3-0), centre: the same as Gmsh's
/// 9-node quadrangle, so Gmsh connectivity is passed unchanged.
struct VtkPiece {
  int id = 0;                         ///< piece id (e.g. subdomain id), >= 0, unique across ranks
  std::vector<double> points;         ///< 3 per point (x, y, z); current or reference coordinates
  std::vector<int> connectivity;      ///< local point indices of all cells, concatenated
  std::vector<int> offsets;           ///< VTK offsets: end of each cell in connectivity
  std::vector<unsigned char> types;   ///< VTK cell type per cell
  std::vector<VtkField> pointData;    ///< per-point arrays
  std::vector<VtkField> cellData;     ///< per-cell arrays

  int numPoints() const { return static_cast<int>(points.size() / 3); }
  int numCells() const { return static_cast<int>(types.size()); }
};

/// \brief Writes a time series of parallel unstructured grids (ASCII VTK XML).
///
/// Files, all in `directory/vtk/`:
///  - `step_SSSSS_piece_PPPP.vtu`: one per piece, written by the rank owning it
///    (step and piece id zero-padded to 5 and 4 digits; more digits if larger);
///  - `step_SSSSS.pvtu`: written by rank 0, lists the pieces of all ranks
///    (in increasing piece id) with the PPointData / PCellData declarations;
///  - `<pvdName>`: written by rank 0 after every step, the collection of
///    all steps written so far by this writer, `timestep` = the step's time.
///    It is replaced atomically (written to a temporary file, then renamed).
///
/// Fields: every piece on every rank must declare the same point and cell
/// fields (same names, component counts and order; the values differ). This
/// is checked collectively, so ranks without pieces are fine (the
/// declarations of the .pvtu come from the lowest rank that has pieces).
///
/// Vectors: a field with 2 components is written with 3 components, z = 0
/// appended, so ParaView can "Warp By Vector" with a 2-D displacement field.
/// Other component counts are written as given (e.g. pass 3 or 4 stress
/// components and name them in the field name or documentation).
///
/// All numbers are written with full double precision ("%.17g").
class VtkWriter {
 public:
  /// Collective. Rank 0 creates `directory/vtk` (and missing parents).
  /// \param directory  output directory, e.g. OutputDirectory::path()
  /// \param pvdName  file name of the time series in `directory/vtk`; ".pvd"
  ///   is appended if missing; must not contain a path separator.
  /// \throws InputError (every rank) if the directory cannot be created or
  ///   pvdName is invalid.
  VtkWriter(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& directory,
            const std::string& pvdName = "solution.pvd");

  /// Collective: every rank calls it with its own pieces (possibly none).
  /// Writing the same step again replaces its files and its .pvd entry.
  /// \throws std::invalid_argument (every rank) if a piece is inconsistent
  ///   (sizes, indices, cell types, duplicate piece ids across ranks, fields
  ///   differing between pieces) or step < 0; nothing is written then.
  /// \throws OutputError (a std::runtime_error, every rank) naming the file and the
  ///   operating system's reason if a file cannot be written, synced or closed.
  void writeStep(int step, double time, const std::vector<VtkPiece>& localPieces);

  /// Continue the series of an earlier run (a restart, collective): the
  /// steps `steps` of `sourceDirectory`/vtk (the files of each step, copied
  /// here unless that is this writer's directory) become the first of this
  /// series, and files of other steps in this writer's directory are
  /// removed (steps the earlier run wrote after its checkpoint). A step
  /// whose .pvtu is missing is left out.
  /// \return the steps left out (the same on every rank)
  /// \throws OutputError (every rank) naming the file that cannot be copied
  ///         or removed
  std::vector<int> adoptSteps(const std::string& sourceDirectory, const std::vector<std::pair<int, double>>& steps);

  /// `directory/vtk`.
  const std::string& vtkDirectory() const { return vtkDir_; }

  /// Full path of the .pvd file.
  std::string pvdPath() const;

  /// File names (relative to vtkDirectory()) of step files and pieces.
  static std::string pvtuFileName(int step);
  static std::string vtuFileName(int step, int pieceId);

  /// (step, time) of the steps written so far, in increasing step order.
  const std::vector<std::pair<int, double>>& steps() const { return steps_; }

 private:
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  std::string vtkDir_;
  std::string pvdName_;
  std::vector<std::pair<int, double>> steps_;
};

}  // namespace ddc
