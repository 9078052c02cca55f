// Reading an input deck (a Teuchos XML parameter list) strictly, and the
// same on every rank.
//
// Teuchos::getParametersFromXmlFile() is lenient: it reads "3abc" as the int
// 3, "2.9" as the int 2, "abc" as the double 0, 99999999999 as a wrapped-
// around int, and keeps the last of two parameters with the same name in one
// list. parseDeck() reads a deck in four steps instead (after skipping a
// UTF-8 byte-order mark and refusing UTF-16 / UTF-32 text by name):
//  1. a lexical pre-scan refuses elements nested deeper than kMaxDeckDepth,
//     before Teuchos builds anything: its XML parser is iterative, but the
//     tree it builds is destroyed, converted to a ParameterList and copied
//     recursively, one stack frame (or several) per level, so 100000 nested
//     lists overflow the stack;
//  2. Teuchos' XML parser builds the XMLObject tree (malformed XML is an
//     InputError naming the file);
//  3. the tree is checked: every <Parameter> has a name, one of the types
//     parseValue() reads (int, double, bool, string) and a value that parses
//     as that type as a whole (the rule --set uses: ddc::parseValue()); no
//     two entries of one <ParameterList> share a name;
//  4. Teuchos::XMLParameterListReader converts the tree.
// Every message names the file, the parameter path and the offending text.
//
// readDeck() is collective: rank 0 reads and checks the file and broadcasts
// its text, every rank parses that text, so no two ranks can disagree about
// a parameter (and a file visible to rank 0 only is enough).
#pragma once

#include <Teuchos_Comm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace ddc {

/// Deepest element nesting of a deck (the root <ParameterList> is level 1,
/// a <Parameter> in it level 2). DDContact's deepest valid parameter path
/// (a FROSch option) is at level 11; the decks in examples/ reach level 7.
constexpr int kMaxDeckDepth = 32;

/// Largest deck file read, in bytes (decks are a few KiB; the limit keeps
/// the broadcast of the text within one MPI message count).
constexpr std::size_t kMaxDeckBytes = std::size_t(64) << 20;

/// Result of maxElementDepth().
struct ElementDepth {
  int depth = 0;  ///< deepest element level seen (0: no element)
  int line = 0;   ///< line (1-based) of the first element at that level
};

/// Deepest element nesting of the XML `text`, found lexically (comments,
/// CDATA sections, processing instructions, declarations and quoted
/// attribute values are skipped; malformed text is scanned as far as it
/// goes, the XML parser reports it). Stops at the first element deeper than
/// `limit`, so the scan is linear and cheap whatever the nesting.
ElementDepth maxElementDepth(const std::string& text, int limit);

/// Parse the deck `text` strictly (steps 1-4 of the file comment). Not
/// collective.
/// \param fileName the deck's file name, for messages.
/// \return the parameters, as Teuchos::XMLParameterListReader reads them.
/// \throws InputError naming `fileName`: text that is not UTF-8 (UTF-16,
///         UTF-32, NUL bytes; a UTF-8 byte-order mark is skipped), nesting
///         deeper than kMaxDeckDepth,
///         malformed XML ("input file 'X' is not a valid Teuchos XML
///         parameter list: ..."), an element other than <ParameterList> /
///         <Parameter>, a missing name, type or value, an unsupported type, a
///         value that does not parse as its type (with the parameter path and
///         the text), a name given twice in one list.
Teuchos::RCP<Teuchos::ParameterList> parseDeck(const std::string& text, const std::string& fileName);

/// Read the deck file `fileName` (not collective).
/// \throws InputError "input file 'X' does not exist", "... is a directory,
///         expected a Teuchos XML parameter file", "... is not a regular
///         file", larger than kMaxDeckBytes, or cannot be read.
std::string readDeckFile(const std::string& fileName);

/// Collective. Rank 0 reads `fileName` (readDeckFile()) and checks it
/// (parseDeck()); an error there is raised as the same InputError on every
/// rank. Otherwise rank 0 broadcasts the text and every rank parses it.
/// \return the parameters (the same on every rank).
Teuchos::RCP<Teuchos::ParameterList> readDeck(const Teuchos::Comm<int>& comm, const std::string& fileName);

/// Collective. Rank 0's `strings` on every rank (the argument is ignored on
/// the other ranks).
std::vector<std::string> broadcastStrings(const Teuchos::Comm<int>& comm, const std::vector<std::string>& strings);

/// A file a run read: the parameter naming it, its name as read, its size
/// in bytes and the FNV-1a fingerprint of its content.
struct InputFileIdentity {
  std::string parameter, file;
  std::uint64_t size = 0, hash = 0;
};

/// The files the Analysis parameters name, as (parameter path, file name
/// resolved as the readers resolve it): "Mesh/Bodies/<Body>/Gmsh/File" of
/// every Gmsh body and "Partition/Element Map File" with Method = Element Map
/// File. Entries of the wrong type or empty are skipped (validation reports
/// them).
/// \param baseDirectory the directory relative names are resolved in.
std::vector<std::pair<std::string, std::string>> namedInputFiles(const Teuchos::ParameterList& params,
                                                                 const std::string& baseDirectory);

/// Collective. Every rank reads each file of `files` (parameter path, file
/// name) itself; this checks first that all ranks can: a file readable on
/// some ranks only, or with different contents on different ranks, is an
/// InputError on every rank naming the parameter, the file and the ranks,
/// rather than some ranks failing alone (MPI_Abort) or building different
/// meshes (a hang). A file no rank can read is left to its reader, whose
/// message is then the same on every rank.
/// \return what was read of each file every rank read: its size and
///         content fingerprint, the same on every rank (a checkpoint records
///         them, so that a restart notices a changed file)
std::vector<InputFileIdentity> requireSameFilesOnEveryRank(
    const Teuchos::Comm<int>& comm, const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace ddc
