// Exodus II results (Output/Exodus): one file per run in the format of the
// SEACAS tools, read by ParaView, VisIt and the Trilinos/SEACAS world. It
// holds the mesh - one element block per body (id = body index + 1, named
// after the body), every node set and side set of the mesh (ids from 1 in
// name order, named "<body>/<set>") - and one time step per converged step:
//  - nodal variables displ_x, displ_y (, displ_z); in dynamics vel_* and
//    acc_*; with contact contact_gap, contact_pressure, contact_multiplier
//    (0 away from slave nodes);
//  - element variables stress_xx, stress_yy, stress_zz, stress_xy,
//    stress_yz, stress_xz (Cauchy), von_mises, strain_energy_density;
//  - the global variables the caller names (load factor or time, energies,
//    contact force).
// Exodus node i + 1 is mesh node i, element e + 1 mesh element e (the bodies
// are contiguous element ranges in body order). Element node order and side
// numbering follow Exodus II (Schoof & Yarberry, "EXODUS II: A Finite
// Element Data Model", SAND92-2137; Sjaardema et al., SEACAS), which differs
// from the Gmsh order of the mesh for Hex20, Hex27 and Tet10
// (DDC_ExodusCells.hpp).
//
// Rank 0 writes the file with the Exodus II library; the other ranks send it
// their elements' values and the displacements of their elements' nodes.
#pragma once

#include <Teuchos_Comm.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "DDC_ExodusCells.hpp"
#include "DDC_Model.hpp"

namespace ddc {

/// Writes the Exodus II results of one run (see the top of this file).
class ExodusWriter {
 public:
  /// Create `path` with the mesh of `model` and the variable names
  /// (collective). `dynamics`: also velocities and accelerations;
  /// `globalNames`: the names of the global variables writeStep() takes.
  /// \throws OutputError (on every rank) naming the file and the Exodus II
  ///         library's reason when it cannot be created or written.
  ExodusWriter(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& path, const Model& model,
               bool dynamics, std::vector<std::string> globalNames);
  ~ExodusWriter();
  ExodusWriter(const ExodusWriter&) = delete;
  ExodusWriter& operator=(const ExodusWriter&) = delete;

  /// Append one time step (collective): the time value (load factor, or
  /// time in dynamics), the displacements `u` (model's owned map), in
  /// dynamics the velocities and accelerations, and the global values (as
  /// many as globalNames). The file is flushed after the step.
  /// \throws OutputError (every rank) when the step cannot be written.
  void writeStep(double time, const Vector& u, const Vector* velocity, const Vector* acceleration,
                 const std::vector<double>& globals);
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
  const Model& model_;
  bool dynamics_;
  std::vector<std::string> globalNames_;
  int exoid_ = -1;  ///< rank 0: the open file (-1 elsewhere or once closed)
  int steps_ = 0;
  int numNodal_ = 0;  ///< nodal variables
};

}  // namespace ddc
