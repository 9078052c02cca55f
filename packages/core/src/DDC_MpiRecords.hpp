// Small MPI helpers shared by the packages: the raw communicator behind a
// Teuchos communicator, a variable-size all-to-all of plain records, and
// agreeing on an error found on some ranks (anyRank, firstErrorOnAnyRank,
// raiseCollectively).
#pragma once

#include <mpi.h>

#include <Teuchos_Comm.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <climits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace ddc {

/// The raw MPI communicator behind a Teuchos communicator (MPI_COMM_SELF for
/// a Teuchos::SerialComm).
inline MPI_Comm rawComm(const Teuchos::Comm<int>& comm) {
  const auto* mpi = dynamic_cast<const Teuchos::MpiComm<int>*>(&comm);
  if (mpi == nullptr) return MPI_COMM_SELF;
  return *mpi->getRawMpiComm();
}
inline MPI_Comm rawComm(const Teuchos::RCP<const Teuchos::Comm<int>>& comm) {
  return comm.is_null() ? MPI_COMM_SELF : rawComm(*comm);
}

/// This rank in `comm`, and the number of ranks of `comm`.
inline int commRank(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}
inline int commSize(MPI_Comm comm) {
  int s = 1;
  MPI_Comm_size(comm, &s);
  return s;
}

/// Rank `rank`'s even share of `count` items over `ranks` ranks in rank
/// order starts at evenShareStart(count, rank, ranks) and ends where the
/// next rank's starts; this rank's share of `comm` is evenShare().
inline long long evenShareStart(long long count, int rank, int ranks) { return count * rank / ranks; }
inline std::pair<long long, long long> evenShare(long long count, MPI_Comm comm) {
  const int rank = commRank(comm), ranks = commSize(comm);
  return {evenShareStart(count, rank, ranks), evenShareStart(count, rank + 1, ranks)};
}

/// Variable-size all-to-all of trivially copyable records: send[r] goes to
/// rank r; returns everything received, ordered by source rank. Collective.
template <class T>
std::vector<T> exchangeRecords(MPI_Comm comm, const std::vector<std::vector<T>>& send) {
  static_assert(std::is_trivially_copyable<T>::value, "exchangeRecords() sends raw bytes");
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::vector<int> sc(size), rc(size), sd(size, 0), rd(size, 0);
  for (int r = 0; r < size; ++r) sc[r] = static_cast<int>(send[r].size() * sizeof(T));
  MPI_Alltoall(sc.data(), 1, MPI_INT, rc.data(), 1, MPI_INT, comm);
  for (int r = 1; r < size; ++r) {
    sd[r] = sd[r - 1] + sc[r - 1];
    rd[r] = rd[r - 1] + rc[r - 1];
  }
  std::vector<T> sendBuf;
  sendBuf.reserve((sd[size - 1] + sc[size - 1]) / sizeof(T));
  for (int r = 0; r < size; ++r) sendBuf.insert(sendBuf.end(), send[r].begin(), send[r].end());
  std::vector<T> recv((rd[size - 1] + rc[size - 1]) / sizeof(T));
  // Never pass null buffers to MPI.
  T dummy{};
  MPI_Alltoallv(sendBuf.empty() ? &dummy : sendBuf.data(), sc.data(), sd.data(), MPI_BYTE,
                recv.empty() ? &dummy : recv.data(), rc.data(), rd.data(), MPI_BYTE, comm);
  return recv;
}

/// Every rank's records on every rank, ordered by source rank. Collective.
template <class T>
std::vector<T> allGather(MPI_Comm comm, const std::vector<T>& mine) {
  return exchangeRecords(comm, std::vector<std::vector<T>>(size_t(commSize(comm)), mine));
}

/// The starts of the ranks' ranges [first, last) in rank order and the end
/// of the last (P + 1 values), on every rank. Collective.
/// \throws std::logic_error naming `who` if a range does not start where
///         the one of the rank before it ends
inline std::vector<long long> contiguousRangeStarts(long long first, long long last, MPI_Comm comm,
                                                    const std::string& who) {
  const std::vector<long long> firsts = allGather(comm, std::vector<long long>{first});
  const std::vector<long long> lasts = allGather(comm, std::vector<long long>{last});
  for (size_t r = 0; r + 1 < firsts.size(); ++r)
    if (lasts[r] != firsts[r + 1]) throw std::logic_error(who + ": the ranges are not contiguous in rank order");
  std::vector<long long> starts = firsts;
  starts.push_back(lasts.back());
  return starts;
}

/// Logical OR of `bad` over the communicator, so that all ranks agree to
/// throw. Collective.
inline bool anyRank(MPI_Comm comm, bool bad) {
  int mine = bad ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm);
  return any != 0;
}

/// The `localError` of the lowest rank where it is non-empty, on every rank;
/// "" when it is empty everywhere. Collective: an error found on one rank
/// must reach all ranks, never leave the others waiting in a collective.
inline std::string firstErrorOnAnyRank(MPI_Comm comm, const std::string& localError) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  int mine = localError.empty() ? INT_MAX : rank, first = INT_MAX;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == INT_MAX) return std::string();
  int len = rank == first ? static_cast<int>(localError.size()) : 0;
  MPI_Bcast(&len, 1, MPI_INT, first, comm);
  std::string text = rank == first ? localError : std::string(static_cast<size_t>(len), ' ');
  MPI_Bcast(&text[0], len, MPI_CHAR, first, comm);
  return text;
}
inline std::string firstErrorOnAnyRank(const Teuchos::Comm<int>& comm, const std::string& localError) {
  return firstErrorOnAnyRank(rawComm(comm), localError);
}

/// If `msg` is non-empty on any rank, throw E on every rank with the message
/// of the lowest such rank (firstErrorOnAnyRank()).
template <class E>
void raiseCollectively(MPI_Comm comm, const std::string& msg) {
  const std::string text = firstErrorOnAnyRank(comm, msg);
  if (!text.empty()) throw E(text);
}

/// Runs `step` on every rank; an E that it throws on some ranks is thrown
/// on all, with the message of the lowest such rank (raiseCollectively()).
/// Collective: `step` itself must not call collectives that an E could
/// leave some ranks waiting in.
template <class E, class Step>
void runCollectively(MPI_Comm comm, const Step& step) {
  std::string error;
  try {
    step();
  } catch (const E& e) {
    error = e.what();
  }
  raiseCollectively<E>(comm, error);
}

}  // namespace ddc
