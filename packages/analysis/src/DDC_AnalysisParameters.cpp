// The parameters of an analysis: every valid parameter with its default and
// doc string (doc/parameters.md is generated from them), by sublist. Each
// component validates its own level against these lists: the mesh bodies
// (buildMesh(), DDC_ModelSetUp.cpp), the steps (DDC_StepsSetUp.cpp), the
// solver (makeSolutionStrategy()), Newton (NewtonSettings), contact
// (ContactOptions), boundary conditions (BoundaryConditions).
#include "DDC_AnalysisParameters.hpp"

#include "DDC_Analysis.hpp"
#include "DDC_BoundaryConditions.hpp"
#include "DDC_ContactParameters.hpp"
#include "DDC_ExodusMesh.hpp"
#include "DDC_Gmsh.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_Newton.hpp"
#include "DDC_Parameters.hpp"
#include "DDC_SolutionStrategy.hpp"

namespace ddc {

using PL = Teuchos::ParameterList;

const std::vector<std::string> kMeshGenerators = {"Rectangle", "Annular Sector", "Box", "Cylindrical Shell Sector",
                                              "Sphere Octant", "Gmsh", "Exodus"};

namespace {

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

}  // namespace

Teuchos::RCP<PL> bodyValidParameters(const ElementFactory& factory) {
  auto pl = Teuchos::rcp(new PL("<Body Name>"));
  pl->set("Generator", "Rectangle",
          "How the body's mesh is made: a built-in generator, a Gmsh file or an Exodus II file; its parameters go in the "
          "sublist of the same name.",
          enumValidator(kMeshGenerators, "Generator"));
  for (const auto& g : kMeshGenerators)
    setSublist(*pl, g, *generatorValidParameters(g), "Parameters of the " + g + " generator (Generator = " + g + ").");
  setSublist(*pl, "Element", *elementValidParameters(factory), "Element type and material of the body.");
  return pl;
}

namespace {

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

}  // namespace

namespace {
/// Bounds of the dynamic parameters, physical in any consistent units in
/// use (doc/user-guide.md, "Dynamics"): beyond them a value is a typing
/// error, and it would overflow the mass, inertia or energy arithmetic.
constexpr double kMaxRayleighAlpha = 1e9;  ///< 1/time
constexpr double kMaxSpeed = 3e11;         ///< the speed of light in mm/s
constexpr double kMaxAcceleration = 1e11;  ///< 10^7 g in mm/s^2
}  // namespace

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
            "of a mode of angular frequency w being alpha_R / (2 w) + beta_R w / 2. At most 1e9 (per second: "
            "critical damping of every mode below 5e8 rad/s, beyond any structural frequency).",
            between(0.0, kMaxRayleighAlpha));
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
      velocity.set(std::string("Velocity ") + a, 0.0,
                   std::string("Initial velocity along ") + a +
                       " (Z: 3-D only); magnitude at most 3e11, the speed of light in mm/s (in m/s 3e8).",
                   finiteMagnitude(kMaxSpeed));
    Teuchos::ParameterList velocities("Initial Velocity");
    setSublist(velocities, "<Condition Name>", velocity, "One sublist per initial-velocity condition.");
    setSublist(*pl, "Initial Velocity", velocities,
               "Velocities at t = 0 by body or node set (default: at rest); later conditions override earlier "
               "ones on shared nodes. Prescribed DOFs take the velocity of their prescribed motion instead.");
    Teuchos::ParameterList body("<Condition Name>");
    body.set("Set", std::string(""), "The body's name: the field acts on all of it.");
    for (const char* a : {"X", "Y", "Z"})
      body.set(std::string("Acceleration ") + a, 0.0,
               std::string("Gravitational acceleration along ") + a +
                   " (Z: 3-D only); magnitude at most 1e11, 10^7 g in mm/s^2 (ten times an ultracentrifuge's).",
               finiteMagnitude(kMaxAcceleration));
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

namespace {

Teuchos::RCP<PL> solverValidParameters() {
  auto pl = Teuchos::rcp(new PL("Solver"));
  pl->set("Memory Check", true,
          "Estimate the memory per rank from the mesh, the partition and the solver before building anything "
          "(doc/user-guide.md, 'Memory') and refuse a run whose estimate, with a margin of 25 % for what it may "
          "miss, exceeds what the ranks of a host share (MemAvailable or a control-group limit) or what a "
          "process may map (ulimit -v); false: run anyway (and no Memory Stop Fraction).");
  pl->set("Memory Stop Fraction", 0.9,
          "With Memory Check: stop at the end of a step, with a checkpoint and a message, once the ranks of "
          "a host hold more than this fraction of what the check allowed them (what the host had available "
          "at the start plus what they held then), or a rank maps more than this fraction of its ulimit -v "
          "(doc/user-guide.md, 'Memory'); 1: only at the limit itself.",
          between(0.0, 1.0, Interval::LeftOpen));
  pl->set("Strategy", "Monolithic",
          "Solution strategy. Monolithic: one global system (distributed Tpetra CrsMatrix, contact "
          "multipliers appended) solved by the Linear Solver below. FETI-DP: dual-primal domain "
          "decomposition over the partition's subdomains (the FETI-DP sublist); contact needs Contact/"
          "Formulation = Decomposed Node-To-Segment there (active pairs become rows of B, across partitions).",
          enumValidator({"Monolithic", "FETI-DP"}, "Strategy"));
  setSublist(*pl, "Linear Solver", *DirectSolverFactory::withIterativeSolvers().validParameters(),
             "Solver of the monolithic system ({Type, <back-end sublists>}): direct (MUMPS, Amesos2) or "
             "iterative (Belos-MueLu, Belos-FROSch; elasticity without contact only).");
  {  // The monolithic system's own MUMPS default (monolithicMumpsOrdering()).
    Teuchos::ParameterList& mumps = pl->sublist("Linear Solver").sublist("MUMPS");
    const Teuchos::ParameterEntry& entry = mumps.getEntry("Ordering");
    mumps.set("Ordering", std::string(monolithicMumpsOrdering()),
              "Fill-reducing ordering of the monolithic system, MUMPS ICNTL(7): METIS (default here: "
              "METIS_NodeND's nested dissection, computed on rank 0 and given to MUMPS, whose factors of 3-D "
              "stiffness matrices are smaller and faster than those of the orderings inside Debian's MUMPS, "
              "doc/performance.md), Auto (7, MUMPS chooses among the others), AMD (0), AMF (2), QAMD (6), PORD (4).",
              entry.validator());
  }
  setSublist(*pl, "FETI-DP", *FetiDpSolver::getValidParameters(),
             "FETI-DP options: local and coarse solvers, preconditioner, scaling, Belos.");
  return pl;
}

Teuchos::RCP<PL> partitionValidParameters() {
  auto pl = Teuchos::rcp(new PL("Partition"));
  pl->set("Number of Subdomains", 0,
          "Number of subdomains; 0: automatic, i.e. with Solver/Strategy = FETI-DP and Method = METIS or "
          "PT-Scotch about one per 'Subdomain Size' DOFs (at least one per MPI rank), otherwise one per MPI rank.",
          atLeast(0));
  pl->set("Subdomain Size", 0,
          "Target DOFs per subdomain of the automatic count (Number of Subdomains = 0, FETI-DP, METIS or "
          "PT-Scotch); 0: the measured optimum of this machine, 1650 in 3-D and 3200 in 2-D (doc/performance.md).",
          atLeast(0));
  pl->set("Method", "METIS",
          "METIS: METIS_PartMeshDual over all bodies, on every rank. PT-Scotch: the dual graph built and "
          "partitioned in parallel, each rank a share of the elements (SCOTCH_dgraphPart; the partition "
          "depends on the number of ranks; doc/partitioning.md). By Body: each body one subdomain. Box Grid: "
          "a regular grid of boxes over the mesh's bounding box (Box Grid X x Box Grid Y (x Box Grid Z in "
          "3-D) subdomains, by element centroid). Element Map File: one subdomain id per element, read from "
          "a file.",
          enumValidator({"METIS", "PT-Scotch", "By Body", "Box Grid", "Element Map File"}, "Method"));
  pl->set("Box Grid X", 2, "Box Grid: number of boxes along x.", greaterThan(0));
  pl->set("Box Grid Y", 2, "Box Grid: number of boxes along y.", greaterThan(0));
  pl->set("Box Grid Z", 1, "Box Grid: number of boxes along z (3-D meshes only).", greaterThan(0));
  pl->set("Element Map File", "",
          "Element Map File: file with one subdomain id per element (mesh element order, whitespace "
          "separated, '#' comments); relative to the input deck's directory.");
  pl->set("Mesh On Every Rank", true,
          "true: every rank keeps the whole mesh through the run. false: once the mesh is partitioned each "
          "rank keeps only its elements and their nodes (doc/architecture.md, 'What a distributed mesh has "
          "to change'), Monolithic or FETI-DP, with or without contact (the contact surfaces stay on every "
          "rank); Output/Exodus is written in pieces, one per rank. "
          "With Method = PT-Scotch no rank builds the whole mesh (each generates a range of the elements, "
          "or reads it from an Exodus II or Gmsh file, and the elements then move to their subdomains' "
          "ranks); otherwise (METIS and the other methods) each rank builds the whole mesh first and "
          "keeps its part, which lowers what a rank holds during the solve, not the peak of the set-up.");
  return pl;
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
          "values (doc/user-guide.md, 'The output directory'). With 'Partition/Mesh On Every Rank' = false each "
          "rank writes its piece instead, results.e.P.r (P ranks, rank r; the pieces SEACAS epu joins and "
          "ParaView reads as one), and no rank gathers the whole mesh or its values.");
  pl->set("Progress", true, "Print one progress line per converged step on rank 0.");
  pl->set("Checkpoint Interval", 10,
          "Write checkpoint.ddc, the state a restart continues from (ddcontact --restart), after every this many "
          "converged steps, after the last one, and when the run fails or is stopped by SIGTERM, SIGINT or SIGUSR1 (at the "
          "end of its current step); it replaces the previous one. 0: no checkpoints (doc/user-guide.md, "
          "'Checkpoints and restart').",
          atLeast(0));
  pl->set("Contact Nodes", false,
          "Write contact_nodes.csv: one row per contact slave node at the last converged step (pair, node, "
          "reference x y z, gap, multiplier, tributary area, pressure, active, tangential force x y z, slip, state: "
          "0 open, 1 stick, 2 slip), for contact-pressure "
          "distributions such as Hertz's (doc/contact.md).");
  return pl;
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
  setSublist(*pl, "Newton", *NewtonSettings::getValidParameters(), "Newton iteration and convergence criteria.");
  setSublist(*pl, "Solver", *solverValidParameters(), "Solution strategy and linear solvers.");
  setSublist(*pl, "Partition", *partitionValidParameters(), "Domain partitioning.");
  setSublist(*pl, "Contact", *ContactOptions::getValidParameters(), "Contact pairs and formulation.");
  setSublist(*pl, "Output", *outputValidParameters(), "What the run writes (besides history.csv).");
  return pl;
}

}  // namespace ddc
