// Exodus II results (Output/Exodus): one file per run in the format of the
// SEACAS tools, read by ParaView, VisIt and the Trilinos/SEACAS world. It
// holds the mesh - one element block per body (id = body index + 1, named
// after the body), every node set and side set of the mesh (ids from 1 in
// name order, named "<body>/<set>") - and one time step per converged step:
//  - the nodal, element and global variables the caller names
//    (ExodusVariables; what an analysis writes is in doc/user-guide.md,
//    "The output directory": displacements, in dynamics velocities and
//    accelerations, contact gap, pressure and multiplier, stresses, energy
//    densities, and the history's global values).
// The writer knows a mesh, not a model: the caller hands it each rank's
// values (ExodusStepValues), as VtkWriter takes pieces.
// Exodus node i + 1 is mesh node i, element e + 1 mesh element e (the bodies
// are contiguous element ranges in body order). Element node order and side
// numbering follow Exodus II (Schoof & Yarberry, "EXODUS II: A Finite
// Element Data Model", SAND92-2137; Sjaardema et al., SEACAS), which differs
// from the Gmsh order of the mesh for Hex20, Hex27 and Tet10
// (DDC_ExodusCells.hpp).
//
// With the whole mesh on every rank, rank 0 writes the file with the Exodus
// II library and the other ranks send it the values of their nodes and
// elements. On a part of the mesh (Mesh::isPart(), no rank holds the whole)
// nothing is gathered: each rank writes its own file, `path`.P.r ("spread"
// files, the Nemesis I convention of SEACAS: r zero-padded to the digits of
// P), with its elements and their nodes, their ids in the whole mesh as the
// node and element id maps, every body's block (empty where the rank has
// none of its elements), the sets restricted to the part, and the whole
// mesh's counts (ex_put_init_global). SEACAS epu joins the pieces into one
// file; ParaView and VisIt read them as one.
#pragma once

#include <Teuchos_Comm.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "DDC_ExodusCells.hpp"
#include "DDC_Mesh.hpp"

namespace ddc {

/// The variables of an Exodus II results file, by name.
struct ExodusVariables {
  std::vector<std::string> nodal;    ///< one value per mesh node and step
  std::vector<std::string> element;  ///< one value per mesh element and step
  std::vector<std::string> global;   ///< one value per step
};

/// One rank's values of one time step (ExodusWriter::writeStep()). A node
/// or element may come from several ranks (the same values); nodes and
/// elements no rank gives are written as 0.
struct ExodusStepValues {
  std::vector<int> nodes;        ///< mesh node ids
  std::vector<double> nodal;     ///< nodes.size() rows of ExodusVariables::nodal.size() values
  std::vector<int> elements;     ///< mesh element ids
  std::vector<double> element;   ///< elements.size() rows of ExodusVariables::element.size() values
  std::vector<double> global;    ///< ExodusVariables::global.size() values (rank 0's are written)
};

/// Writes the Exodus II results of one run (see the top of this file).
class ExodusWriter {
 public:
  /// Create `path` with `mesh` (the same on every rank) and the variable
  /// names (collective); on a part of a mesh each rank creates its piece
  /// piecePath(path, ranks, rank).
  /// \throws OutputError (on every rank) naming the file and the Exodus II
  ///         library's reason when it cannot be created or written.
  ExodusWriter(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& path, const Mesh& mesh,
               ExodusVariables variables);
  ~ExodusWriter();
  ExodusWriter(const ExodusWriter&) = delete;
  ExodusWriter& operator=(const ExodusWriter&) = delete;

  /// Append one time step (collective): the time value (load factor, or
  /// time in dynamics) and this rank's values. The file is flushed after
  /// the step.
  /// \throws std::invalid_argument (every rank) when the values do not fit
  ///         the variables; OutputError (every rank) when the step cannot
  ///         be written.
  void writeStep(double time, const ExodusStepValues& values);
  /// The variables named at construction.
  const ExodusVariables& variables() const { return variables_; }
  /// Continue the results of an earlier run of the same model (a restart,
  /// collective): copy its first `count` time steps (time values and every
  /// variable) from the Exodus II results `source` - one file, or the
  /// pieces of one (resultFiles()), written on any number of ranks; the
  /// values go by node and element id - which must not be path(). Copies
  /// fewer if `source` has fewer; none if it is missing, unreadable, has
  /// other variables or another mesh.
  /// \return the steps copied and, when fewer than `count`, why (the same
  ///         on every rank)
  /// \throws OutputError (every rank) when this file cannot be written
  std::pair<int, std::string> copySteps(const std::string& source, int count);
  /// Close the file (collective; also done by the destructor, which does
  /// not throw). \throws OutputError when closing fails.
  void close();
  /// The file's path (with pieces, the path they are named after).
  const std::string& path() const { return path_; }
  /// Whether each rank writes a piece of the results (the mesh is a part).
  bool spread() const { return mesh_.isPart(); }
  /// The piece of rank `rank` of `ranks` of the results `path`: `path`.P.r,
  /// r zero-padded to the digits of P.
  static std::string piecePath(const std::string& path, int ranks, int rank);
  /// The files of the results `path` on disk: `path` when it is a file,
  /// else the pieces piecePath(path, P, r) for r = 0 .. P - 1 when all of
  /// them exist for one P; empty otherwise. Reads the directory of `path`
  /// on the calling rank only.
  static std::vector<std::string> resultFiles(const std::string& path);
  /// The sizes of the node sets and side sets in the whole mesh (in name
  /// order), which every piece states.
  struct SetCounts {
    std::vector<int> nodeSets, sideSets;
  };
  /// Time steps written so far.
  int numSteps() const { return steps_; }

 private:
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  std::string path_;
  std::string file_;  ///< the file this rank writes: path_, or its piece
  const Mesh& mesh_;
  ExodusVariables variables_;
  SetCounts setCounts_;  ///< with pieces
  int exoid_ = -1;  ///< the open file of a writing rank (-1 elsewhere or once closed)
  /// Whether this rank writes a file: rank 0, or every rank with pieces.
  bool writes() const { return spread() || comm_->getRank() == 0; }
  /// Create the file of this rank (writes()); returns the first error or "".
  std::string create(const std::string& file);
  int steps_ = 0;
};

}  // namespace ddc
