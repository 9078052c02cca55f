#include "DDC_Analysis.hpp"

#include <Teuchos_XMLParameterListHelpers.hpp>

#include <cstdio>
#include <iostream>

#include "DDC_CoincidentNodes.hpp"
#include "DDC_ContactParameters.hpp"
#include "DDC_Distribution.hpp"
#include "DDC_Error.hpp"
#include "DDC_FaultSeam.hpp"
#include "DDC_InputDeck.hpp"
#include "DDC_Memory.hpp"
#include "DDC_MeshInRanges.hpp"
#include "DDC_OutputObservers.hpp"
#include "DDC_Parameters.hpp"
#include "DDC_RunCheckpoint.hpp"
#include "DDC_SurfaceContactElement.hpp"

namespace ddc {

using PL = Teuchos::ParameterList;

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
  if (!dynamic_) requireDynamicsForDynamicConditions(params.sublist("Dynamics"));
  DDC_INPUT_REQUIRE(params.isSublist("Mesh"), "sublist 'Mesh' is required");
  newton_ = NewtonSettings::fromParameters(params.sublist("Newton"));
  progressEnabled_ = params.sublist("Output").get<bool>("Progress");
  DDC_INPUT_REQUIRE(!params.sublist("Output").get<bool>("Contact Nodes") ||
                        (params.isSublist("Contact") && params.sublist("Contact").isSublist("Pairs") &&
                         params.sublist("Contact").sublist("Pairs").numParams() > 0),
                    "parameter 'Output/Contact Nodes' is true, but the deck has no contact pairs "
                    "(Contact/Pairs): there are no contact nodes to write");
  // Every rank reads the mesh and map files named in the parameters: a file
  // missing or different on some ranks must fail all ranks alike.
  inputFiles_ = requireSameFilesOnEveryRank(*comm_, namedInputFiles(params, baseDirectory));
  buildModel(params, baseDirectory);
  unloaded_ = model_->createVector();
  if (dynamic_) dynamics_ = makeDynamics(params.sublist("Dynamics"), *model_, *strategy_);
  stepControl_ = stepControlSettings(params, dynamic_, model_->decomposedContact());
  const std::string sizes = std::to_string(model_->mesh().numGlobalNodes()) + " nodes, " +
                            std::to_string(model_->mesh().numGlobalElements()) + " elements, " +
                            std::to_string(model_->partition().numSubdomains) + " subdomains; estimated " +
                            formatBytes(memoryEstimate_.total()) + " per rank";
  Activity activity("setting up the " + strategy_->name() + " solver (" + sizes + ")");
  strategy_->setUp(model_, [this](const std::string& line) { progress(line); });
  progress(distributionLine(*comm_, *model_, rankShare(*model_, strategy_->coarseRowsOnThisRank()),
                            memoryEstimate_.total(), meshOrigin_));
  params_ = params;
}

Analysis::~Analysis() = default;

namespace {

/// 'Partition/Mesh On Every Rank' = false: `mesh` becomes this rank's part
/// (rankPart(): the elements of its subdomains and their nodes) and
/// `partition` its elements' subdomains; the whole mesh goes with the last
/// reference to it.
void keepOwnPart(std::shared_ptr<Mesh>& mesh, Partition& partition, int rank, int ranks) {
  RankPart own = rankPart(*mesh, partition, rank, ranks);
  mesh = std::make_shared<Mesh>(std::move(own.mesh));
  partition = std::move(own.partition);
}

/// The contact elements by role and facet type, from the factory (host
/// codes may replace them there).
ContactComponent::SurfaceElementSource surfaceElementMaker(const ElementFactory& factory) {
  return [factory](SurfaceContactRole role, CellType facet) {
    Teuchos::ParameterList pl;
    const std::string type = surfaceContactElementName(role, facet);
    pl.set("Type", type);
    auto el = std::dynamic_pointer_cast<const SurfaceContactElement>(factory.create(pl, "Contact/Formulation"));
    DDC_INPUT_REQUIRE(el != nullptr, "element type '" << type << "' registered in the factory is not a surface "
                                                      "contact element");
    return el;
  };
}

}  // namespace

void Analysis::buildModel(Teuchos::ParameterList& params, const std::string& baseDirectory) {
  // Memory: what each rank may use, checked by the mesh generators before
  // they allocate and, once the mesh and partition are known, against the
  // estimate of the whole run (doc/user-guide.md, "Memory").
  const bool memoryCheck = params.sublist("Solver").get<bool>("Memory Check");
  const MemoryLimit memory = memoryCheck ? availableMemory(*comm_) : MemoryLimit();
  const std::string memoryHint =
      "refine less, run on more ranks or hosts, or set 'Solver/Memory Check' = false to run anyway";
  memoryBudget_ = MemoryBudget();
  PL& meshParams = params.sublist("Mesh");
  // Without the whole mesh on every rank and with PT-Scotch, the bodies are
  // generated or read by element range (no rank holds the whole mesh);
  // otherwise each rank builds the whole mesh (and keeps its part after
  // partitioning).
  meshOrigin_ = meshOrigin(params);
  const MPI_Comm comm = rawComm(comm_);
  auto mesh = meshOrigin_ == MeshOrigin::Ranges
                  ? buildMeshInRanges(meshParams, factory_, &memory, memoryHint, comm, baseDirectory)
              : buildMesh(meshParams, factory_, baseDirectory, &memory, memoryHint, comm);
  auto elements = makeBodyElements(*mesh, meshParams, factory_);
  // Nearly incompressible materials lock: said at the start and with a
  // Newton failure, where it is the likely cause (with the other caveats).
  caveats_ = nearlyIncompressibleBodies(*mesh, meshParams);
  requireAdmissibleElements(*mesh, elements, rawComm(comm_));
  auto bcs = BoundaryConditions::fromParameters(params.sublist("Boundary Conditions"), *mesh, "Boundary Conditions");
  // The integrators' terms of the previous step take the external force as
  // the time times Model::externalForce(): a traction's Load Curve is static.
  for (const auto& t : bcs.tractions)
    DDC_INPUT_REQUIRE(!dynamic_ || t.curve.empty(),
                      "parameter 'Boundary Conditions/" << t.name << "/Load Curve' is set on a traction, but "
                          "'Dynamics/Integrator' is not None: a traction's Load Curve applies to static runs "
                          "only; remove it (the traction then grows with the time) or set 'Dynamics/Integrator' "
                          "= None");
  auto contact = ContactOptions::fromParameters(params.sublist("Contact"), *mesh, "Contact", rawComm(comm_));
  if (dynamic_ && params.sublist("Contact").get<std::string>("Initial Contact State") == "Automatic")
    contact.initialInContact = false;  // Previous Step: a time step changes the active set little
  const std::string strategy = params.sublist("Solver").get<std::string>("Strategy");
  requireJoinedCoincidentNodes(*mesh, contact, rawComm(comm_));
  requireSupportedBodies(*mesh, bcs, contact, strategy == "FETI-DP", dynamic_, rawComm(comm_));
  Partition partition = partitionMesh(mesh, params, contact, memoryCheck, baseDirectory);
  strategy_ = makeSolutionStrategy(comm_, params.sublist("Solver"), contact);
  Activity activity("building the model (" + std::to_string(mesh->numGlobalNodes()) + " nodes, " +
                    std::to_string(mesh->numGlobalElements()) + " elements, " +
                    std::to_string(partition.numSubdomains) + " subdomains; estimated " +
                    formatBytes(memoryEstimate_.total()) + " per rank)");
  if (meshOrigin_ == MeshOrigin::EveryRank && !params.sublist("Partition").get<bool>("Mesh On Every Rank"))
    keepOwnPart(mesh, partition, comm_->getRank(), comm_->getSize());
  model_ = std::make_shared<Model>(comm_, mesh, std::move(elements), std::move(partition), std::move(bcs),
                                   std::move(contact), surfaceElementMaker(factory_));
}

Partition Analysis::partitionMesh(std::shared_ptr<Mesh>& mesh, const PL& params, const ContactOptions& contact,
                                  bool memoryCheck, const std::string& baseDirectory) {
  // A run too large even with evenly sized subdomains is refused before
  // METIS runs (it takes seconds on large meshes, on every rank).
  const int ranks = comm_->getSize();
  const PL& solver = params.sublist("Solver");
  const std::string strategy = solver.get<std::string>("Strategy");
  if (memoryCheck) {
    const Partition balanced = balancedPartition(*mesh, params.sublist("Partition"), strategy, ranks);
    if (balanced.numSubdomains >= ranks) requireMemory(*mesh, balanced, solver, contact);
  }
  Partition partition = partitionModel(*mesh, params.sublist("Partition"), strategy, rawComm(comm_), baseDirectory);
  if (partition.edgeCut >= 0)
    progress(partitionSummary(*mesh, partition, params.sublist("Partition").get<std::string>("Method"),
                              rawComm(comm_)));
  if (meshOrigin_ != MeshOrigin::EveryRank) {
    // Each element to the rank of its subdomain.
    Activity activity("moving each element to the rank of its subdomain");
    RankPart own = migratedRankPart(rawComm(comm_), *mesh, partition);
    mesh = std::make_shared<Mesh>(std::move(own.mesh));
    own.partition.edgeCut = partition.edgeCut;
    partition = std::move(own.partition);
  }
  if (memoryCheck) requireMemory(*mesh, partition, solver, contact);
  else memoryEstimate_ = estimate(*mesh, partition, solver, contact);
  return partition;
}

void Analysis::requireMemory(const Mesh& mesh, const Partition& partition, const PL& solver,
                             const ContactOptions& contact) {
  // The estimate with its margin against what the ranks of each host share
  // and what each process may map (doc/user-guide.md, "Memory").
  memoryEstimate_ = estimate(mesh, partition, solver, contact);
  memoryBudget_ = memoryBudget(*comm_, memoryEstimate_.perRank.at(comm_->getRank()), kMemoryEstimateMargin);
  DDC_INPUT_REQUIRE(memoryBudget_.fits,
                    "the run needs an estimated "
                        << formatBytes(memoryEstimate_.total()) << " per rank (" << memoryEstimate_.describe()
                        << "; doc/user-guide.md, 'Memory'), more than the " << formatBytes(memoryBudget_.available)
                        << " available (" << memoryBudget_.source
                        << "): run fewer ranks per host or on more hosts, refine less, or choose a lighter solver "
                           "(FETI-DP, or Belos-MueLu instead of a direct solver); or set 'Solver/Memory Check' = "
                           "false to run anyway");
}

MemoryEstimate Analysis::estimate(const Mesh& mesh, const Partition& partition, const PL& solver,
                                  const ContactOptions& contact) const {
  if (!mesh.isPart()) return estimateMemory(mesh, partition, comm_->getSize(), solver, contact);
  const ModelSize size =
      measureModelOnParts(rawComm(comm_), mesh, partition, contact, estimateReadsRankNodes(solver));
  return estimateMemory(size, comm_->getSize(), solver);
}

void Analysis::progress(const std::string& line) const {
  if (comm_->getRank() == 0 && progressEnabled_) std::cout << line << std::endl;
}

const std::vector<StepRecord>& Analysis::history() const {
  static const std::vector<StepRecord> none;
  return loop_ ? loop_->history() : none;
}

const RunTiming& Analysis::timing() const {
  static const RunTiming none;
  return loop_ ? loop_->timing() : none;
}

void Analysis::setRestart(RestartSource source) {
  DDC_INPUT_REQUIRE(source.checkpoint, "setRestart: no checkpoint");
  const CheckpointReader& c = *source.checkpoint;
  const auto saved = Teuchos::getParametersFromXmlString(c.bytes("parameters"));
  checkRestartParameters(*saved, params_, c.path());
  // A checkpoint of another layout is refused by findRestartSource(), or by
  // run() when it is restored (requireCheckpointLayout()).
  if (c.has(kInputFilesSection)) {
    checkRestartInputFiles(c.bytes(kInputFilesSection), inputFiles_, c.path());
    checkRestartFinalValue(checkpointLastStep(c), stepLoopSettings(params_, dynamic_), c.path());
  }
  restart_ = std::make_unique<RestartSource>(std::move(source));
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

/// The analysis' own observers of one run, in the order the loop tells them.
struct Analysis::RunObservers {
  std::unique_ptr<HistoryObserver> history;
  std::unique_ptr<ProgressObserver> progress;
  std::unique_ptr<ExodusObserver> exodus;
  std::unique_ptr<VtkObserver> vtk;
  std::unique_ptr<CheckpointObserver> checkpoint;
  std::unique_ptr<ContactNodesObserver> contactNodes;
  std::unique_ptr<StopObserver> stop;
  std::unique_ptr<StepFaults> faults;
  void addTo(StepLoop& loop) const {
    for (StepObserver* o : std::initializer_list<StepObserver*>{history.get(), progress.get(), exodus.get(), vtk.get(),
                                                                  checkpoint.get(), contactNodes.get(), stop.get()})
      if (o) loop.addObserver(*o);
    loop.setFaults(faults.get());
  }
};

std::unique_ptr<Analysis::RunObservers> Analysis::makeObservers(OutputDirectory* dir) {
  auto obs = std::make_unique<RunObservers>();
  const ProgressPrinter say = [this](const std::string& line) { progress(line); };
  obs->progress = std::make_unique<ProgressObserver>(say, caveats_);
  obs->faults = makeFaultInjectionSeam(comm_);
  const PL& out = params_.sublist("Output");
  const int checkpointInterval = dir ? out.get<int>("Checkpoint Interval") : 0;
  if (dir) {
    DDC_INPUT_REQUIRE(!dir->committed(), "output directory '" << dir->finalPath()
                                                              << "' was committed already: one run per OutputDirectory");
    const RunKind kind = loop_->kind();
    obs->history = std::make_unique<HistoryObserver>(comm_, dir->path(), kind);
    writeParametersFile(*comm_, dir->path() + "/parameters.xml", params_);
    if (out.get<bool>("VTK")) obs->vtk = std::make_unique<VtkObserver>(comm_, dir->path(), out.get<int>("VTK Interval"), say);
    if (out.get<bool>("Exodus"))
      obs->exodus = std::make_unique<ExodusObserver>(comm_, dir->path(), *model_, kind,
                                                     restart_ ? restart_->directory + "/results.e" : "", say);
    if (checkpointInterval > 0)
      obs->checkpoint = std::make_unique<CheckpointObserver>(dir->path() + "/" + kCheckpointFileName,
                                                             dir->finalPath(), checkpointInterval, params_,
                                                             describeInputFiles(inputFiles_), obs->vtk.get());
    // contact_nodes.csv holds the contact state of the last converged step.
    if (model_->hasContact() && out.get<bool>("Contact Nodes"))
      obs->contactNodes = std::make_unique<ContactNodesObserver>(dir->path() + "/contact_nodes.csv");
  }
  MemoryWatch watch;
  watch.active = params_.sublist("Solver").get<bool>("Memory Check");
  watch.budget = memoryBudget_;
  watch.fraction = params_.sublist("Solver").get<double>("Memory Stop Fraction");
  obs->stop = std::make_unique<StopObserver>(obs->checkpoint.get(),
                                             dir ? "Output/Checkpoint Interval = 0" : "no output directory", watch);
  return obs;
}

void Analysis::runSteps(OutputDirectory* dir) {
  auto controller = hostController_ ? std::move(hostController_) : makeStepController(params_, dynamic_, stepControl_);
  StepLoopSettings settings = stepLoopSettings(params_, dynamic_);
  settings.estimatedMemory = "estimated " + formatBytes(memoryEstimate_.total()) + " per rank";
  settings.failureNote = caveats_;
  loop_ = std::make_unique<StepLoop>(model_, *strategy_, dynamics_.get(), newton_, std::move(controller), settings);
  auto observers = makeObservers(dir);
  if (restart_) {
    auto series = restoreRunCheckpoint(*loop_, *model_, *restart_->checkpoint);
    if (observers->vtk) observers->vtk->continueSeries(restart_->directory, std::move(series));
    const StepRecord& last = loop_->history().back();
    char buf[200];
    std::snprintf(buf, sizeof buf, "restart: continuing after step %d (%s %.6g) from ", last.step,
                  settings.factorName.c_str(), last.loadFactor);
    progress(buf + restart_->checkpoint->path());
    restart_.reset();  // one run continues from it
  }
  observers->addTo(*loop_);
  for (const auto& o : hostObservers_) loop_->addObserver(*o);
  // A run that stops or fails with a checkpoint, and says to continue it
  // with a restart, marks its staging directory so: a plain run into the
  // same directory does not discard it (doc/user-guide.md, "Checkpoints and
  // restart").
  try {
    loop_->run();
  } catch (const RunInterrupted&) {
    if (dir && observers->checkpoint) dir->markResumable(kCheckpointFileName);
    throw;
  } catch (const SolverError&) {
    if (dir && observers->checkpoint) dir->markResumable(kCheckpointFileName);
    throw;
  }
  if (dir) {
    dir->commit();
    progress("results in " + dir->finalPath());
  }
}

}  // namespace ddc
