#include "DDC_Analysis.hpp"

#include "DDC_ExodusWriter.hpp"

#include "DDC_TimeIntegrator.hpp"

#include <Teuchos_XMLParameterListHelpers.hpp>

#include <algorithm>
#include <array>
#include <set>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "DDC_ContactParameters.hpp"
#include "DDC_Error.hpp"
#include "DDC_Substructuring.hpp"
#include "DDC_ExodusMesh.hpp"
#include "DDC_Gmsh.hpp"
#include "DDC_HistoryWriter.hpp"
#include "DDC_InputDeck.hpp"
#include "DDC_Memory.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_ModelOutput.hpp"
#include "DDC_OutputDirectory.hpp"
#include "DDC_Parameters.hpp"
#include "DDC_Partition.hpp"
#include "DDC_ResultFile.hpp"
#include "DDC_StopRequest.hpp"
#include "DDC_VtkWriter.hpp"

namespace ddc {

namespace {

using PL = Teuchos::ParameterList;

const std::vector<std::string> kGenerators = {"Rectangle", "Annular Sector", "Box", "Cylindrical Shell Sector",
                                              "Sphere Octant", "Gmsh", "Exodus"};

Teuchos::RCP<const PL> generatorValidParameters(const std::string& g) {
  if (g == "Rectangle") return RectangleGenerator::getValidParameters();
  if (g == "Annular Sector") return AnnularSectorGenerator::getValidParameters();
  if (g == "Box") return BoxGenerator::getValidParameters();
  if (g == "Cylindrical Shell Sector") return CylindricalShellSectorGenerator::getValidParameters();
  if (g == "Sphere Octant") return SphereOctantGenerator::getValidParameters();
  if (g == "Exodus") return ExodusMeshReader::getValidParameters();
  return GmshReader::getValidParameters();
}

/// "Element" sublist: Type plus the union of the element types' parameters.
Teuchos::RCP<PL> elementValidParameters(const ElementFactory& factory) {
  auto pl = Teuchos::rcp(new PL("Element"));
  const auto names = factory.bodyNames();  // contact elements are not body types
  std::string doc = "Element type of the body:";
  for (const auto& n : names) doc += " '" + n + "' (" + factory.entry(n).description + ");";
  pl->set("Type", names.empty() ? std::string() : std::string("Quad4"), doc, enumValidator(names, "Type"));
  for (const auto& n : names) {
    const auto& v = *factory.entry(n).validParameters;
    for (auto it = v.begin(); it != v.end(); ++it)
      if (!pl->isParameter(v.name(it)) && !pl->isSublist(v.name(it))) pl->setEntry(v.name(it), v.entry(it));
  }
  return pl;
}

Teuchos::RCP<PL> bodyValidParameters(const ElementFactory& factory) {
  auto pl = Teuchos::rcp(new PL("<Body Name>"));
  pl->set("Generator", "Rectangle",
          "How the body's mesh is made: a built-in generator, a Gmsh file or an Exodus II file; its parameters go in the "
          "sublist of the same name.",
          enumValidator(kGenerators, "Generator"));
  for (const auto& g : kGenerators)
    setSublist(*pl, g, *generatorValidParameters(g), "Parameters of the " + g + " generator (Generator = " + g + ").");
  setSublist(*pl, "Element", *elementValidParameters(factory), "Element type and material of the body.");
  return pl;
}

Teuchos::RCP<PL> loadSteppingValidParameters() {
  auto pl = Teuchos::rcp(new PL("Load Stepping"));
  pl->set("Number of Steps", 10, "Number of equal load steps from load factor 0 to the final load factor.",
          greaterThan(0));
  pl->set("Final Load Factor", 1.0,
          "Load factor at the end of the analysis (boundary values scale with it). Load factors run from 0 up "
          "to it, so it is positive: a reversed load is given by the signs of the boundary values.",
          greaterThan(0.0));
  pl->set("Max Bisections", 6,
          "How many times a load step may be halved when Newton fails (diverges, exceeds its iteration "
          "limit or inverts an element) before the analysis stops with an error.",
          atLeast(0));
  return pl;
}

/// "Step Control": steps sized by the frozen-geometry error of the
/// decomposed contact element (doc/contact.md, "Step control by the
/// frozen-geometry error").
Teuchos::RCP<PL> stepControlValidParameters() {
  auto pl = Teuchos::rcp(new PL("Step Control"));
  pl->set("Error Tolerance", 0.0,
          "0 (default): the steps of Load Stepping / Dynamics, halved only when Newton fails. > 0 (needs "
          "Contact/Formulation = Decomposed ...): the largest frozen-geometry error indicator a step may "
          "have, an estimate of the relative strain-energy error the frozen projection and normal leave, "
          "read at the step-end pairing (doc/contact.md). A step above it is solved again with the "
          "projections and normals of its end (Geometry Corrections), then smaller; a step well below it "
          "lets the next one grow (within Minimum/Maximum Step Size; the first step is Final Load Factor / "
          "Number of Steps, or Dynamics/Time Step). On the two half-rings the error was about the indicator "
          "(median ratio 0.8-0.9) and 0.005 kept it below 0.5 % (doc/figure4.md).",
          between(0.0, 1.0, Interval::RightOpen));
  pl->set("Geometry Corrections", 3,
          "How many times a step whose indicator exceeds Error Tolerance is solved again with the projections "
          "and normals of its end (each time one pairing exchange and a Newton solve) before it is repeated "
          "smaller; 0: repeated smaller at once. The repeats converge to the geometry of the step's end "
          "(doc/contact.md).",
          atLeast(0));
  pl->set("Minimum Step Size", 0.0,
          "Smallest step (load factor or time) the error control may take; a step at this size is accepted "
          "whatever its indicator (with a warning). 0 (default): the first step halved Max Bisections times.",
          atLeast(0.0));
  pl->set("Maximum Step Size", 0.0,
          "Largest step the error control may grow to (load factor or time). 0 (default): the first step "
          "(the steps never grow beyond Final Load Factor / Number of Steps, or Dynamics/Time Step).",
          atLeast(0.0));
  return pl;
}

/// "Dynamics": the integrator, the time steps, the Newmark parameters, the
/// mass matrix and the initial velocities (doc/user-guide.md, "Dynamics").
Teuchos::RCP<const Teuchos::ParameterList> dynamicsValidParameters() {
  static const Teuchos::RCP<const Teuchos::ParameterList> valid = [] {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("Dynamics"));
    pl->set("Integrator", std::string("None"),
            "None: a quasi-static analysis (Load Stepping; no inertia). Otherwise implicit structural dynamics, "
            "M a + f_int(u) = f_ext(t), integrated by Newmark (Newmark Beta, Newmark Gamma), HHT-alpha (HHT "
            "Alpha) or Generalized-alpha (Spectral Radius); the load factor of the boundary conditions is then "
            "the time t (a Load Curve gives a value as a function of time), and Load Stepping is not read.",
            enumValidator({"None", "Newmark", "HHT-alpha", "Generalized-alpha"}, "Integrator"));
    pl->set("Final Time", 1.0, "Time at the end of a dynamic analysis (it starts at 0).", greaterThan(0.0));
    pl->set("Time Step", 0.1,
            "Time step h of a dynamic analysis; Final Time / Time Step must be a whole number of steps. A step "
            "on which Newton fails is halved (Max Bisections).",
            greaterThan(0.0));
    pl->set("Max Bisections", 6, "How many times a time step may be halved when Newton fails.", atLeast(0));
    pl->set("Newmark Beta", 0.25, "Newmark beta (> 0, 2 beta >= gamma): 1/4 with gamma = 1/2 is the trapezoidal "
                                  "rule, which conserves the energy of a linear free vibration.",
            greaterThan(0.0));
    pl->set("Newmark Gamma", 0.5, "Newmark gamma (>= 1/2): 1/2 has no numerical damping, more damps high "
                                  "frequencies (first-order accurate).",
            atLeast(0.5));
    pl->set("HHT Alpha", -0.05,
            "HHT-alpha's alpha in [-1/3, 0] (Hilber, Hughes & Taylor 1977): 0 is the trapezoidal rule, more "
            "negative damps high frequencies more; second-order accurate.",
            between(-1.0 / 3.0, 0.0));
    pl->set("Spectral Radius", 0.8,
            "Generalized-alpha's spectral radius at infinite frequency rho_inf in [0, 1] (Chung & Hulbert 1993): "
            "1 no numerical damping, 0 annihilates the highest modes in one step; second-order accurate.",
            between(0.0, 1.0));
    pl->set("Rayleigh Alpha", 0.0,
            "Mass-proportional Rayleigh damping alpha_R (1/time): C = alpha_R M + beta_R K, the damping ratio "
            "of a mode of angular frequency w being alpha_R / (2 w) + beta_R w / 2.",
            atLeast(0.0));
    pl->set("Rayleigh Beta", 0.0,
            "Stiffness-proportional Rayleigh damping beta_R (time), K the element tangents at the current "
            "state (see Rayleigh Alpha).",
            atLeast(0.0));
    pl->set("Mass Matrix", std::string("Consistent"),
            "Element mass matrices: Consistent (int rho N_a N_b dV), HRZ (diagonal, scaled to the element's "
            "mass; positive for every element type) or Row-Sum (diagonal; zero or negative at the corners of "
            "Hex20 and Tet10, refused there).",
            enumValidator({"Consistent", "HRZ", "Row-Sum"}, "Mass Matrix"));
    pl->set("Contact Surface Mass", std::string("Redistributed"),
            "With contact pairs: Redistributed moves the mass of every contact-surface node (slave and master "
            "surfaces) to the other nodes of its elements, each element keeping its mass (Khenous, Laborde & "
            "Renard 2008), so an impact does not leave the surface nodes chattering and the energy is kept; "
            "Kept leaves the mass matrices as they are (doc/user-guide.md, \"Contact in dynamics\").",
            enumValidator({"Redistributed", "Kept"}, "Contact Surface Mass"));
    Teuchos::ParameterList velocity("<Condition Name>");
    velocity.set("Set", std::string(""),
                 "A body's name (every node of it) or a qualified node set 'Body/set'.");
    for (const char* a : {"X", "Y", "Z"})
      velocity.set(std::string("Velocity ") + a, 0.0, std::string("Initial velocity along ") + a + " (Z: 3-D only).",
                   finiteNumber());
    Teuchos::ParameterList velocities("Initial Velocity");
    setSublist(velocities, "<Condition Name>", velocity, "One sublist per initial-velocity condition.");
    setSublist(*pl, "Initial Velocity", velocities,
               "Velocities at t = 0 by body or node set (default: at rest); later conditions override earlier "
               "ones on shared nodes. Prescribed DOFs take the velocity of their prescribed motion instead.");
    Teuchos::ParameterList body("<Condition Name>");
    body.set("Set", std::string(""), "The body's name: the field acts on all of it.");
    for (const char* a : {"X", "Y", "Z"})
      body.set(std::string("Acceleration ") + a, 0.0,
               std::string("Gravitational acceleration along ") + a + " (Z: 3-D only).", finiteNumber());
    Teuchos::ParameterList gravity("Gravity");
    setSublist(gravity, "<Condition Name>", body, "One sublist per body force.");
    setSublist(*pl, "Gravity", gravity,
               "Body forces by body: a uniform acceleration g (gravity), the force M g with the run's mass "
               "matrices, constant from t = 0 (not scaled by time); the initial acceleration balances it "
               "(doc/user-guide.md, \"Dynamics\").");
    return Teuchos::RCP<const Teuchos::ParameterList>(pl);
  }();
  return valid;
}

/// Each condition sublist of "Dynamics/<group>" (Initial Velocity,
/// Gravity), validated against its template, with its parameter path.
template <class F>
void forEachCondition(PL& dyn, const std::string& group, const char* keys, F f) {
  PL& list = dyn.sublist(group);
  const PL& valid = dynamicsValidParameters()->sublist(group).sublist("<Condition Name>");
  for (auto it = list.begin(); it != list.end(); ++it) {
    const std::string& name = list.name(it);
    const std::string where = "Dynamics/" + group + "/" + name;
    DDC_INPUT_REQUIRE(list.isSublist(name), "'" << where << "' must be a sublist (" << keys << ")");
    PL& c = list.sublist(name);
    validateLevel(c, valid, where);
    f(c, where);
  }
}

Teuchos::RCP<PL> newtonValidParameters() {
  auto pl = Teuchos::rcp(new PL("Newton"));
  pl->set("Max Iterations", 25, "Maximum Newton iterations (linear solves) per load step.", greaterThan(0));
  pl->set("Residual Tolerance", 1e-8,
          "Converged when ||r|| <= tol * ||r_0|| (r_0: first residual of the step, with the consistent "
          "predictor of prescribed displacements) ...",
          atLeast(0.0));
  pl->set("Absolute Residual Tolerance", 1e-10, "... or when ||r|| <= this absolute value (force units)",
          atLeast(0.0));
  pl->set("Energy Tolerance", 1e-16,
          "and the energy norm |du . r| <= tol * |du_0 . r_0| (both criteria must hold).", atLeast(0.0));
  pl->set("Print Iterations", false, "Print the residual and energy norm of every Newton iteration.");
  pl->set("Forcing Term", "Eisenstat-Walker",
          "Relative tolerance of each iterative linear solve (FETI-DP's dual solve, Belos back ends; a direct "
          "solve is exact anyway). Constant: the solver's own Convergence Tolerance every time. "
          "Eisenstat-Walker (inexact Newton): the first solve of a step uses that tolerance; solve k > 0 "
          "eta_k = 0.9 (||r_k|| / ||r_k-1||)^2 (Eisenstat & Walker 1996, choice 2, safeguarded by "
          "0.9 eta_k-1^2; left out with contact), and no solve is asked for less than 'Forcing Term Floor' "
          "times the Newton target max(Residual Tolerance ||r_0||, Absolute Residual Tolerance) over "
          "||r_k||; divided by how much less the previous solve reduced ||r|| than its tolerance promised; "
          "the full tolerance again after ||r|| grew; always between the solver's tolerance and 'Maximum "
          "Forcing Term' (doc/user-guide.md, 'Solution method'). The converged result meets the same "
          "Newton criteria either way.",
          enumValidator({"Eisenstat-Walker", "Constant"}, "Forcing Term"));
  pl->set("Maximum Forcing Term", 0.1, "Loosest relative tolerance of a linear solve with Forcing Term = "
          "Eisenstat-Walker.", between(0.0, 1.0, Interval::Open));
  pl->set("Forcing Term Floor", 0.1,
          "With Forcing Term = Eisenstat-Walker, a linear solve need not reduce the residual below this "
          "fraction of the Newton target (the absolute floor of the forcing term).",
          between(0.0, 1.0, Interval::LeftOpen));
  return pl;
}

Teuchos::RCP<PL> solverValidParameters() {
  auto pl = Teuchos::rcp(new PL("Solver"));
  pl->set("Memory Check", true,
          "Estimate the memory per rank from the mesh, the partition and the solver before building anything "
          "(doc/user-guide.md, 'Memory') and refuse a run whose estimate exceeds what this host offers each "
          "rank (MemAvailable, a control-group limit or ulimit -v, shared by the ranks on the host); false: "
          "run anyway.");
  pl->set("Strategy", "Monolithic",
          "Solution strategy. Monolithic: one global system (distributed Tpetra CrsMatrix, contact "
          "multipliers appended) solved by the Linear Solver below. FETI-DP: dual-primal domain "
          "decomposition over the partition's subdomains (the FETI-DP sublist); contact needs Contact/"
          "Formulation = Decomposed Node-To-Segment there (active pairs become rows of B, across partitions).",
          enumValidator({"Monolithic", "FETI-DP"}, "Strategy"));
  setSublist(*pl, "Linear Solver", *DirectSolverFactory::withIterativeSolvers().validParameters(),
             "Solver of the monolithic system ({Type, <back-end sublists>}): direct (MUMPS, Amesos2) or "
             "iterative (Belos-MueLu, Belos-FROSch; elasticity without contact only).");
  setSublist(*pl, "FETI-DP", *FetiDpSolver::getValidParameters(),
             "FETI-DP options: local and coarse solvers, preconditioner, scaling, Belos.");
  return pl;
}

Teuchos::RCP<PL> partitionValidParameters() {
  auto pl = Teuchos::rcp(new PL("Partition"));
  pl->set("Number of Subdomains", 0,
          "Number of subdomains; 0: automatic, i.e. with Solver/Strategy = FETI-DP and Method = METIS about one "
          "per 'Subdomain Size' DOFs (at least one per MPI rank), otherwise one per MPI rank.",
          atLeast(0));
  pl->set("Subdomain Size", 0,
          "Target DOFs per subdomain of the automatic count (Number of Subdomains = 0, FETI-DP, METIS); 0: "
          "the measured optimum of this machine, 1650 in 3-D and 3200 in 2-D (doc/performance.md).",
          atLeast(0));
  pl->set("Method", "METIS",
          "METIS: METIS_PartMeshDual over all bodies. By Body: each body one subdomain. Box Grid: a regular "
          "grid of boxes over the mesh's bounding box (Box Grid X x Box Grid Y (x Box Grid Z in 3-D) "
          "subdomains, by element centroid). Element Map File: one subdomain id per element, read from a file.",
          enumValidator({"METIS", "By Body", "Box Grid", "Element Map File"}, "Method"));
  pl->set("Box Grid X", 2, "Box Grid: number of boxes along x.", greaterThan(0));
  pl->set("Box Grid Y", 2, "Box Grid: number of boxes along y.", greaterThan(0));
  pl->set("Box Grid Z", 1, "Box Grid: number of boxes along z (3-D meshes only).", greaterThan(0));
  pl->set("Element Map File", "",
          "Element Map File: file with one subdomain id per element (mesh element order, whitespace "
          "separated, '#' comments); relative to the input deck's directory.");
  return pl;
}

int automaticSubdomainCount(const Mesh& mesh, const PL& partition, const std::string& strategy, int ranks) {
  if (strategy != "FETI-DP" || partition.get<std::string>("Method") != "METIS") return ranks;
  // Measured on block_3d at 421k DOFs (1650 DOFs per subdomain against 840
  // and 3300) and the 2-D elastic block at 822k (doc/performance.md): local
  // factorisations grow faster than linearly in the subdomain size, the
  // coarse problem with the number of subdomains.
  int size = partition.get<int>("Subdomain Size");
  if (size == 0) size = mesh.dim() == 3 ? 1650 : 3200;
  const double dofs = double(mesh.numNodes()) * mesh.dim();
  const double count = std::min(std::round(dofs / size), double(std::max(mesh.numElements(), 1)));
  return std::max(ranks, int(count));
}

Teuchos::RCP<PL> outputValidParameters() {
  auto pl = Teuchos::rcp(new PL("Output"));
  pl->set("VTK", true, "Write VTK files (vtk/*.vtu, *.pvtu, solution.pvd).");
  pl->set("VTK Interval", 1, "Write VTK every this many converged steps (the last step is always written).",
          greaterThan(0));
  pl->set("Exodus", false,
          "Write results.e, the Exodus II results of the run: the mesh (an element block per body, the node "
          "and side sets) and every converged step's displacements (velocities and accelerations in "
          "dynamics), contact gap, pressure and multiplier, element stresses and von Mises stress, and global "
          "values (doc/user-guide.md, 'The output directory').");
  pl->set("Progress", true, "Print one progress line per converged step on rank 0.");
  pl->set("Checkpoint Interval", 10,
          "Write checkpoint.ddc, the state a restart continues from (ddcontact --restart), after every this many "
          "converged steps, after the last one, and when the run fails or is stopped by SIGTERM, SIGINT or SIGUSR1 (at the "
          "end of its current step); it replaces the previous one. 0: no checkpoints (doc/user-guide.md, "
          "'Checkpoints and restart').",
          atLeast(0));
  pl->set("Contact Nodes", false,
          "Write contact_nodes.csv: one row per contact slave node at the last converged step (pair, node, "
          "reference x y z, gap, multiplier, tributary area, pressure, active), for contact-pressure "
          "distributions such as Hertz's (doc/contact.md).");
  return pl;
}

template <class T>
T get(const PL& pl, const std::string& name) {
  return pl.get<T>(name);
}

}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> Analysis::getValidParameters(const ElementFactory& factory) {
  auto pl = Teuchos::rcp(new PL("DDContact"));
  PL mesh("Mesh");
  PL bodies("Bodies");
  setSublist(bodies, "<Body Name>", *bodyValidParameters(factory), "One sublist per body; its name is the body's name.");
  setSublist(mesh, "Bodies", bodies, "The bodies of the model (at least one).");
  setSublist(*pl, "Mesh", mesh, "Geometry: bodies, their meshes, elements and materials.");
  PL bcs("Boundary Conditions");
  setSublist(bcs, "<Condition Name>", *BoundaryConditions::getValidParameters(), "One sublist per condition.");
  setSublist(*pl, "Boundary Conditions", bcs, "Prescribed displacements and tractions, scaled by the load factor.");
  setSublist(*pl, "Load Stepping", *loadSteppingValidParameters(), "Load stepping and bisection.");
  setSublist(*pl, "Dynamics", *dynamicsValidParameters(),
             "Implicit structural dynamics (Integrator = Newmark) instead of quasi-static load stepping.");
  setSublist(*pl, "Step Control", *stepControlValidParameters(),
             "Steps sized by the frozen-geometry error of the decomposed contact element (off by default).");
  setSublist(*pl, "Newton", *newtonValidParameters(), "Newton iteration and convergence criteria.");
  setSublist(*pl, "Solver", *solverValidParameters(), "Solution strategy and linear solvers.");
  setSublist(*pl, "Partition", *partitionValidParameters(), "Domain partitioning.");
  setSublist(*pl, "Contact", *ContactOptions::getValidParameters(), "Contact pairs and formulation.");
  setSublist(*pl, "Output", *outputValidParameters(), "What the run writes (besides history.csv).");
  return pl;
}

namespace {
/// Poisson's ratio from which a body is reported nearly incompressible
/// (lambda/mu >= 49): displacement elements lock noticeably.
constexpr double kNearlyIncompressible = 0.49;
/// The range of a body's extent and coordinates buildMesh() accepts.
constexpr double kMinBodyExtent = 1e-100;
constexpr double kMaxCoordinate = 1e100;
}  // namespace

std::shared_ptr<Mesh> buildMesh(Teuchos::ParameterList& meshParams, const ElementFactory& factory,
                                const std::string& baseDirectory, const MemoryLimit* budget,
                                const std::string& budgetHint) {
  PL validMesh("Mesh");
  validMesh.sublist("Bodies");
  validateLevel(meshParams, validMesh, "Mesh");
  DDC_INPUT_REQUIRE(meshParams.isSublist("Bodies") && meshParams.sublist("Bodies").numParams() > 0,
                    "sublist 'Mesh/Bodies' is required and must describe at least one body");
  PL& bodies = meshParams.sublist("Bodies");
  const auto validBody = bodyValidParameters(factory);
  auto mesh = std::make_shared<Mesh>();
  if (budget && std::isfinite(budget->bytes)) mesh->setMemoryBudget(budget->bytes, budget->source, budgetHint);
  for (auto it = bodies.begin(); it != bodies.end(); ++it) {
    const std::string name = bodies.name(it);
    const std::string path = "Mesh/Bodies/" + name;
    Activity activity("building the mesh of body '" + name + "' (" + std::to_string(mesh->numNodes()) +
                      " nodes before it)");
    DDC_INPUT_REQUIRE(bodies.isSublist(name), "'" << path << "' must be a sublist describing a body");
    PL& body = bodies.sublist(name);
    validateLevel(body, *validBody, path);
    const std::string gen = body.get<std::string>("Generator");
    for (const auto& g : kGenerators)
      DDC_INPUT_REQUIRE(g == gen || !body.isSublist(g), "sublist '" << path << "/" << g
                                                                    << "' does not apply: Generator is '"
                                                                    << gen << "'");
    DDC_INPUT_REQUIRE(body.isSublist("Element"), "sublist '" << path << "/Element' is required (Type, Material)");
    PL& elem = body.sublist("Element");
    DDC_INPUT_REQUIRE(elem.isParameter("Type"), "parameter '" << path << "/Element/Type' is required");
    const auto& entry = factory.entry(elem.get<std::string>("Type"), path + "/Element");
    DDC_INPUT_REQUIRE(!entry.contact, "'" << path << "/Element/Type' = '" << elem.get<std::string>("Type")
                                          << "' is a contact element (the contact component makes those for "
                                             "Contact/Pairs); a body needs one of "
                                          << quotedNames(factory.bodyNames(), "(none registered)"));
    // The mesh cell type of the element: the one of its dimension and node count.
    const auto& cells = elementCellTypes();
    const auto cellIt = std::find_if(cells.begin(), cells.end(), [&](CellType c) {
      return cellDimension(c) == entry.dim && numCellNodes(c) == entry.numNodes;
    });
    DDC_INPUT_REQUIRE(cellIt != cells.end(), "element type '" << elem.get<std::string>("Type") << "' of '" << path
                                                               << "' is " << entry.dim << "-D with " << entry.numNodes
                                                               << " nodes, which no mesh cell type has (bodies need "
                                                                  "Quad4, Quad9, Hex8, Hex20, Hex27, Tet4 or Tet10 "
                                                                  "cells)");
    const CellType cell = *cellIt;
    PL& gp = body.sublist(gen);
    if (gen == "Rectangle")
      generateRectangle(*mesh, name, cell, gp, path + "/Rectangle");
    else if (gen == "Annular Sector")
      generateAnnularSector(*mesh, name, cell, gp, path + "/Annular Sector");
    else if (gen == "Box")
      generateBox(*mesh, name, cell, gp, path + "/Box");
    else if (gen == "Cylindrical Shell Sector")
      generateCylindricalShellSector(*mesh, name, cell, gp, path + "/Cylindrical Shell Sector");
    else if (gen == "Sphere Octant")
      generateSphereOctant(*mesh, name, cell, gp, path + "/Sphere Octant");
    else if (gen == "Exodus")
      readExodusBody(*mesh, name, cell, gp, path + "/Exodus", baseDirectory);
    else
      readGmshBody(*mesh, name, cell, gp, path + "/Gmsh", baseDirectory);
    // Lengths far from 1 under- or overflow in the element arithmetic
    // (Jacobians are cubes of lengths in 3-D, stiffnesses divide by them):
    // a body's extent must lie in [1e-100, 1e100].
    const Body& b = mesh->body(mesh->numBodies() - 1);
    double lo[3] = {1e308, 1e308, 1e308}, hi[3] = {-1e308, -1e308, -1e308};
    for (int n = b.firstNode; n < b.firstNode + b.numNodes; ++n)
      for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], mesh->coord(n)[c]), hi[c] = std::max(hi[c], mesh->coord(n)[c]);
    double extent = 1e308, far = 0.0;  // the smallest extent over the axes
    for (int c = 0; c < mesh->dim(); ++c) {
      extent = std::min(extent, hi[c] - lo[c]);
      far = std::max({far, std::abs(lo[c]), std::abs(hi[c])});
    }
    DDC_INPUT_REQUIRE(b.numNodes == 0 || (extent >= kMinBodyExtent && far <= kMaxCoordinate),
                      "'" << path << "/" << gen << "': body '" << name << "' spans " << extent
                          << " along its thinnest axis, with coordinates up to " << far
                          << " in magnitude; its extent must lie in ["
                          << kMinBodyExtent << ", " << kMaxCoordinate << "] and its coordinates within "
                          << kMaxCoordinate << " (lengths this far from 1 under- or overflow in the element "
                             "arithmetic): choose other length units");
  }
  mesh->check();
  return mesh;
}

Analysis::Analysis(Teuchos::RCP<const Teuchos::Comm<int>> comm, Teuchos::ParameterList& params,
                   ElementFactory factory, const std::string& baseDirectory)
    : comm_(std::move(comm)), factory_(std::move(factory)) {
  // Contact elements live in the contact package; make sure they are known.
  if (!factory_.has(surfaceContactElementName(SurfaceContactRole::Conventional, CellType::Quad4)))
    registerSurfaceContactElements(factory_);
  const auto valid = getValidParameters(factory_);
  validateLevel(params, *valid, "");
  for (const char* s : {"Load Stepping", "Dynamics", "Step Control", "Newton", "Solver", "Partition", "Output"})
    validateLevel(params.sublist(s), valid->sublist(s), s);
  dynamic_ = params.sublist("Dynamics").get<std::string>("Integrator") != "None";
  DDC_INPUT_REQUIRE(params.isSublist("Mesh"), "sublist 'Mesh' is required");
  {
    const PL& nw = params.sublist("Newton");
    DDC_INPUT_REQUIRE(nw.get<double>("Residual Tolerance") > 0.0 || nw.get<double>("Absolute Residual Tolerance") > 0.0,
                      "'Newton/Residual Tolerance' and 'Newton/Absolute Residual Tolerance' are both 0: Newton would "
                      "need |r| = 0 exactly, which round-off never gives; set one of them > 0 (defaults 1e-8, 1e-10)");
    DDC_INPUT_REQUIRE(nw.get<double>("Energy Tolerance") > 0.0,
                      "'Newton/Energy Tolerance' is 0: Newton would need |du.r| = 0 exactly, which round-off never "
                      "gives; set it > 0 (default 1e-16)");
  }
  progressEnabled_ = params.sublist("Output").get<bool>("Progress");
  DDC_INPUT_REQUIRE(!params.sublist("Output").get<bool>("Contact Nodes") ||
                        (params.isSublist("Contact") && params.sublist("Contact").isSublist("Pairs") &&
                         params.sublist("Contact").sublist("Pairs").numParams() > 0),
                    "parameter 'Output/Contact Nodes' is true, but the deck has no contact pairs "
                    "(Contact/Pairs): there are no contact nodes to write");
  // Every rank reads the mesh and map files named in the parameters: a file
  // missing or different on some ranks must fail all ranks alike.
  requireSameFilesOnEveryRank(*comm_, namedInputFiles(params, baseDirectory));

  // Memory: what each rank may use, checked by the mesh generators before
  // they allocate and, once the mesh and partition are known, against the
  // estimate of the whole run (doc/user-guide.md, "Memory").
  const bool memoryCheck = params.sublist("Solver").get<bool>("Memory Check");
  const MemoryLimit memory = memoryCheck ? availableMemory(*comm_) : MemoryLimit();
  const std::string memoryHint =
      "refine less, run on more ranks or hosts, or set 'Solver/Memory Check' = false to run anyway";

  // Mesh and one element evaluator per body.
  auto mesh = buildMesh(params.sublist("Mesh"), factory_, baseDirectory, &memory, memoryHint);
  std::vector<std::shared_ptr<const Element>> elements;
  for (int b = 0; b < mesh->numBodies(); ++b) {
    const std::string path = "Mesh/Bodies/" + mesh->body(b).name + "/Element";
    elements.push_back(factory_.create(params.sublist("Mesh").sublist("Bodies").sublist(mesh->body(b).name).sublist("Element"), path));
  }
  // Nearly incompressible materials: the elements are displacement-only
  // (no mixed u-p formulation), so they lock: said at the start and with a
  // Newton failure, where it is the likely cause.
  for (int b = 0; b < mesh->numBodies(); ++b) {
    const PL& el = params.sublist("Mesh").sublist("Bodies").sublist(mesh->body(b).name).sublist("Element");
    if (!el.isSublist("Material") || !el.sublist("Material").isType<double>("Poisson's Ratio")) continue;
    const double nu = el.sublist("Material").get<double>("Poisson's Ratio");
    if (nu < kNearlyIncompressible) continue;
    std::ostringstream os;
    os.precision(12);
    os << (nearlyIncompressible_.empty() ? "" : "; ") << "body '" << mesh->body(b).name
       << "' is nearly incompressible ('Mesh/Bodies/" << mesh->body(b).name
       << "/Element/Material/Poisson's Ratio' = " << nu << ", lambda/mu = " << std::setprecision(3)
       << 2.0 * nu / (1.0 - 2.0 * nu)
       << "): the elements are displacement-only, with no mixed (u-p) formulation, so they lock: results too "
          "stiff and Newton slow to converge or stagnating; use a Poisson's ratio below "
       << kNearlyIncompressible;
    nearlyIncompressible_ += os.str();
  }
  // Reject inverted or degenerate elements before anything runs (every rank
  // holds the mesh, so every rank reaches the same verdict).
  for (int e = 0; e < mesh->numElements(); ++e) {
    const int nn = mesh->elementNumNodes(e), d = mesh->dim();
    Eigen::MatrixXd X(nn, d);
    for (int i = 0; i < nn; ++i)
      for (int c = 0; c < d; ++c) X(i, c) = mesh->coord(mesh->elementNodes(e)[i])[c];
    const double detJ = elements[mesh->elementBody(e)]->minReferenceJacobian(X);
    DDC_INPUT_REQUIRE(detJ > 0.0, "mesh: element " << e << " of body '" << mesh->body(mesh->elementBody(e)).name
                                                  << "' is inverted or degenerate (min det J = " << detJ << "); "
                                                  << (d == 2 ? "its nodes must run counter-clockwise"
                                                             : "its nodes must follow the Gmsh order with a "
                                                               "positive orientation")
                                                  << ", first node at (" << mesh->coordText(mesh->elementNodes(e)[0])
                                                  << ")");
  }

  auto bcs = BoundaryConditions::fromParameters(params.sublist("Boundary Conditions"), *mesh, "Boundary Conditions");
  auto contact = ContactOptions::fromParameters(params.sublist("Contact"), *mesh, "Contact");
  if (dynamic_ && params.sublist("Contact").get<std::string>("Initial Contact State") == "Automatic")
    contact.initialInContact = false;  // Previous Step: a time step changes the active set little
  // Every body that no contact pair joins to another body must be supported by its
  // prescribed displacements: both directions and at least two nodes (a
  // single pinned node leaves the rotation free). Otherwise the global
  // (and the FETI-DP coarse) matrix is singular, which MUMPS would factorise
  // without complaint.
  {
    // A pair between two surfaces of one body (self-contact) cannot hold it:
    // its forces are internal to the body.
    std::vector<char> inContact(mesh->numBodies(), 0);
    for (const auto& pr : contact.pairs) {
      const int slaveBody = mesh->bodyIndex(pr.slaveSet.substr(0, pr.slaveSet.find('/')));
      const int masterBody = mesh->bodyIndex(pr.masterSet.substr(0, pr.masterSet.find('/')));
      if (slaveBody != masterBody) inContact[slaveBody] = inContact[masterBody] = 1;
    }
    std::vector<std::set<int>> fixedNodes(mesh->numBodies());
    const int dim = mesh->dim();
    std::vector<std::array<bool, 3>> fixedDir(mesh->numBodies(), {false, false, false});
    for (const auto& d : bcs.displacements)
      for (int n : mesh->nodeSet(d.setName)) {
        int b = 0;
        while (!(n >= mesh->body(b).firstNode && n < mesh->body(b).firstNode + mesh->body(b).numNodes)) ++b;
        fixedNodes[b].insert(n);
        for (int c = 0; c < dim; ++c) fixedDir[b][c] = fixedDir[b][c] || d.fix[c];
      }
    const bool fetiStrategy = params.sublist("Solver").get<std::string>("Strategy") == "FETI-DP";
    // Two distinct nodes hold a 2-D body's rotation; a 3-D body needs three
    // not on one line (two leave the rotation about their line free).
    auto enoughNodes = [&](const std::set<int>& nodes) {
      if (dim == 2) return nodes.size() >= 2;
      const Eigen::Vector3d a(mesh->coord(*nodes.begin()).data());
      double far = 0.0, area = 0.0;
      Eigen::Vector3d b = a;
      for (int n : nodes) {
        const Eigen::Vector3d x(mesh->coord(n).data());
        if ((x - a).norm() > far) far = (x - a).norm(), b = x;
      }
      for (int n : nodes) area = std::max(area, (b - a).cross(Eigen::Vector3d(mesh->coord(n).data()) - a).norm());
      return nodes.size() >= 3 && area > 1e-12 * far * far;  // relative to the set's extent: not collinear
    };
    // In dynamics the mass holds every body (K + c M is nonsingular): a free
    // body is legal there.
    for (int b = 0; b < mesh->numBodies() && !dynamic_; ++b) {
      const bool supported =
          !fixedNodes[b].empty() && enoughNodes(fixedNodes[b]) && fixedDir[b][0] && fixedDir[b][1] && (dim == 2 || fixedDir[b][2]);
      // FETI-DP: contact rows are dual constraints; they cannot remove the
      // rigid modes of K~ (the coarse problem would be singular).
      DDC_INPUT_REQUIRE(supported || !inContact[b] || !fetiStrategy,
                        "body '" << mesh->body(b).name
                                 << "' is held only by contact: with Solver/Strategy = FETI-DP every body must be "
                                    "supported by its own prescribed displacements (Boundary Conditions: "
                                 << (dim == 2 ? "x and y, at least two nodes" : "x, y and z, at least three nodes not on one line")
                                 << "), because the contact rows are dual constraints and cannot "
                                    "fix the rigid-body modes of the subdomain problems; use Solver/Strategy = "
                                    "Monolithic, or prescribe displacements on the body");
      DDC_INPUT_REQUIRE(inContact[b] || supported,
                        "body '" << mesh->body(b).name
                                 << "' is not supported: its prescribed displacements (Boundary Conditions) must "
                                 << (dim == 2 ? "act in both x and y and on at least two nodes"
                                              : "act in x, y and z and on at least three nodes not on one line")
                                 << " to remove its rigid-body motion, and no contact pair joins it to another "
                                    "body");
    }
  }
  const PL& part = params.sublist("Partition");
  int nsub = part.get<int>("Number of Subdomains");
  if (nsub == 0) nsub = automaticSubdomainCount(*mesh, part, params.sublist("Solver").get<std::string>("Strategy"),
                                                comm_->getSize());
  Partition partition;
  const std::string method = part.get<std::string>("Method");
  auto requireCount = [&](int count) {
    const int given = part.get<int>("Number of Subdomains");
    DDC_INPUT_REQUIRE(given == 0 || given == count, "'Partition/Number of Subdomains' = "
                                                        << given << " contradicts Method = " << method << ", which gives "
                                                        << count << " subdomains (use 0 or " << count << ")");
  };
  if (method == "Box Grid") {
    partition = partitionBoxGrid(*mesh, part.get<int>("Box Grid X"), part.get<int>("Box Grid Y"),
                                 part.get<int>("Box Grid Z"));
    requireCount(partition.numSubdomains);
  } else if (method == "Element Map File") {
    std::string file = part.get<std::string>("Element Map File");
    DDC_INPUT_REQUIRE(!file.empty(), "parameter 'Partition/Element Map File' is required with Method = Element Map File");
    file = resolveDeckFile(file, baseDirectory);
    partition = partitionFromFile(*mesh, file);
    requireCount(partition.numSubdomains);
  } else if (method == "By Body") {
    partition = partitionByBody(*mesh);
    requireCount(partition.numSubdomains);
  } else {
    Activity activity("partitioning " + std::to_string(mesh->numElements()) + " elements into " +
                      std::to_string(nsub) + " subdomains (METIS)");
    partition = partitionMetis(*mesh, nsub);
  }
  DDC_INPUT_REQUIRE(partition.numSubdomains >= comm_->getSize(),
                    "'Partition/Number of Subdomains' (" << partition.numSubdomains << ") must be at least the number of MPI ranks ("
                                                          << comm_->getSize() << ")");
  memoryEstimate_ = estimateMemory(*mesh, partition, comm_->getSize(), params.sublist("Solver"));
  DDC_INPUT_REQUIRE(!memoryCheck || memoryEstimate_.total() <= memory.bytes,
                    "the run needs an estimated " << formatBytes(memoryEstimate_.total()) << " per rank ("
                                                  << memoryEstimate_.describe()
                                                  << "; doc/user-guide.md, 'Memory'), more than the "
                                                  << formatBytes(memory.bytes) << " available (" << memory.source
                                                  << "): " << memoryHint);


  strategy_ = makeSolutionStrategy(comm_, params.sublist("Solver"), contact);

  // The contact elements by role and facet type, from the factory (host
  // codes may replace them there).
  auto surfaceElements = [factory = factory_](SurfaceContactRole role, CellType facet) {
    Teuchos::ParameterList pl;
    const std::string type = surfaceContactElementName(role, facet);
    pl.set("Type", type);
    auto el = std::dynamic_pointer_cast<const SurfaceContactElement>(factory.create(pl, "Contact/Formulation"));
    DDC_INPUT_REQUIRE(el != nullptr, "element type '" << type << "' registered in the factory is not a surface "
                                                      "contact element");
    return el;
  };
  const std::string sizes = std::to_string(mesh->numNodes()) + " nodes, " + std::to_string(mesh->numElements()) +
                            " elements, " + std::to_string(partition.numSubdomains) + " subdomains; estimated " +
                            formatBytes(memoryEstimate_.total()) + " per rank";
  {
    Activity activity("building the model (" + sizes + ")");
    model_ = std::make_shared<Model>(comm_, mesh, std::move(elements), std::move(partition), std::move(bcs),
                                     std::move(contact), surfaceElements);
    u_ = model_->createVector();
  }
  if (dynamic_) setUpDynamics(params.sublist("Dynamics"));
  setUpStepControl(params);
  Activity activity("setting up the " + strategy_->name() + " solver (" + sizes + ")");
  strategy_->setUp(model_, [this](const std::string& line) { progress(line); });
  params_ = params;
}

Analysis::~Analysis() = default;

void Analysis::setUpStepControl(const Teuchos::ParameterList& params) {
  const PL& sc = params.sublist("Step Control");
  stepControl_ = StepControlSettings{};
  stepControl_.tolerance = sc.get<double>("Error Tolerance");
  stepControl_.corrections = sc.get<int>("Geometry Corrections");
  if (stepControl_.tolerance == 0.0) return;
  DDC_INPUT_REQUIRE(model_->decomposedContact(),
                    "'Step Control/Error Tolerance' = "
                        << stepControl_.tolerance
                        << " controls the frozen-geometry error of the decomposed contact element, and this run "
                           "has none (Contact/Formulation = Decomposed Node-To-Segment or Decomposed "
                           "Node-To-Surface, with a contact pair); set it to 0");
  const PL& ls = params.sublist(dynamic_ ? "Dynamics" : "Load Stepping");
  const double first = dynamic_ ? ls.get<double>("Time Step")
                                : ls.get<double>("Final Load Factor") / ls.get<int>("Number of Steps");
  const double finalValue = dynamic_ ? ls.get<double>("Final Time") : ls.get<double>("Final Load Factor");
  const char* firstName = dynamic_ ? "'Dynamics/Time Step'" : "'Load Stepping/Final Load Factor' / 'Number of Steps'";
  const double minSize = sc.get<double>("Minimum Step Size"), maxSize = sc.get<double>("Maximum Step Size");
  stepControl_.minSize = minSize > 0.0 ? minSize : std::ldexp(first, -ls.get<int>("Max Bisections"));
  stepControl_.maxSize = maxSize > 0.0 ? maxSize : first;
  stepControl_.first = std::clamp(first, stepControl_.minSize, stepControl_.maxSize);
  DDC_INPUT_REQUIRE(stepControl_.minSize <= stepControl_.maxSize,
                    "'Step Control/Minimum Step Size' = " << stepControl_.minSize
                                                          << " exceeds 'Step Control/Maximum Step Size' = "
                                                          << stepControl_.maxSize
                                                          << (maxSize > 0.0 ? "" : " (0: the first step)"));
  DDC_INPUT_REQUIRE(stepControl_.maxSize <= finalValue,
                    "'Step Control/Maximum Step Size' = " << stepControl_.maxSize << " exceeds the whole analysis ("
                                                          << (dynamic_ ? "Dynamics/Final Time" : "Load Stepping/Final Load Factor")
                                                          << " = " << finalValue << ")");
  DDC_INPUT_REQUIRE(minSize == 0.0 || minSize <= first,
                    "'Step Control/Minimum Step Size' = " << minSize << " exceeds the first step " << first << " ("
                                                          << firstName << ")");
}

void Analysis::setUpDynamics(Teuchos::ParameterList& dyn) {
  const Mesh& mesh = model_->mesh();
  // Every body needs inertia.
  for (const auto& name : model_->bodiesWithoutMass())
    DDC_THROW(InputError, "'Dynamics/Integrator' = " << dyn.get<std::string>("Integrator") << " needs the mass of "
                          "every body, but body '" << name << "' has none: set 'Mesh/Bodies/" << name
                          << "/Element/Material/Density' > 0");
  // A whole number of time steps.
  const double T = dyn.get<double>("Final Time"), h = dyn.get<double>("Time Step");
  const double steps = std::round(T / h);
  DDC_INPUT_REQUIRE(steps >= 1 && std::abs(steps * h - T) <= 1e-9 * T && steps < 1e9,
                    "'Dynamics/Final Time' = " << T << " is not a whole number of 'Dynamics/Time Step' = " << h
                                               << " (" << T / h << " steps)");
  const std::string mass = dyn.get<std::string>("Mass Matrix");
  const MassLumping lumping = mass == "HRZ"       ? MassLumping::HRZ
                              : mass == "Row-Sum" ? MassLumping::RowSum
                                                  : MassLumping::Consistent;
  if (lumping == MassLumping::RowSum)
    for (int b = 0; b < mesh.numBodies(); ++b) {
      const CellType t = mesh.elementType(mesh.body(b).firstElement);
      DDC_INPUT_REQUIRE(t != CellType::Hex20 && t != CellType::Tet10,
                        "'Dynamics/Mass Matrix' = Row-Sum gives zero or negative masses at the corners of "
                            << cellTypeName(t) << " elements (body '" << mesh.body(b).name
                            << "'); use HRZ or Consistent");
    }
  model_->setMassLumping(lumping);
  try {
    model_->setContactSurfaceMassRedistributed(dyn.get<std::string>("Contact Surface Mass") == "Redistributed");
  } catch (const InputError& e) {
    throw InputError(std::string("'Dynamics/Contact Surface Mass' = Redistributed: ") + e.what() +
                     " (or set it to Kept)");
  }
  const std::string scheme = dyn.get<std::string>("Integrator");
  integrator_ = std::make_unique<NewmarkIntegrator>(
      scheme == "HHT-alpha"           ? NewmarkParameters::hht(dyn.get<double>("HHT Alpha"), "Dynamics")
      : scheme == "Generalized-alpha" ? NewmarkParameters::generalisedAlpha(dyn.get<double>("Spectral Radius"), "Dynamics")
                                      : NewmarkParameters::newmark(dyn.get<double>("Newmark Beta"),
                                                                   dyn.get<double>("Newmark Gamma"), "Dynamics"));
  integrator_->setRayleighDamping(dyn.get<double>("Rayleigh Alpha"), dyn.get<double>("Rayleigh Beta"));
  // Initial velocities by body or node set; prescribed DOFs start at rest.
  initialVelocity_ = model_->createVector();
  forEachCondition(dyn, "Initial Velocity", "Set, Velocity X/Y/Z", [&](PL& c, const std::string& where) {
    const std::string set = c.get<std::string>("Set");
    std::vector<int> nodes;
    try {
      if (set.find('/') == std::string::npos) {
        const Body& body = mesh.body(mesh.bodyIndex(set));
        for (int n = 0; n < body.numNodes; ++n) nodes.push_back(body.firstNode + n);
      } else {
        nodes = mesh.nodeSet(set);
      }
    } catch (const InputError& e) {
      throw InputError("'" + where + "/Set' = '" + set + "' is neither a body nor a qualified node set "
                       "'Body/set': " + e.what());
    }
    DDC_INPUT_REQUIRE(mesh.dim() == 3 || c.get<double>("Velocity Z") == 0.0,
                      "'" << where << "/Velocity Z' is set but the model is 2-D");
    const double v[3] = {c.get<double>("Velocity X"), c.get<double>("Velocity Y"), c.get<double>("Velocity Z")};
    for (int n : nodes)
      for (int k = 0; k < mesh.dim(); ++k) {
        const GO g = model_->dof(n, k);
        if (initialVelocity_->getMap()->isNodeGlobalElement(g) && !model_->isConstrained(g))
          initialVelocity_->replaceGlobalValue(g, v[k]);
      }
  });
  // Gravity by body: the force M g with the run's mass matrices.
  auto g = model_->createVector();
  bool anyGravity = false;
  forEachCondition(dyn, "Gravity", "Set, Acceleration X/Y/Z", [&](PL& c, const std::string& where) {
    const std::string set = c.get<std::string>("Set");
    int b = -1;
    try {
      b = mesh.bodyIndex(set);
    } catch (const InputError& e) {
      throw InputError("'" + where + "/Set' = '" + set + "' is not a body: " + e.what());
    }
    DDC_INPUT_REQUIRE(mesh.dim() == 3 || c.get<double>("Acceleration Z") == 0.0,
                      "'" << where << "/Acceleration Z' is set but the model is 2-D");
    const double a[3] = {c.get<double>("Acceleration X"), c.get<double>("Acceleration Y"),
                         c.get<double>("Acceleration Z")};
    const Body& body = mesh.body(b);
    for (int n = body.firstNode; n < body.firstNode + body.numNodes; ++n)
      for (int k = 0; k < mesh.dim(); ++k) {
        const GO gid = model_->dof(n, k);
        if (g->getMap()->isNodeGlobalElement(gid)) g->replaceGlobalValue(gid, a[k]);
      }
    anyGravity = anyGravity || a[0] != 0.0 || a[1] != 0.0 || a[2] != 0.0;
  });
  if (anyGravity) {
    auto f = model_->createVector();
    model_->applyMass(*g, *f);
    model_->setBodyForce(*f);
  }
  acceleration_ = model_->createVector();
  velocity_ = model_->createVector();
  inertia_ = Inertia{};
  inertia_.acceleration = acceleration_.get();
  strategy_->setInertia(&inertia_);
}

void Analysis::progress(const std::string& line) const {
  if (comm_->getRank() == 0 && progressEnabled_) {
    std::cout << line << std::endl;
  }
}

bool Analysis::solveIncrement(double lambda0, double lambda1, StepRecord& rec) {
  const PL& nw = params_.sublist("Newton");
  const int maxIt = nw.get<int>("Max Iterations");
  const double rtol = nw.get<double>("Residual Tolerance");
  const double atol = nw.get<double>("Absolute Residual Tolerance");
  const double etol = nw.get<double>("Energy Tolerance");
  const bool printIt = nw.get<bool>("Print Iterations");
  // Inexact Newton (doc/user-guide.md "Solution method"): only iterative solves have
  // a tolerance to set.
  const double linTol = strategy_->linearTolerance();
  const bool forcing = linTol > 0.0 && nw.get<std::string>("Forcing Term") == "Eisenstat-Walker";
  const double etaMax = std::max(nw.get<double>("Maximum Forcing Term"), linTol);
  const double etaFloor = nw.get<double>("Forcing Term Floor");
  // eta: the wanted reduction of the Newton residual; solveTol: the
  // tolerance asked of the solver for it (eta / mismatch).
  double eta = linTol, solveTol = linTol, mismatch = 1.0, rPrev = 0.0;
  const bool contact = model_->hasContact();
  const bool conventional = contact && !model_->decomposedContact();

  auto u = model_->createVector();
  u->assign(*u_);
  auto dp = model_->createVector();
  model_->prescribedIncrement(lambda0, lambda1, *dp);
  auto r = model_->createVector();
  auto du = model_->createVector();
  double r0 = 0.0, e0 = 0.0;
  double lastEnergy = 0.0;  // |du.r| of the last iteration (for the failure message)
  rec.residualHistory.clear();
  rec.failure.clear();
  // Active sets seen after each change in this increment: a repeat is cycling.
  std::vector<std::vector<int>> seen;
  // The signature is the active set and the pairing: a slave flipping
  // between two segments cycles as surely as one flipping its state.
  auto activeSet = [&] {
    std::vector<int> a;
    for (const auto& sl : model_->contactSlots()) a.insert(a.end(), {int(sl.active), sl.master[0], sl.master[1], sl.segment});
    return a;
  };
  if (contact) seen.push_back(activeSet());
  // Conventional element, Contact/Pairing Cycles = Freeze: once the pairing
  // cycles, it is kept for the rest of the increment (doc/contact.md).
  bool pairingFrozen = false;
  strategy_->beginIncrement();
  for (int it = 0; it < maxIt; ++it) {
    const auto start = std::chrono::steady_clock::now();
    // One element pass: the residual and what the strategy solves with (the
    // global tangent, or the subdomain stiffness matrices).
    AssemblyResult assembled;
    if (integrator_) {
      // Dynamics: a(u) and the factor of M in the tangent at this iterate.
      integrator_->acceleration(*u, *acceleration_);
      if (integrator_->damped()) integrator_->velocity(*u, *velocity_);
      inertia_ = integrator_->inertia(*acceleration_, integrator_->damped() ? velocity_.get() : nullptr);
    }
    try {
      assembled = strategy_->assemble(*u, lambda1, *r, it == 0 ? dp.get() : nullptr);
    } catch (const InadmissibleDeformation& e) {
      rec.failure = std::string("Newton iteration ") + std::to_string(it) + ": " + e.what();
      progress("    " + rec.failure);
      return false;
    }
    // A rigid motion nothing restrains makes the tangent singular; a direct
    // solver may factorise it anyway and return a drift along it (the same
    // on every rank: the check ends with a reduction).
    if (!assembled.freeMotions.empty()) {
      std::ostringstream os;
      os << "the problem is singular in step " << rec.step << " (load factor " << lambda0 << " -> " << lambda1
         << "), Newton iteration " << it << ": no prescribed displacement and no active contact restrains "
         << assembled.freeMotions
         << ". Prescribe displacements (Boundary Conditions) that hold these motions; frictionless contact "
            "holds a body only along its contact normals (doc/user-guide.md, \"A singular problem\")";
      throw SolverError(os.str());
    }
    timing_.assembly += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double rnorm = r->norm2();
    rec.residualHistory.push_back(rnorm);
    if (!std::isfinite(rnorm)) {
      const std::string where = model_->describeNonFinite(*r);
      rec.failure = "Newton iteration " + std::to_string(it) + ": non-finite residual" +
                    (where.empty() ? std::string() : ": " + where);
      progress("    " + rec.failure);
      return false;
    }
    if (it == 0) r0 = rnorm;
    const bool residualOk = it > 0 && rnorm <= std::max(rtol * r0, atol);

    if (forcing) {
      if (it > 0) {
        // How much less the last solve reduced the Newton residual than its
        // tolerance promised (FETI-DP's tolerance is on the dual residual,
        // an interface jump, not on the force residual); nonlinearity and
        // contact changes count too, which errs towards tighter solves.
        mismatch = std::max(1.0, rnorm / (solveTol * rPrev));
        if (rnorm > rPrev) {
          eta = linTol;  // the residual grew: solve tightly again
        } else {
          // Eisenstat & Walker (1996), choice 2 (gamma 0.9, alpha 2), with
          // their safeguard against a sudden tightening; not with contact,
          // whose active-set decisions need accurate multipliers.
          const double safeguard = 0.9 * eta * eta;
          eta = contact ? 0.0 : 0.9 * (rnorm / rPrev) * (rnorm / rPrev);
          if (!contact && safeguard > 0.1) eta = std::max(eta, safeguard);
          // No need to go below a fraction of what Newton asks for.
          if (rnorm > 0.0) eta = std::max(eta, etaFloor * std::max(rtol * r0, atol) / rnorm);
          eta = std::min(eta, etaMax);
        }
      }
      solveTol = std::min(std::max(eta / mismatch, linTol), etaMax);
      strategy_->setSolveTolerance(solveTol);
      rPrev = rnorm;
    }
    r->scale(-1.0);
    const StrategySolveInfo info = strategy_->solve(*r, *du);
    timing_.linearSetup += info.setupSeconds;
    timing_.linearSolve += info.solveSeconds;
    rec.dualIterations += info.iterations;
    const int solveIterations = info.iterations;
    for (int i = 0; i < 6; ++i) timing_.feti[i] += info.feti[i];
    ++timing_.linearSolves;
    // |du·r|: the energy norm of the correction.
    const double energy = std::abs(du->dot(*r));
    if (it == 0) {
      du->update(1.0, *dp, 1.0);  // constrained rows solved to 0; impose the increment
      e0 = energy;
    }
    u->update(1.0, *du, 1.0);
    rec.newtonIterations = it + 1;

    // Contact: follow the current configuration (conventional NTS), then
    // check the contact state on the multipliers (release in tension,
    // activate on penetration).
    bool pairingChanged = false;
    std::vector<int> changed, repaired;
    if (contact) {
      if (conventional && !pairingFrozen) pairingChanged = model_->updatePairing(*u, false, false, &repaired);
      changed = model_->updateActiveSet(*u);
    }
    if (printIt && comm_->getRank() == 0) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "    iter %2d  |r| = %.3e  |du.r| = %.3e", it, rnorm, energy);
      std::string line = buf;
      if (solveIterations > 0) line += "  dual/Krylov " + std::to_string(solveIterations);
      if (info.conditionEstimate > 0.0) {
        char kappa[40];
        std::snprintf(kappa, sizeof kappa, " (condition ~%.3g)", info.conditionEstimate);
        line += kappa;
      }
      if (forcing) {
        char tol[40];
        std::snprintf(tol, sizeof tol, " (tol %.1e)", solveTol);
        line += tol;
      }
      if (contact)
        line += "  active " + std::to_string(model_->contactSummary().active) + " (" +
                std::to_string(changed.size()) + " changed" + (pairingChanged ? ", new pairing" : "") + ")";
      std::cout << line << std::endl;
    }
    if (!std::isfinite(energy)) {
      const std::string where = model_->describeNonFinite(*du);
      rec.failure = "Newton iteration " + std::to_string(it) + ": non-finite correction" +
                    (where.empty() ? std::string() : ": " + where);
      progress("    " + rec.failure);
      return false;
    }
    if (!changed.empty() || pairingChanged) {
      auto a = activeSet();
      const bool repeated = std::find(seen.begin(), seen.end(), a) != seen.end();
      if (repeated && pairingChanged && model_->contactOptions().freezeCyclingPairing) {
        pairingFrozen = true;
        progress("    Newton iteration " + std::to_string(it) + ": the pairing cycles (" +
                 std::to_string(repaired.size()) + " slave nodes changed master facet); kept for the rest of "
                 "this increment (Contact/Pairing Cycles = Freeze)");
        seen.push_back(std::move(a));
        continue;
      }
      if (repeated) {
        std::ostringstream os;
        os << "the contact active set cycles (a set seen before in this increment returned)";
        auto list = [&](const char* what, const std::vector<int>& slots) {
          if (slots.empty()) return;
          os << "; " << what << ":";
          for (size_t i = 0; i < slots.size() && i < 10; ++i) os << "\n      " << model_->describeSlot(slots[i]);
          if (slots.size() > 10) os << "\n      ... and " << slots.size() - 10 << " more";
        };
        list("pairs changing state", changed);
        list("slave nodes changing master segment", repaired);
        rec.failure = os.str();
        progress("    " + rec.failure);
        return false;
      }
      seen.push_back(std::move(a));
    }
    lastEnergy = energy;
    if (residualOk && energy <= etol * e0 && changed.empty() && !pairingChanged) {
      u_->assign(*u);
      return true;
    }
  }
  rec.failure = "no convergence in " + std::to_string(maxIt) + " iterations (Newton/Max Iterations)" +
                unmetCriterion(rec.residualHistory, rtol, atol, lastEnergy, etol, e0, lambda1 - lambda0);
  return false;
}

std::string Analysis::unmetCriterion(const std::vector<double>& residuals, double rtol, double atol, double energy,
                                     double etol, double e0, double increment) const {
  if (residuals.size() < 2) return "";
  const double r0 = residuals.front(), r = residuals.back();
  const double target = std::max(rtol * r0, atol);
  std::ostringstream os;
  os.precision(3);
  if (r > target)
    os << ": |r| = " << r << " > max(Residual Tolerance x |r_0|, Absolute Residual Tolerance) = " << target;
  else if (energy > etol * e0)
    os << ": |r| met its tolerance, but |du.r| = " << energy << " > Energy Tolerance x |du_0.r_0| = " << etol
       << " x " << e0 << " = " << etol * e0;
  else
    return "";  // the contact state kept changing (reported where it does)
  // Stagnation: the last kStagnant residuals no lower than a tenth of the
  // lowest before them. Then more iterations do not help; the tolerance is
  // below what the arithmetic of this increment resolves.
  constexpr size_t kStagnant = 5;
  if (residuals.size() >= 2 * kStagnant) {
    const auto tail = residuals.end() - kStagnant;
    const double before = *std::min_element(residuals.begin(), tail);
    const double recent = *std::min_element(tail, residuals.end());
    if (recent >= 0.1 * before)
      os << "; the residual stagnates around " << recent << " (the first was " << r0
         << "), so more iterations do not help: either the tolerance is below the round-off of this increment ("
         << (dynamic_ ? "time step " : "load factor increment ") << increment << "; "
         << (dynamic_ ? "" : "fewer 'Load Stepping/Number of Steps' or ")
         << "a larger 'Newton/Absolute Residual Tolerance' / 'Newton/Energy Tolerance' help then) or the tangent "
            "does not fit the residual";
  }
  return os.str();
}

double Analysis::externalWorkIncrement(const Vector& fint0, const Vector& u0, double lambda0, const Vector& fint1,
                                       const Vector& u1, double lambda1) const {
  // Trapezoidal rule in the load factor: reactions at prescribed DOFs (the
  // force there: RunState::reaction) and applied tractions and body forces,
  // times the displacement step.
  const auto& map = *model_->ownedMap();
  const GO first = map.getMinGlobalIndex();
  auto f0 = fint0.getData(), f1 = fint1.getData(), a = u0.getData(), b = u1.getData();
  auto fe = model_->externalForce().getData();
  Teuchos::ArrayRCP<const double> fb;  // the constant body force, if any
  if (model_->bodyForce()) fb = model_->bodyForce()->getData();
  double w = 0.0;
  for (size_t l = 0; l < map.getNodeNumElements(); ++l) {
    const double step = b[l] - a[l];
    if (model_->isConstrained(first + l))
      w += 0.5 * (f0[l] + f1[l]) * step;
    else
      w += (0.5 * (lambda0 + lambda1) * fe[l] + (fb.is_null() ? 0.0 : fb[l])) * step;
  }
  double sum = 0.0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, w, Teuchos::outArg(sum));
  return sum;
}

void Analysis::writeContactNodes(const std::string& path, const std::vector<ContactSlot>& slots) const {
  std::string error;
  if (comm_->getRank() == 0) {
    std::ostringstream os;
    os << "pair,node,x,y,z,gap,multiplier,tributary_area,pressure,active\n";
    os.precision(17);
    for (const auto& s : slots) {
      const auto& X = model_->mesh().coord(s.slaveNode);
      os << s.pair << ',' << s.slaveNode << ',' << X[0] << ',' << X[1] << ',' << (model_->mesh().dim() == 3 ? X[2] : 0.0)
         << ',' << (s.paired() ? s.gap : 0.0) << ',' << (s.active ? s.state.multiplier : 0.0) << ','
         << s.tributaryLength << ',' << s.pressure() << ',' << (s.active ? 1 : 0) << '\n';
    }
    try {
      writeFileAtomically(path, os.str());
    } catch (const OutputError& e) {
      error = e.what();
    }
  }
  error = firstErrorOnAnyRank(*comm_, error);
  if (!error.empty()) throw OutputError(error);
}

namespace {

/// The history rows as numbers, for a checkpoint: the fields of each
/// StepRecord, then its residual history (count, values). Every number
/// round-trips exactly (integers are far below 2^53).
std::vector<double> packHistory(const std::vector<StepRecord>& history) {
  std::vector<double> out;
  for (const StepRecord& r : history) {
    out.insert(out.end(), {double(r.step), r.loadFactor, r.strainEnergy, double(r.newtonIterations),
                           double(r.dualIterations), double(r.bisections), r.wallSeconds, r.externalWork,
                           double(r.activeContacts), r.contactForce[0], r.contactForce[1], r.contactForce[2],
                           double(r.contactExchanges), double(r.contactBytes), r.kineticEnergy, r.stepSize,
                           double(r.rejections), double(r.corrections), r.geometryError,
                           double(r.residualHistory.size())});
    out.insert(out.end(), r.residualHistory.begin(), r.residualHistory.end());
  }
  return out;
}

/// Fields of a packed StepRecord before its residual history.
constexpr size_t kPackedRecord = 20;

std::vector<StepRecord> unpackHistory(const std::vector<double>& packed, const std::string& file) {
  std::vector<StepRecord> history;
  size_t i = 0;
  while (i < packed.size()) {
    DDC_INPUT_REQUIRE(i + kPackedRecord <= packed.size(), "checkpoint '" << file << "': history row "
                                                                         << history.size() + 1 << " is cut short");
    const double* p = packed.data() + i;
    StepRecord r;
    r.step = int(p[0]);
    r.loadFactor = p[1];
    r.strainEnergy = p[2];
    r.newtonIterations = int(p[3]);
    r.dualIterations = int(p[4]);
    r.bisections = int(p[5]);
    r.wallSeconds = p[6];
    r.externalWork = p[7];
    r.activeContacts = int(p[8]);
    r.contactForce[0] = p[9], r.contactForce[1] = p[10], r.contactForce[2] = p[11];
    r.contactExchanges = long(p[12]);
    r.contactBytes = long(p[13]);
    r.kineticEnergy = p[14];
    r.stepSize = p[15];
    r.rejections = int(p[16]);
    r.corrections = int(p[17]);
    r.geometryError = p[18];
    const size_t n = size_t(p[19]);
    i += kPackedRecord;
    DDC_INPUT_REQUIRE(n <= packed.size() - i, "checkpoint '" << file << "': history row " << history.size() + 1
                                                              << " is cut short");
    r.residualHistory.assign(packed.begin() + long(i), packed.begin() + long(i + n));
    i += n;
    history.push_back(std::move(r));
  }
  return history;
}

/// "SIGTERM", "SIGINT", "SIGUSR1", or "signal N".
std::string signalName(int signal) {
  if (signal == SIGTERM) return "SIGTERM";
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGUSR1) return "SIGUSR1";
  return "signal " + std::to_string(signal);
}

/// The same entries as `v` (on model.ownedMap()) on a map of the
/// partition-free DOF ids (Model::partitionFreeDof()), in the same local
/// order: a checkpoint's vectors read back on any number of ranks.
Teuchos::RCP<Vector> partitionFreeVector(const Model& model, const Vector& v) {
  const Map& owned = *model.ownedMap();
  std::vector<GO> ids(owned.getNodeNumElements());
  for (size_t i = 0; i < ids.size(); ++i) ids[i] = model.partitionFreeDof(owned.getGlobalElement(LO(i)));
  const Teuchos::ArrayView<const GO> view(ids.data(), ids.size());
  auto map = Teuchos::rcp(new Map(owned.getGlobalNumElements(), view, 0, owned.getComm()));
  auto out = Teuchos::rcp(new Vector(map));
  auto src = v.getData();
  auto dst = out->getDataNonConst();
  for (size_t i = 0; i < ids.size(); ++i) dst[i] = src[i];
  return out;
}

/// The checkpoint's record of the run: its layout version, the ranks that
/// wrote it, the output counter and the external work.
constexpr double kCheckpointLayout = 1.0;

}  // namespace

void Analysis::setRestart(RestartSource source) {
  DDC_INPUT_REQUIRE(source.checkpoint, "setRestart: no checkpoint");
  const CheckpointReader& c = *source.checkpoint;
  const auto saved = Teuchos::getParametersFromXmlString(c.bytes("parameters"));
  checkRestartParameters(*saved, params_, c.path());
  restart_ = std::make_unique<RestartSource>(std::move(source));
}

void Analysis::writeCheckpoint(const std::string& path, const RunState& st, const std::vector<double>& controllerState,
                               const std::vector<std::pair<int, double>>& vtkSteps) const {
  CheckpointWriter w(comm_);
  std::ostringstream xml;
  Teuchos::writeParameterListToXmlOStream(params_, xml);
  w.putBytes("parameters", xml.str());
  w.putDoubles("run", {kCheckpointLayout, double(comm_->getSize()), double(st.outputCount), st.externalWork});
  w.putDoubles("controller", controllerState);
  w.putDoubles("history", packHistory(history_));
  std::vector<double> vtk;
  for (const auto& [step, time] : vtkSteps) vtk.insert(vtk.end(), {double(step), time});
  w.putDoubles("vtk steps", vtk);
  auto put = [&](const std::string& name, const Vector& v) { w.putVector(name, *partitionFreeVector(*model_, v)); };
  put("displacement", *u_);
  put("internal force", *st.fint);
  put("reaction", *st.reaction);
  if (integrator_) {
    put("velocity", integrator_->velocity());
    put("acceleration", integrator_->accelerationNow());
  }
  if (model_->hasContact()) {
    w.putDoubles("contact slots", packSlots(model_->contactSlots()));
    w.putDoubles("converged contact slots", packSlots(st.convergedSlots));
    const auto paired = model_->contact()->pairedRecord();
    w.putBytes("paired contact pairs", std::string(paired.begin(), paired.end()));
  }
  w.write(path);
}

std::vector<std::pair<int, double>> Analysis::restoreCheckpoint(RunState& st, StepController& steps) {
  const CheckpointReader& c = *restart_->checkpoint;
  const std::string& file = c.path();
  const auto run = c.doubles("run");
  DDC_INPUT_REQUIRE(run.size() == 4 && run[0] == kCheckpointLayout,
                    "checkpoint '" << file << "': written by another version of DDContact (section 'run')");
  st.outputCount = int(run[2]);
  st.externalWork = run[3];
  history_ = unpackHistory(c.doubles("history"), file);
  DDC_INPUT_REQUIRE(!history_.empty(), "checkpoint '" << file << "' holds no converged step");
  DDC_INPUT_REQUIRE(steps.restoreState(c.doubles("controller"), int(history_.size())),
                    "checkpoint '" << file
                                   << "': its step controller cannot be restored (a host's own controller "
                                      "(Analysis::setStepController()) saves none)");
  // Read on this model's partition-free ids, kept in the owned map's order.
  auto get = [&](const std::string& name, Vector& v) {
    auto tmp = partitionFreeVector(*model_, v);
    c.vector(name, *tmp);
    auto src = tmp->getData();
    auto dst = v.getDataNonConst();
    for (size_t i = 0; i < v.getLocalLength(); ++i) dst[i] = src[i];
  };
  get("displacement", *u_);
  get("internal force", *st.fint);
  get("reaction", *st.reaction);
  st.reactionPrev->assign(*st.reaction);
  st.uPrev->assign(*u_);
  if (integrator_) {
    DDC_INPUT_REQUIRE(c.has("velocity") && c.has("acceleration"),
                      "checkpoint '" << file << "' is of a quasi-static run; this one is dynamic");
    auto v = model_->createVector(), a = model_->createVector();
    get("velocity", *v);
    get("acceleration", *a);
    integrator_->restoreState(*u_, *v, *a);
  }
  if (model_->hasContact()) {
    auto slots = unpackSlots(c.doubles("contact slots"));
    const auto& now = model_->contactSlots();
    bool same = slots.size() == now.size();
    for (size_t k = 0; same && k < slots.size(); ++k)
      same = slots[k].pair == now[k].pair && slots[k].slaveNode == now[k].slaveNode;
    DDC_INPUT_REQUIRE(same, "checkpoint '" << file << "': its contact slave nodes are not this model's");
    model_->restoreContactState(slots);
    st.convergedSlots = unpackSlots(c.doubles("converged contact slots"));
    const std::string& paired = c.bytes("paired contact pairs");
    DDC_INPUT_REQUIRE(paired.size() == model_->contact()->pairedRecord().size(),
                      "checkpoint '" << file << "': its contact pairs are not this model's");
    model_->addPairedRecord(std::vector<char>(paired.begin(), paired.end()));
  }
  const auto vtk = c.doubles("vtk steps");
  std::vector<std::pair<int, double>> series;
  for (size_t i = 0; i + 1 < vtk.size(); i += 2) series.emplace_back(int(vtk[i]), vtk[i + 1]);
  return series;
}

void Analysis::run(const std::string& outputDirectory) {
  if (outputDirectory.empty()) {
    runSteps(nullptr);
    return;
  }
  // A restart continuing in the directory of the unfinished run it
  // continues keeps that run's staging directory (its files are read).
  RunDescription description;
  if (restart_ && restart_->unfinished && OutputDirectory::normalisedPath(outputDirectory) == restart_->finalPath)
    description.resumeWith = kCheckpointFileName;
  OutputDirectory dir(comm_, outputDirectory, description);
  for (const auto& note : dir.recoveryNotes()) progress("output: " + note);
  run(dir);
}

void Analysis::run(OutputDirectory& dir) {
  runSteps(&dir);
}

void Analysis::runSteps(OutputDirectory* dir) {
  const auto t0 = std::chrono::steady_clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  // Quasi-static: load factors from Load Stepping. Dynamics: the load
  // factor is the time, in steps of Dynamics/Time Step.
  const PL& ls = params_.sublist(dynamic_ ? "Dynamics" : "Load Stepping");
  const double finalLambda = dynamic_ ? ls.get<double>("Final Time") : ls.get<double>("Final Load Factor");
  const int nsteps = dynamic_ ? static_cast<int>(std::round(finalLambda / ls.get<double>("Time Step")))
                              : ls.get<int>("Number of Steps");
  const int maxBisect = ls.get<int>("Max Bisections");
  const char* stepping = dynamic_ ? "Dynamics" : "Load Stepping";
  const char* factorName = dynamic_ ? "time" : "load factor";
  const PL& out = params_.sublist("Output");
  const bool contact = model_->hasContact();
  const bool decomposed = model_->decomposedContact();
  // Checkpoints (Output/Checkpoint Interval) need a directory to go to.
  const int checkpointInterval = dir ? out.get<int>("Checkpoint Interval") : 0;
  const std::string checkpointPath = checkpointInterval > 0 ? dir->path() + "/" + kCheckpointFileName : "";
  // A restart continuing in the staging directory of the run it continues
  // (RunDescription::resumeWith): that run's results.e is moved aside
  // before this run's is created, copied from and removed (a restart that
  // failed before that finds it aside).
  std::string exodusSource;
  bool exodusAside = false;
  if (restart_ && dir && out.get<bool>("Exodus")) {
    exodusSource = restart_->directory + "/results.e";
    std::string error;
    std::error_code ec;
    if (comm_->getRank() == 0 && std::filesystem::equivalent(restart_->directory, dir->path(), ec)) {
      const std::string aside = dir->path() + "/results.e.before-restart";
      if (!std::filesystem::exists(aside, ec) && std::filesystem::exists(exodusSource, ec))
        std::filesystem::rename(exodusSource, aside, ec);
      if (ec) error = "cannot move '" + exodusSource + "' aside for the restart: " + ec.message();
      exodusSource = aside;
      exodusAside = true;
    }
    error = firstErrorOnAnyRank(*comm_, error);
    if (!error.empty()) throw OutputError(error);
    exodusSource = broadcastStrings(*comm_, {exodusSource}).front();
  }

  std::unique_ptr<HistoryWriter> hist;
  std::unique_ptr<VtkWriter> vtk;
  std::unique_ptr<ExodusWriter> exodus;
  if (dir) {
    DDC_INPUT_REQUIRE(!dir->committed(), "output directory '" << dir->finalPath()
                                                              << "' was committed already: one run per OutputDirectory");
    auto columns = HistoryWriter::standardColumns();
    columns.insert(columns.end(), {"external_work", "contact_bytes", "bisections", "contact_force_z"});
    if (dynamic_) columns.insert(columns.end(), {"time", "kinetic_energy", "total_energy"});
    if (decomposed) columns.insert(columns.end(), {"step_size", "rejected_steps", "geometry_corrections", "geometry_error"});
    hist = std::make_unique<HistoryWriter>(comm_, dir->path() + "/history.csv", columns);
    // The validated parameters, defaults included; written with every step
    // checked (a full disk must not leave an empty file behind).
    std::string error;
    if (comm_->getRank() == 0) {
      try {
        std::ostringstream xml;
        Teuchos::writeParameterListToXmlOStream(params_, xml);
        writeFileAtomically(dir->path() + "/parameters.xml", xml.str());
      } catch (const OutputError& e) {
        error = e.what();
      }
    }
    error = firstErrorOnAnyRank(*comm_, error);
    if (!error.empty()) throw OutputError(error);
    if (out.get<bool>("VTK")) vtk = std::make_unique<VtkWriter>(comm_, dir->path(), "solution.pvd");
    if (out.get<bool>("Exodus")) {
      std::vector<std::string> globals = {factorName == std::string("time") ? "time" : "load_factor", "strain_energy",
                                          "external_work", "active_contacts", "contact_force_x", "contact_force_y"};
      if (model_->mesh().dim() == 3) globals.push_back("contact_force_z");
      if (dynamic_) globals.push_back("kinetic_energy");
      exodus = std::make_unique<ExodusWriter>(comm_, dir->path() + "/results.e", model_->mesh(),
                                              exodusVariables(*model_, dynamic_, globals));
    }
  }
  // contact_nodes.csv holds the contact state of the last converged step
  // (RunState::convergedSlots, copied before the step-end re-pairing).
  const bool contactNodes = dir && contact && out.get<bool>("Contact Nodes");
  auto writeVtk = [&](int step, double lambda) {
    if (!vtk) return;
    if (integrator_)
      writeVtkStep(*vtk, *model_, *u_, step, lambda, &integrator_->velocity(), &integrator_->accelerationNow());
    else
      writeVtkStep(*vtk, *model_, *u_, step, lambda);
  };
  history_.clear();
  u_->putScalar(0.0);
  // The initial acceleration balances the body force (u = 0 and every
  // load factor-scaled load 0 at t = 0).
  if (integrator_) integrator_->initialise(*model_, *u_, *initialVelocity_, model_->bodyForce());

  // The state the steps carry forward (one object: what a restart saves).
  RunState st;
  st.reactionPrev = model_->createVector();
  st.reaction = model_->createVector();
  st.uPrev = model_->createVector();
  st.fint = model_->createVector();
  if (integrator_) integrator_->inertiaForce(*model_, *st.reactionPrev);  // M a0 (+ C v0)
  // The steps: equal ones halved on Newton failure, or sized by the
  // frozen-geometry error (Step Control).
  std::unique_ptr<StepController> controller;
  AdaptiveSteps* adaptive = nullptr;
  if (hostController_) {
    controller = std::move(hostController_);
    adaptive = dynamic_cast<AdaptiveSteps*>(controller.get());
  } else if (stepControl_.tolerance > 0.0) {
    auto a = std::make_unique<AdaptiveSteps>(finalLambda, stepControl_.first, stepControl_.minSize,
                                             stepControl_.maxSize, stepControl_.tolerance, maxBisect,
                                             stepControl_.corrections);
    adaptive = a.get();
    controller = std::move(a);
  } else {
    controller = std::make_unique<BisectingSteps>(finalLambda, nsteps, maxBisect);
  }
  StepController& steps = *controller;
  // history.csv's row of a converged (sub)step.
  auto historyRow = [&](const StepRecord& rec) {
    std::vector<double> row{double(rec.step), rec.loadFactor, rec.strainEnergy, double(rec.newtonIterations),
                            double(rec.dualIterations), double(rec.activeContacts), rec.contactForce[0],
                            rec.contactForce[1], double(rec.contactExchanges), rec.wallSeconds, rec.externalWork,
                            double(rec.contactBytes), double(rec.bisections), rec.contactForce[2]};
    if (dynamic_) row.insert(row.end(), {rec.loadFactor, rec.kineticEnergy, rec.kineticEnergy + rec.strainEnergy});
    if (decomposed)
      row.insert(row.end(), {rec.stepSize, double(rec.rejections), double(rec.corrections), rec.geometryError});
    return row;
  };
  // The checkpoint's state: the step controller's after the last accepted
  // step, the history rows of the checkpoint last written.
  std::vector<double> acceptedState = steps.saveState();
  size_t checkpointRows = 0;
  double wallOffset = 0.0;  // a restart's wall times go on from the checkpoint's
  if (restart_) {
    auto series = restoreCheckpoint(st, steps);
    acceptedState = steps.saveState();
    wallOffset = history_.back().wallSeconds;
    if (hist)
      for (const StepRecord& r : history_) hist->appendRow(historyRow(r));
    if (vtk) {
      const auto missing = vtk->adoptSteps(restart_->directory, series);
      if (!missing.empty())
        progress("warning: restart: " + std::to_string(missing.size()) + " VTK steps of the checkpointed run are "
                 "missing in '" + restart_->directory + "/vtk' (VTK was off, or the files were removed); the series "
                 "goes on without them");
    }
    if (exodus) {
      const auto [copied, why] = exodus->copySteps(exodusSource, int(history_.size()));
      if (copied < int(history_.size()))
        progress("warning: restart: results.e holds " + std::to_string(copied) + " of the " +
                 std::to_string(history_.size()) + " steps before the checkpoint (" + why + ")");
      std::error_code ec;
      if (exodusAside) std::filesystem::remove(exodusSource, ec);  // rank 0's flag
    }
    char buf[200];
    std::snprintf(buf, sizeof buf, "restart: continuing after step %d (%s %.6g) from ", history_.back().step,
                  factorName, history_.back().loadFactor);
    progress(buf + restart_->checkpoint->path());
    restart_.reset();  // one run continues from it
  } else {
    writeVtk(0, 0.0);
  }
  // The attempts of the step being worked on: the exchanges (also of
  // attempts Newton failed on) and the Newton and dual iterations of the
  // attempts the step control sent back count in the accepted step's row
  // (its cost); the contact state of the step's start, which a repeat with
  // the geometry of the step's end keeps.
  struct Attempts {
    long exchanges0 = 0, bytes0 = 0;  ///< the model's counters when the step began
    int rejections = 0, corrections = 0;  ///< sent back smaller / repeated
    int newton = 0, dual = 0;             ///< iterations of the attempts sent back
    std::vector<ContactSlot> startSlots;
    bool repeating = false;  ///< the next attempt repeats the step with the geometry of its end
  };
  auto firstAttempt = [&] {
    Attempts a;
    a.exchanges0 = contact ? model_->exchanges() : 0;
    a.bytes0 = contact ? model_->bytesExchanged() : 0;
    return a;
  };
  Attempts att = firstAttempt();
  // "step   3/10" (equal steps) or "step   3" (their number is not known).
  auto stepLabel = [&](int n) {
    char b[40];
    if (steps.numSteps() > 0)
      std::snprintf(b, sizeof b, "%3d/%d", n, steps.numSteps());
    else
      std::snprintf(b, sizeof b, "%3d", n);
    return std::string(b);
  };
  if (!nearlyIncompressible_.empty()) progress("warning: " + nearlyIncompressible_);
  auto contactWarnings = [&] {
    for (const auto& w : model_->takeContactWarnings()) progress("warning: " + w);
  };
  contactWarnings();  // from the initial pairing
  try {
    while (!steps.done()) {
      const StepProposal p = steps.propose();
      const int n = p.step;
      StepRecord rec;
      rec.step = n;
      // The contact state at the step's start (a repeat with the geometry of
      // the step's end keeps the one saved before it).
      if (contact && !att.repeating) att.startSlots = model_->contactSlots();
      att.repeating = false;
      if (contact && model_->contactOptions().initialInContact) model_->activateAllPaired();
      if (integrator_) {
        // f_ext(t_n) = λ_n f_ext for the α-methods' previous-step terms.
        auto externalNow = model_->createVector();
        externalNow->update(p.from, model_->externalForce(), 0.0);
        if (model_->bodyForce()) externalNow->update(1.0, *model_->bodyForce(), 1.0);
        integrator_->beginStep(*model_, p.size, *st.fint, *externalNow);
      }
      Activity activity("solving step " + std::to_string(n) + " (" + factorName + " " + std::to_string(p.from) + " -> " +
                        std::to_string(p.to) + ", " + std::to_string(model_->ownedMap()->getGlobalNumElements()) +
                        " unknowns; estimated " + formatBytes(memoryEstimate_.total()) + " per rank)");
      // Test seams (DDCONTACT_FAULT_INJECTION): SIGTERM to rank 0 when step
      // n is first tried (once: a second SIGTERM ends the process); every
      // attempt of step n failing as Newton does.
      static bool raised = false;
      if (faultInjectionActive() && comm_->getRank() == 0 && !raised && faultInjection("sigterm", std::to_string(n))) {
        raised = true;
        std::raise(SIGTERM);
      }
      const bool injectedFailure = faultInjectionActive() && faultInjection("newton-failure", std::to_string(n));
      if (injectedFailure) rec.failure = "test fault injection: newton-failure@" + std::to_string(n);
      if (injectedFailure || !solveIncrement(p.from, p.to, rec)) {
        if (contact) model_->restoreContactState(att.startSlots);
        if (!steps.reject(p)) {
          std::ostringstream os;
          os << "Newton did not converge in step " << n << " (" << factorName << " " << p.from << " -> " << p.to
             << ") after " << p.depth << " bisections (" << stepping << "/Max Bisections = " << maxBisect;
          if (adaptive) os << ", Step Control/Minimum Step Size = " << adaptive->minSize();
          os << "): " << rec.failure;
          if (!rec.residualHistory.empty()) os << "; residual history:";
          for (double x : rec.residualHistory) os << " " << x;
          if (!nearlyIncompressible_.empty()) os << "; note: " << nearlyIncompressible_;
          throw SolverError(os.str());
        }
        const StepProposal next = steps.propose();
        char buf[200];
        std::snprintf(buf, sizeof buf, "  step %d: Newton failed at %s %.6g; bisecting (depth %d), next %.6g", n,
                      factorName, p.to, next.depth, next.to);
        progress(buf);
        continue;
      }
      const double lambda = p.to;
      rec.loadFactor = lambda;
      rec.bisections = p.depth;
      rec.stepSize = p.size;
      auto fint = model_->createVector();
      rec.strainEnergy = model_->assemble(*u_, lambda, fint.get(), nullptr, nullptr).strainEnergy;
      ContactSummary cs;
      std::vector<ContactSlot> convergedSlots;
      if (contact) {
        // Converged: refresh the pairing once per step, with a global search
        // (tracking cannot see another part of the surface come nearer). The
        // decomposed element freezes the new projections and normals.
        // Multipliers, gaps and normals of the converged state are read first:
        // after re-pairing, the decomposed slots hold the next step's normals.
        model_->updateActiveSet(*u_);
        cs = model_->contactSummary();
        if (contactNodes || decomposed) convergedSlots = model_->contactSlots();
        model_->updatePairing(*u_, true, decomposed);
        contactWarnings();
        if (decomposed) {
          // The frozen-geometry error indicator (doc/contact.md, "Step control
          // by the frozen-geometry error"), relative to the energy of the state.
          double energy = rec.strainEnergy;
          if (integrator_) {
            auto v = model_->createVector();
            integrator_->velocity(*u_, *v);
            energy += model_->kineticEnergy(*v);
          }
          const double w = model_->contact()->frozenGeometryError(convergedSlots).total();
          rec.geometryError = energy > 0.0 ? w / energy : 0.0;
        }
      }
      const StepVerdict verdict = steps.judge(p, rec.geometryError);
      if (verdict != StepVerdict::Accept) {
        // Back to the step's start: the displacements (the integrator and
        // f_int were not advanced) and, to try a smaller step, the contact
        // state; a repeat keeps the pairing just refreshed at the step's end,
        // so the step is solved again with the projections and normals of
        // its end.
        u_->assign(*st.uPrev);
        const bool repeat = verdict == StepVerdict::Repeat;
        att.repeating = repeat;
        att.newton += rec.newtonIterations;
        att.dual += rec.dualIterations;
        if (repeat)
          ++att.corrections;
        else {
          model_->restoreContactState(att.startSlots);
          ++att.rejections;
        }
        const StepProposal next = steps.propose();
        char buf[300];
        std::snprintf(buf, sizeof buf, "  step %d: frozen-geometry error %.3g above Step Control/Error Tolerance at %s %.6g; %s", n,
                      rec.geometryError, factorName, p.to,
                      repeat ? "repeating it with the projections and normals of its end" : "repeating it smaller");
        std::string line = buf;
        if (!repeat) {
          std::snprintf(buf, sizeof buf, " (size %.3g -> %.3g)", p.size, next.size);
          line += buf;
        }
        progress(line);
        continue;
      }
      steps.accept(p);
      acceptedState = steps.saveState();
      rec.rejections = att.rejections;
      rec.corrections = att.corrections;
      rec.newtonIterations += att.newton;
      rec.dualIterations += att.dual;
      st.fint = fint;
      if (contactNodes) st.convergedSlots = convergedSlots;
      // The forces the prescribed DOFs exert: f_int, and in dynamics also the
      // inertia and damping of the prescribed nodes (a moving support
      // accelerates its nodes' mass).
      st.reaction->assign(*st.fint);
      if (integrator_) {
        integrator_->acceptStep(*u_);
        rec.kineticEnergy = model_->kineticEnergy(integrator_->velocity());
        auto f = model_->createVector();
        integrator_->inertiaForce(*model_, *f);
        st.reaction->update(1.0, *f, 1.0);
      }
      st.externalWork += externalWorkIncrement(*st.reactionPrev, *st.uPrev, p.from, *st.reaction, *u_, lambda);
      rec.externalWork = st.externalWork;
      st.reactionPrev->assign(*st.reaction);
      st.uPrev->assign(*u_);
      if (contact) {
        rec.activeContacts = cs.active;
        rec.contactForce[0] = cs.force[0];
        rec.contactForce[1] = cs.force[1];
        rec.contactForce[2] = cs.force[2];
        rec.contactExchanges = model_->exchanges() - att.exchanges0;
        rec.contactBytes = model_->bytesExchanged() - att.bytes0;
      }
      att = firstAttempt();  // of the next step
      if (adaptive && adaptive->atMinimum()) {
        char buf[240];
        std::snprintf(buf, sizeof buf, "warning: step %d: frozen-geometry error %.3g above Step Control/Error Tolerance at the minimum step size %.3g (Step Control/Minimum Step Size); accepted",
                      n, rec.geometryError, p.size);
        progress(buf);
      }
      rec.wallSeconds = seconds() + wallOffset;
      history_.push_back(rec);
      if (hist) hist->appendRow(historyRow(rec));
      char buf[300];
      if (dynamic_)
        std::snprintf(buf, sizeof buf,
                      "step %s  time %.6g (dt %.3g)  Newton %2d  |r| %.3e -> %.3e  strain %.6e  kinetic %.6e  %.2f s",
                      stepLabel(n).c_str(), lambda, p.size, rec.newtonIterations, rec.residualHistory.front(),
                      rec.residualHistory.back(), rec.strainEnergy, rec.kineticEnergy, rec.wallSeconds);
      else
        std::snprintf(buf, sizeof buf, "step %s  load %.6g  Newton %2d  |r| %.3e -> %.3e  energy %.6e  %.2f s",
                      stepLabel(n).c_str(), lambda, rec.newtonIterations, rec.residualHistory.front(), rec.residualHistory.back(),
                      rec.strainEnergy, rec.wallSeconds);
      std::string line = buf;
      if (adaptive) {
        std::snprintf(buf, sizeof buf, "  size %.3g  error %.3g", p.size, rec.geometryError);
        line += buf;
      }
      if (contact) {
        std::snprintf(buf, sizeof buf, "  contacts %d  force (%.4g, %.4g)", rec.activeContacts, rec.contactForce[0],
                      rec.contactForce[1]);
        line += buf;
        // z after the 2-D pair, so the line reads the same in 2-D.
        if (model_->mesh().dim() == 3) {
          std::snprintf(buf, sizeof buf, " z %.4g", rec.contactForce[2]);
          line += buf;
        }
      }
      progress(line);
      if (exodus) {
        std::vector<double> g = {lambda, rec.strainEnergy, rec.externalWork, double(rec.activeContacts),
                                 rec.contactForce[0], rec.contactForce[1]};
        if (model_->mesh().dim() == 3) g.push_back(rec.contactForce[2]);
        if (dynamic_) g.push_back(rec.kineticEnergy);
        writeExodusStep(*exodus, *model_, lambda, *u_, integrator_ ? &integrator_->velocity() : nullptr,
                          integrator_ ? &integrator_->accelerationNow() : nullptr, g);
      }
      const bool last = steps.done();
      if (++st.outputCount % out.get<int>("VTK Interval") == 0 || last)
        writeVtk(static_cast<int>(history_.size()), lambda);
      if (!checkpointPath.empty() && (history_.size() % size_t(checkpointInterval) == 0 || last)) {
        writeCheckpoint(checkpointPath, st, acceptedState, vtk ? vtk->steps() : std::vector<std::pair<int, double>>());
        checkpointRows = history_.size();
      }
      // A stop requested by a signal on any rank (requestStop()): after this
      // step, on every rank.
      int stop = stopRequested(), stopAll = 0;
      Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, stop, Teuchos::outArg(stopAll));
      if (stopAll && !last) {
        std::ostringstream os;
        os << "stopped by " << signalName(stopAll) << " after step " << n << " (" << factorName << " " << lambda << ")";
        if (!checkpointPath.empty()) {
          if (checkpointRows != history_.size())
            writeCheckpoint(checkpointPath, st, acceptedState, vtk ? vtk->steps() : std::vector<std::pair<int, double>>());
          os << "; its checkpoint is '" << checkpointPath << "': continue with --restart '" << dir->finalPath() << "'";
        } else {
          os << "; no checkpoint (" << (dir ? "Output/Checkpoint Interval = 0" : "no output directory") << ")";
        }
        throw RunInterrupted(os.str(), stopAll);
      }
    }
  } catch (const SolverError& e) {
    // A failed step: the checkpoint of the last converged one, unless it
    // is on disk already (the state is that step's: a failed attempt
    // leaves the displacements, and its contact state is restored here).
    if (checkpointPath.empty() || history_.empty()) throw;
    std::ostringstream os;
    os << e.what();
    try {
      if (checkpointRows != history_.size()) {
        u_->assign(*st.uPrev);
        if (contact && !att.startSlots.empty()) model_->restoreContactState(att.startSlots);
        writeCheckpoint(checkpointPath, st, acceptedState, vtk ? vtk->steps() : std::vector<std::pair<int, double>>());
      }
      os << "; the checkpoint of step " << history_.back().step << " (" << factorName << " "
         << history_.back().loadFactor << ") is '" << checkpointPath << "': continue with --restart '"
         << dir->finalPath() << "' (changing the steps or the solver settings)";
    } catch (const OutputError& w) {
      // The failure is the news; that its checkpoint is missing comes second.
      os << "; the checkpoint of the last converged step could not be written: " << w.what();
    }
    throw SolverError(os.str());
  }
  const double lambda = steps.current();
  // The validators make every run step (Number of Steps > 0, Final Load
  // Factor > 0 and finite); should anything still leave no converged step,
  // the run must fail rather than commit a history.csv without rows.
  if (history_.empty() || !(lambda > 0.0)) {
    std::ostringstream os;
    os << "the analysis made no converged step (" << stepping << ": " << nsteps << " steps to " << finalLambda
       << "), so there are no results";
    throw SolverError(os.str());
  }
  if (contactNodes) writeContactNodes(dir->path() + "/contact_nodes.csv", st.convergedSlots);
  if (contact) {
    const auto c = model_->searchCounters();
    std::ostringstream os;
    os << "contact: " << model_->exchanges() << " contact-geometry exchanges (" << model_->bytesExchanged()
       << " bytes between ranks); slave queries: " << c[0] << " by tracking (" << c[1]
       << " fell back to the global search), " << c[2] << " by the global search";
    progress(os.str());
    for (const auto& pair : model_->neverPairedPairs())
      progress("warning: " + pair + " never paired a slave node in this run: no master facet within the search "
               "radius (Contact/Search Radius) faced any of its slave nodes, so contact was not enforced there "
               "(doc/contact.md, 'Which slave nodes pair')");
  }
  {
    // Peak resident memory per rank.
    const double mine = peakResidentBytes() / (1024.0 * 1024.0);
    Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, mine, Teuchos::outArg(timing_.peakMemoryMiB));
    double t[3] = {timing_.assembly, timing_.linearSetup, timing_.linearSolve}, tmax[3];
    Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 3, t, tmax);
    timing_.assembly = tmax[0], timing_.linearSetup = tmax[1], timing_.linearSolve = tmax[2];
    int dual = 0;
    for (const auto& r : history_) dual += r.dualIterations;
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "timing (max over ranks): assembly %.3f s, linear setup %.3f s, linear solve %.3f s over %d "
                  "solves (%d dual/Krylov iterations); peak memory per rank %.1f MiB",
                  timing_.assembly, timing_.linearSetup, timing_.linearSolve, timing_.linearSolves, dual,
                  timing_.peakMemoryMiB);
    progress(buf);
    const std::string breakdown = strategy_->timingReport(timing_.feti);
    if (!breakdown.empty()) progress(breakdown);
  }
  if (dir) {
    hist->close();
    hist.reset();
    vtk.reset();
    if (exodus) exodus->close();
    exodus.reset();
    dir->commit();
    progress("results in " + dir->finalPath());
  }
}

}  // namespace ddc
