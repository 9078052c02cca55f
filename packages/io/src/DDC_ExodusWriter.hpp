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
// Rank 0 writes the file with the Exodus II library; the other ranks send it
// the values of their nodes and elements.
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
  /// names (collective).
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
  /// variable) from the Exodus II file `source`, which must not be path().
  /// Copies fewer if `source` has fewer; none if it is missing, unreadable
  /// or has other variables.
  /// \return the steps copied and, when fewer than `count`, why (the same
  ///         on every rank)
  /// \throws OutputError (every rank) when this file cannot be written
  std::pair<int, std::string> copySteps(const std::string& source, int count);
  /// Close the file (collective; also done by the destructor, which does
  /// not throw). \throws OutputError when closing fails.
  void close();
  /// The file's path.
  const std::string& path() const { return path_; }
  /// Time steps written so far.
  int numSteps() const { return steps_; }

 private:
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  std::string path_;
  const Mesh& mesh_;
  ExodusVariables variables_;
  int exoid_ = -1;  ///< rank 0: the open file (-1 elsewhere or once closed)
  int steps_ = 0;
};

}  // namespace ddc
