// ddcontact: XML-driven nonlinear structural analysis (DDContact).
//
// Sample runs:
//   mpirun -np 2 ddcontact examples/arch.xml
//   ddcontact examples/elastic_block.xml --set "Mesh/Bodies/Block/Rectangle/Refinement=4"
//   ddcontact --print-parameters > doc/parameters.md
//
// Steps: (1) take rank 0's command line on every rank and parse it, (2) read
// the XML deck on rank 0 (strictly: ddc::readDeck) and broadcast it, apply
// --set overrides, (3) validate and build the analysis, (4) run it into the
// output directory. Any error ends the run on every rank with a message
// naming the file / parameter / mesh entity and a non-zero exit status.
#include <mpi.h>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Tpetra_Core.hpp>
#include <array>
#include <cctype>
#include <chrono>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <new>
#include <sstream>
#include <thread>
#include <vector>

#include "DDC_Analysis.hpp"
#include "DDC_BlasKernels.hpp"
#include "DDC_Error.hpp"
#include "DDC_InputDeck.hpp"
#include "DDC_Memory.hpp"
#include "DDC_MpiSession.hpp"
#include "DDC_OutputDirectory.hpp"
#include "DDC_Parameters.hpp"
#include "DDC_ResultFile.hpp"
#include "DDC_Restart.hpp"
#include "DDC_StopRequest.hpp"

namespace {

const char* kUsage =
    "usage: ddcontact INPUT.xml [--output-dir DIR] [--restart DIR] [--set PATH=VALUE]...\n"
    "       ddcontact --help | --print-parameters\n"
    "\n"
    "Runs the analysis described by the Teuchos XML parameter file INPUT.xml. Rank 0 reads it\n"
    "(strictly: every value must parse as its type, every name appear once per list) and every\n"
    "rank uses its contents; every rank also uses rank 0's command line.\n"
    "\n"
    "  --output-dir DIR    where results go (default: ddcontact-out/<input stem>);\n"
    "                      written to DIR.partial and moved to DIR when the run succeeds,\n"
    "                      so a failed run never overwrites earlier results; DIR must be\n"
    "                      new, empty or an earlier ddcontact result (DIR/ddcontact-result.txt),\n"
    "                      and one run at a time may use it (DIR.lock)\n"
    "  --restart DIR       continue the run whose output directory was DIR from its last\n"
    "                      checkpoint (DIR.partial/checkpoint.ddc if that run did not finish,\n"
    "                      else DIR/checkpoint.ddc), into --output-dir (default: DIR itself);\n"
    "                      the deck may change only the steps, Newton, Solver, Partition and\n"
    "                      Output settings (doc/user-guide.md, 'Checkpoints and restart')\n"
    "  --set PATH=VALUE    override a parameter, e.g. --set \"Load Stepping/Number of Steps=50\"\n"
    "                      (sublists joined by '/', VALUE parsed with the parameter's type)\n"
    "  --print-parameters  print every valid parameter with its default and description\n"
    "  --help              print this text\n"
    "\n"
    "Output: DIR/history.csv (one row per converged step), DIR/vtk/ (ParaView: solution.pvd),\n"
    "DIR/parameters.xml (the validated parameters, defaults included), DIR/checkpoint.ddc.\n"
    "SIGTERM, SIGINT or SIGUSR1 (which mpirun forwards) stops the run after its current step,\n"
    "with a checkpoint (a second signal ends it at once).\n";

struct Options {
  std::string input, outputDir, restart;
  std::vector<std::string> sets;
  bool help = false, printParameters = false;
};

/// The value of --output-dir or --set as given, checked before anything else
/// reads it: an empty directory (an unset shell variable) would otherwise
/// mean the default directory and replace the result there; a --set without
/// '=' (its value given as a separate argument) would make the value look
/// like a second input file.
void checkOptionValue(const std::string& option, const std::string& value) {
  if (option == "--output-dir")
    DDC_INPUT_REQUIRE(!value.empty(), "option --output-dir needs a directory, got an empty name (an unset shell "
                                      "variable?); leave the option out for the default ddcontact-out/<input stem>");
  if (option == "--restart")
    DDC_INPUT_REQUIRE(!value.empty(), "option --restart needs the output directory of the run to continue, got an "
                                      "empty name (an unset shell variable?)");
  if (option == "--set")
    DDC_INPUT_REQUIRE(value.find('=') != std::string::npos && value.find('=') > 0,
                      "option --set needs PATH=VALUE in one argument, got '"
                          << value << "' (quote a value with spaces: --set \"Load Stepping/Number of Steps=50\")");
}

/// Sets the value of an option that may be given once (--output-dir,
/// --restart): given twice, the last would win silently and the run would
/// continue or replace another directory than one of them names.
void setOnce(const std::string& option, std::string& target, const std::string& value,
             std::vector<std::string>& given) {
  for (const auto& g : given)
    DDC_INPUT_REQUIRE(g != option, "option " << option << " given twice ('" << ddc::echoed(target) << "' and '"
                                             << ddc::echoed(value) << "'); give it once");
  given.push_back(option);
  target = value;
  checkOptionValue(option, value);
}

Options parse(const std::vector<std::string>& args) {
  Options o;
  std::vector<std::string> given;  // the options that may be given once, as seen
  const int argc = static_cast<int>(args.size());
  for (int i = 0; i < argc; ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--print-parameters") {
      o.printParameters = true;
    } else if (a == "--set") {
      DDC_INPUT_REQUIRE(i + 1 < argc, "option " << a << " needs a value\n" << kUsage);
      o.sets.push_back(args[++i]);
      checkOptionValue(a, args[i]);
    } else if (a == "--output-dir" || a == "--restart") {
      DDC_INPUT_REQUIRE(i + 1 < argc, "option " << a << " needs a value\n" << kUsage);
      setOnce(a, a == "--restart" ? o.restart : o.outputDir, args[++i], given);
    } else if (a.rfind("--restart=", 0) == 0) {
      setOnce("--restart", o.restart, a.substr(10), given);
    } else if (a.rfind("--output-dir=", 0) == 0) {
      setOnce("--output-dir", o.outputDir, a.substr(13), given);
    } else if (a.rfind("--set=", 0) == 0) {
      o.sets.push_back(a.substr(6));
      checkOptionValue("--set", o.sets.back());
    } else if (!a.empty() && a[0] == '-') {
      DDC_THROW(ddc::InputError, "unknown option '" << a << "'\n" << kUsage);
    } else {
      DDC_INPUT_REQUIRE(o.input.empty(), "only one input file may be given (got '" << o.input << "' and '" << a
                                                                                 << "')");
      o.input = a;
    }
  }
  return o;
}

/// A message of at most about `max` characters: the start and the end of a
/// longer one, with the count left out between them (a 1 MB value given on
/// the command line was repeated in full).
std::string capText(const std::string& text, std::size_t max) {
  if (text.size() <= max) return text;
  const std::size_t head = max * 3 / 4, tail = max / 4;
  return text.substr(0, head) + " [... " + std::to_string(text.size() - head - tail) + " characters left out ...] " +
         text.substr(text.size() - tail);
}

/// Longest message printed (a quoted value is capped by ddc::echoed()).
constexpr std::size_t kMaxMessage = 4000;

/// Every rank runs rank 0's command line. An MPMD launch (`mpirun -np 1
/// ddcontact a.xml : -np 1 ddcontact b.xml`) would otherwise give the ranks
/// different decks, overrides or output directories, and they would wait
/// for each other in different collectives for ever. Rank 0 says so when a
/// rank was started with other arguments.
std::vector<std::string> commandLine(int argc, char** argv, const Teuchos::Comm<int>& comm) {
  const std::vector<std::string> mine(argv + 1, argv + argc);
  std::vector<std::string> args = ddc::broadcastStrings(comm, mine);
  const int differs = args != mine ? comm.getRank() : comm.getSize();
  int firstDiffering = comm.getSize();
  Teuchos::reduceAll<int, int>(comm, Teuchos::REDUCE_MIN, differs, Teuchos::outArg(firstDiffering));
  if (firstDiffering < comm.getSize() && comm.getRank() == 0) {
    std::cerr << "ddcontact: note: rank " << firstDiffering
              << " was started with other arguments than rank 0; every rank runs rank 0's:";
    for (const auto& a : args) std::cerr << " '" << ddc::echoed(a) << "'";
    std::cerr << std::endl;
  }
  return args;
}

int run(const std::vector<std::string>& args, const Teuchos::RCP<const Teuchos::Comm<int>>& comm) {
  const Options o = parse(args);
  if (o.help) {
    if (comm->getRank() == 0) std::cout << kUsage;
    return 0;
  }
  if (o.printParameters) {
    if (comm->getRank() == 0) {
      std::cout << "# DDContact parameters\n\n"
                   "Generated by `ddcontact --print-parameters` from the components' getValidParameters().\n"
                   "Sublists named `<...>` are templates: give them any name (one per body, condition, ...).\n\n";
      ddc::printParameterDoc(*ddc::Analysis::getValidParameters(), std::cout);
    }
    return 0;
  }
  DDC_INPUT_REQUIRE(!o.input.empty(), "no input file given\n" << kUsage);
  // Rank 0 reads and checks the deck, every rank parses the text it broadcasts.
  auto params = ddc::readDeck(*comm, o.input);
  const auto valid = ddc::Analysis::getValidParameters();
  for (const auto& s : o.sets) ddc::applyOverride(*params, *valid, s);

  const std::filesystem::path inputPath(o.input);
  // A restart reads its checkpoint first: continuing in the same directory,
  // opening it would otherwise remove the unfinished run's staging directory.
  std::unique_ptr<ddc::RestartSource> restart;
  if (!o.restart.empty()) restart = std::make_unique<ddc::RestartSource>(ddc::findRestartSource(comm, o.restart));
  const std::string outDir =
      !o.outputDir.empty() ? o.outputDir
      : restart            ? restart->finalPath
                           : (std::filesystem::path("ddcontact-out") / inputPath.stem()).string();
  std::string base = inputPath.parent_path().string();
  if (base.empty()) base = ".";

  std::string command = "ddcontact";
  for (const auto& a : args) command += " " + a;
  std::error_code ec;
  ddc::RunDescription description{std::filesystem::absolute(inputPath, ec).lexically_normal().string(), command, ""};
  if (restart && restart->unfinished && ddc::OutputDirectory::normalisedPath(outDir) == restart->finalPath)
    description.resumeWith = ddc::kCheckpointFileName;
  std::unique_ptr<ddc::Analysis> analysis;
  auto build = [&] {
    analysis = std::make_unique<ddc::Analysis>(comm, *params, ddc::ElementFactory::withBuiltins(), base);
    if (comm->getRank() == 0) {
      const auto& m = analysis->model().mesh();
      std::cout << "ddcontact: " << o.input << ": " << m.numBodies() << " bodies, " << m.numGlobalElements()
                << " elements, " << m.dim() * m.numGlobalNodes() << " DOFs, "
                << analysis->model().partition().numSubdomains << " subdomains on " << comm->getSize()
                << " ranks; estimated memory " << ddc::formatBytes(analysis->memoryEstimate().total()) << " per rank"
                << std::endl;
      const std::string blas = ddc::blasKernelAdvice(ddc::detectBlasKernels());
      if (!blas.empty()) std::cout << "ddcontact: BLAS: " << blas << std::endl;
    }
  };
  // A restart checks the deck against the checkpoint before the output
  // directory is opened: a refused restart leaves the directory it would
  // continue in as it was.
  if (restart) {
    build();
    analysis->setRestart(std::move(*restart));
  }
  // Otherwise the output directory first: a directory in use by another
  // run, or one DDContact did not write, stops the run before any work is
  // done.
  ddc::OutputDirectory dir(comm, outDir, description);
  if (comm->getRank() == 0)
    for (const auto& note : dir.recoveryNotes()) std::cout << "ddcontact: output: " << note << std::endl;
  if (!analysis) build();
  analysis->run(dir);
  return 0;
}

/// Start-up handshake, before the first collective: every rank of the job
/// must be a ddcontact. Each rank other than 0 sends rank 0 a hello and waits
/// for its answer; rank 0 answers once every rank has said hello. A rank that
/// runs another program (an MPMD launch such as `mpirun -np 1 ddcontact D :
/// -np 1 other`) never says hello or answers, and instead of waiting for it
/// for ever in the first collective the job ends after the time-out,
/// DDCONTACT_STARTUP_TIMEOUT seconds (default 60), with a message naming the
/// silent ranks. Returns false (rank 0 printing why) if the time-out set is
/// not a number of seconds: every rank reads the same environment and stops.
bool startupHandshake(MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  double timeout = 60.0;
  if (const char* env = std::getenv("DDCONTACT_STARTUP_TIMEOUT")) {
    char* end = nullptr;
    const double t = std::strtod(env, &end);
    if (end == env || *end != '\0' || !(t > 0.0) || t > 1e6) {
      if (rank == 0)
        std::cerr << "ddcontact: error: environment variable DDCONTACT_STARTUP_TIMEOUT = '"
                  << ddc::echoed(env) << "': expected a number of seconds in (0, 1e6]" << std::endl;
      return false;
    }
    timeout = t;
  }
  if (size == 1) return true;
  constexpr int kTag = 31415;  // below the smallest MPI_TAG_UB MPI allows (32767)
  constexpr int kLength = 32;
  static const char kHello[kLength] = "ddcontact start-up handshake 1";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  // Waits for the requests until done or the deadline; false on time-out.
  auto wait = [&](std::vector<MPI_Request>& requests) {
    int done = 0;
    while (true) {
      MPI_Testall(static_cast<int>(requests.size()), requests.data(), &done, MPI_STATUSES_IGNORE);
      if (done) return true;
      if (std::chrono::steady_clock::now() > deadline) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  };
  const char* hint =
      "; every rank of the job must run ddcontact (an MPMD launch that starts another program on some ranks is not "
      "supported; DDCONTACT_STARTUP_TIMEOUT sets the time-out for slow starts)";
  if (rank == 0) {
    std::vector<std::array<char, kLength>> hello(size - 1);
    std::vector<MPI_Request> requests(size - 1);
    for (int r = 1; r < size; ++r) MPI_Irecv(hello[r - 1].data(), kLength, MPI_CHAR, r, kTag, comm, &requests[r - 1]);
    const bool all = wait(requests);
    std::ostringstream silent, foreign;
    for (int r = 1; r < size; ++r) {
      if (requests[r - 1] != MPI_REQUEST_NULL) {
        int done = 0;
        MPI_Test(&requests[r - 1], &done, MPI_STATUS_IGNORE);
        if (!done) {
          silent << (silent.tellp() > 0 ? ", " : "") << r;
          continue;
        }
      }
      if (std::string(hello[r - 1].data(), strnlen(hello[r - 1].data(), kLength)) != kHello)
        foreign << (foreign.tellp() > 0 ? ", " : "") << r;
    }
    if (!all || foreign.tellp() > 0) {
      std::cerr << "ddcontact: error: the start-up handshake ";
      if (silent.tellp() > 0) std::cerr << "heard nothing from rank(s) " << silent.str() << " within " << timeout << " s";
      if (silent.tellp() > 0 && foreign.tellp() > 0) std::cerr << ", and ";
      if (foreign.tellp() > 0) std::cerr << "got another program's message from rank(s) " << foreign.str();
      std::cerr << hint << std::endl;
      MPI_Abort(comm, 1);
    }
    std::vector<MPI_Request> answers(size - 1);
    for (int r = 1; r < size; ++r) MPI_Isend(kHello, kLength, MPI_CHAR, r, kTag, comm, &answers[r - 1]);
    MPI_Waitall(size - 1, answers.data(), MPI_STATUSES_IGNORE);
    return true;
  } else {
    std::array<char, kLength> answer{};
    std::vector<MPI_Request> requests(2);
    MPI_Isend(kHello, kLength, MPI_CHAR, 0, kTag, comm, &requests[0]);
    MPI_Irecv(answer.data(), kLength, MPI_CHAR, 0, kTag, comm, &requests[1]);
    if (!wait(requests) || std::string(answer.data(), strnlen(answer.data(), kLength)) != kHello) {
      std::cerr << "ddcontact: error on rank " << rank << ": the start-up handshake heard nothing from rank 0 within "
                << timeout << " s" << hint << std::endl;
      MPI_Abort(comm, 1);
    }
    return true;
  }
}

/// After an exception: if every rank failed (input errors are detected
/// identically on all ranks) they meet in a barrier and exit cleanly, rank 0
/// printing the message. If only some ranks failed, the others are stuck in
/// a collective: abort the job so that nothing hangs.
int fail(const std::string& fullMessage, MPI_Comm comm, const char* label = "error") {
  const std::string msg = capText(fullMessage, kMaxMessage);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  MPI_Request req;
  MPI_Ibarrier(comm, &req);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  int done = 0;
  while (!done && std::chrono::steady_clock::now() < deadline) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (!done) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (done) {
    if (rank == 0) std::cerr << "ddcontact: " << label << (*label ? ": " : "") << msg << std::endl;
    return 1;
  }
  std::cerr << "ddcontact: error on rank " << rank << ": " << msg << std::endl;
  MPI_Abort(comm, 1);
  return 1;
}

/// The message of a failed allocation `what` ("std::bad_alloc", or what
/// Kokkos said): the activity (with its sizes) and this rank's peak.
std::string outOfMemory(const std::string& what) {
  return "out of memory (" + what + ") while " + ddc::currentActivity() + "; this rank's peak was " +
         ddc::formatBytes(ddc::peakResidentBytes()) +
         " (doc/user-guide.md, 'Memory': refine less, or run on more ranks or hosts; with 'Solver/Memory Check' "
         "= false nothing was checked before)";
}

/// Kokkos' message from "Kokkos failed to allocate" on, its whitespace
/// runs made single blanks and cut after the requested size.
std::string kokkosAllocation(const std::string& text) {
  std::string out;
  for (char c : text) {
    const bool blank = std::isspace(static_cast<unsigned char>(c));
    if (blank && (out.empty() || out.back() == ' ')) continue;
    out += blank ? ' ' : c;
    if (out.size() > 400) break;
  }
  const auto failed = out.find(" failed, ");
  if (failed != std::string::npos && failed > 30) out.resize(failed + 7);
  while (!out.empty() && (out.back() == ' ' || out.back() == '.' || out.back() == ',')) out.pop_back();
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  ddc::MpiSession mpi(&argc, &argv);  // MPI_THREAD_MULTIPLE (PT-Scotch), before Tpetra
  Tpetra::ScopeGuard scope(&argc, &argv);
  // Before the first collective (Teuchos::MpiComm's constructor has one).
  if (!startupHandshake(MPI_COMM_WORLD)) return 1;
  auto comm = Tpetra::getDefaultComm();
  int status = 0;
  std::string msg;
  int stopSignal = 0;
  // SIGTERM / SIGINT / SIGUSR1: stop after the current step, with a checkpoint.
  ddc::installStopHandlers();
  if (ddc::faultInjectionActive() && comm->getRank() == 0)
    std::cerr << "ddcontact: test fault injection active: DDCONTACT_FAULT_INJECTION="
              << std::getenv("DDCONTACT_FAULT_INJECTION") << std::endl;
  try {
    status = run(commandLine(argc, argv, *comm), comm);
  } catch (const ddc::RunInterrupted& e) {
    msg = e.what();
    stopSignal = e.signal();
  } catch (const ddc::InputError& e) {
    msg = e.what();
  } catch (const ddc::SolverError& e) {
    msg = std::string("solver failure: ") + e.what();
  } catch (const ddc::OutputError& e) {
    msg = std::string("output: ") + e.what() + " (earlier results are untouched)";
  } catch (const std::bad_alloc&) {
    msg = outOfMemory("std::bad_alloc");
  } catch (const std::exception& e) {
    msg = std::string("unexpected: ") + e.what();
  }
  // Kokkos reports a failed allocation as a std::runtime_error (which a
  // solver may wrap in its own failure): out of memory as well.
  const auto kokkos = msg.find("Kokkos failed to allocate");
  if (kokkos != std::string::npos) msg = outOfMemory(kokkosAllocation(msg.substr(kokkos)));
  // A stop exits with 128 + the signal, as a shell reports a process the
  // signal ended.
  if (stopSignal) status = fail(msg, MPI_COMM_WORLD, "") == 0 ? 0 : 128 + stopSignal;
  else if (!msg.empty()) status = fail(msg, MPI_COMM_WORLD);
  return status;
}
