#pragma once
// The processes of one run. Under mpirun (OpenMPI, or any launcher that sets the PMI/PMIx
// environment) they are MPI's COMM_WORLD; otherwise this process alone, and MPI is never
// initialised, so a plain `isocurv extract` neither needs nor pays for the MPI runtime.
//
// Every collective here must be called by all ranks in the same order. Work that may fail on some
// ranks only is wrapped so that each rank reaches the next agree() with its error as a string
// (dist::guarded), never with an exception in flight: a rank that threw past a collective would
// leave the others waiting for ever.
// Tested in tests/app/test_extract_curvature.cpp (through its users).
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace isocurv::dist {

class World {
 public:
  /// Initialises MPI (once, from main) when this process was started by a launcher; a no-op
  /// otherwise. @throw Error when it was, but this build has no MPI (each process would think it
  /// is alone and write the same files).
  static void init(int& argc, char**& argv);
  /// The world (a one-process world when not launched by mpirun).
  static World& get();
  /// Finalises MPI when init started it (from main, after the command).
  static void finalize();

  int rank() const { return rank_; }
  int size() const { return size_; }
  /// True when started by a launcher, even `mpirun -np 1`.
  bool launched() const { return launched_; }

  /// Collective. Each rank passes its error ("" when it succeeded); every rank gets back the
  /// lowest failing rank's error, or "" when none failed; prefixed "rank K: " when only some
  /// ranks failed.
  std::string agree(const std::string& error) const;
  /// Collective element-wise sums (the vectors have one length on every rank).
  std::vector<double> sum(const std::vector<double>& values) const;
  std::vector<std::int64_t> sum(const std::vector<std::int64_t>& values) const;
  /// Collective element-wise maxima.
  std::vector<double> max(const std::vector<double>& values) const;
  /// Collective: every rank's bytes at `root`, one vector per rank in rank order (an empty list
  /// on the other ranks).
  std::vector<std::vector<char>> gather(const std::vector<char>& bytes, int root = 0) const;
  /// Collective: `root`'s bytes on every rank.
  std::vector<char> broadcast(std::vector<char> bytes, int root = 0) const;
  void barrier() const;

 private:
  int rank_ = 0, size_ = 1;
  bool launched_ = false, initialised_ = false;
};

/// A counter every rank draws from, 0, 1, 2, ... in the order the draws arrive, for handing out
/// work as ranks become free (mpirun with a batch of files). Held by rank 0 in an MPI window and
/// drawn with one-sided atomics, so drawing never waits for rank 0 to finish what it is doing.
/// Construction and destruction are collective; draw() is not.
class SharedCounter {
 public:
  explicit SharedCounter(const World& world);
  ~SharedCounter();
  SharedCounter(const SharedCounter&) = delete;
  SharedCounter& operator=(const SharedCounter&) = delete;
  /// The next number (each handed out once over all ranks).
  std::int64_t draw();

 private:
  bool mpi_ = false;
  std::int64_t local_ = 0;  ///< the count when there is no MPI world
  void* window_ = nullptr;  ///< MPI_Win, when mpi_
};

/// Runs `work`, returning "" or the one-line message of what it threw (Error, std::exception,
/// bad_alloc as "out of memory"), so that the caller reaches its next agree() either way.
std::string guarded(const std::function<void()>& work);

/// agree(guarded(work)): throws Error with the agreed message on every rank when any rank's
/// `work` failed (main() prints errors on rank 0 only; every rank exits with status 1).
/// `work` may itself call collectives (the estimators' reductions, core/surface_piece.h) when
/// each starts with check_peers: a rank that failed before one meets the others there.
void together(const World& world, const std::function<void()>& work);

/// Thrown by check_peers: another rank's work failed, and every rank already knows (together()
/// passes it on as an Error without agreeing again).
struct AgreedFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Collective, for collectives inside together()'s work: agree("") with the other ranks, whose
/// failed work's agree() this meets; throws AgreedFailure with the failing rank's message.
void check_peers(const World& world);

}  // namespace isocurv::dist
