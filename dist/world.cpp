#include "dist/world.h"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <new>

#include "core/error.h"

#ifdef ISOCURV_HAVE_MPI
#include <mpi.h>
#endif

namespace isocurv::dist {
namespace {

World& instance() {
  static World w;
  return w;
}

// Whether a launcher started this process: OpenMPI's mpirun, PMIx (OpenMPI 4+, Slurm), MPICH's
// Hydra (PMI).
bool started_by_launcher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

}  // namespace

World& World::get() { return instance(); }

#ifdef ISOCURV_HAVE_MPI

void World::init(int& argc, char**& argv) {
  World& w = instance();
  if (w.initialised_ || !started_by_launcher()) return;
  int provided = 0;
  // The ranks' own threads (TBB, the batch writer) never call MPI.
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    throw Error("MPI could not be initialised (started by mpirun?)");
  // Errors come back as codes, not as MPI's own abort; a failing collective becomes one Error.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, &w.rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &w.size_);
  w.launched_ = w.initialised_ = true;
}

void World::finalize() {
  World& w = instance();
  if (!w.initialised_) return;
  w.initialised_ = false;
  MPI_Finalize();
}

namespace {
void check(int code, const char* what) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(code, text, &len);
  throw Error(std::string("MPI ") + what + " failed: " + std::string(text, std::size_t(len)));
}
}  // namespace

std::string World::agree(const std::string& error) const {
  if (!initialised_) return error;
  // The lowest failing rank (size_ when none), then its message.
  int mine = error.empty() ? size_ : rank_, first = size_;
  check(MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD), "allreduce");
  if (first == size_) return "";
  int failed = error.empty() ? 0 : 1, failing = 0;
  check(MPI_Allreduce(&failed, &failing, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD), "allreduce");
  std::vector<char> text;
  if (rank_ == first) text.assign(error.begin(), error.end());
  text = broadcast(std::move(text), first);
  const std::string message(text.begin(), text.end());
  // Named by rank only when some ranks failed and others did not (a bad file fails them all).
  return failing < size_ ? "rank " + std::to_string(first) + ": " + message : message;
}

namespace {
// Element-wise MPI_Allreduce of `values` (one length on every rank).
template <class T>
std::vector<T> all_reduce(const std::vector<T>& values, MPI_Datatype type, MPI_Op op) {
  std::vector<T> out(values.size());
  check(MPI_Allreduce(values.data(), out.data(), int(values.size()), type, op, MPI_COMM_WORLD), "allreduce");
  return out;
}
}  // namespace

std::vector<double> World::sum(const std::vector<double>& values) const {
  return !initialised_ || values.empty() ? values : all_reduce(values, MPI_DOUBLE, MPI_SUM);
}

std::vector<std::int64_t> World::sum(const std::vector<std::int64_t>& values) const {
  return !initialised_ || values.empty() ? values : all_reduce(values, MPI_INT64_T, MPI_SUM);
}

std::vector<double> World::max(const std::vector<double>& values) const {
  return !initialised_ || values.empty() ? values : all_reduce(values, MPI_DOUBLE, MPI_MAX);
}

std::vector<std::vector<char>> World::gather(const std::vector<char>& bytes, int root) const {
  if (!initialised_) return {bytes};
  // Sizes first (64-bit), then the bytes in chunks below 2 GiB per rank.
  const std::int64_t mine = std::int64_t(bytes.size());
  std::vector<std::int64_t> sizes(rank_ == root ? std::size_t(size_) : 0);
  check(MPI_Gather(&mine, 1, MPI_INT64_T, sizes.data(), 1, MPI_INT64_T, root, MPI_COMM_WORLD), "gather");
  std::vector<std::vector<char>> out(sizes.size());
  constexpr int kTag = 7411;
  if (rank_ == root) {
    for (int r = 0; r < size_; ++r) {
      out[r].resize(std::size_t(sizes[r]));
      if (r == root) {
        out[r] = bytes;
        continue;
      }
      for (std::int64_t at = 0; at < sizes[r];) {
        const int n = int(std::min<std::int64_t>(sizes[r] - at, 1 << 30));
        check(MPI_Recv(out[r].data() + at, n, MPI_CHAR, r, kTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "receive");
        at += n;
      }
    }
  } else {
    for (std::int64_t at = 0; at < mine;) {
      const int n = int(std::min<std::int64_t>(mine - at, 1 << 30));
      check(MPI_Send(bytes.data() + at, n, MPI_CHAR, root, kTag, MPI_COMM_WORLD), "send");
      at += n;
    }
  }
  return out;
}

std::vector<char> World::broadcast(std::vector<char> bytes, int root) const {
  if (!initialised_) return bytes;
  std::int64_t n = std::int64_t(bytes.size());
  check(MPI_Bcast(&n, 1, MPI_INT64_T, root, MPI_COMM_WORLD), "broadcast");
  bytes.resize(std::size_t(n));
  for (std::int64_t at = 0; at < n;) {
    const int k = int(std::min<std::int64_t>(n - at, 1 << 30));
    check(MPI_Bcast(bytes.data() + at, k, MPI_CHAR, root, MPI_COMM_WORLD), "broadcast");
    at += k;
  }
  return bytes;
}

void World::barrier() const {
  if (initialised_) check(MPI_Barrier(MPI_COMM_WORLD), "barrier");
}

SharedCounter::SharedCounter(const World& world) : mpi_(world.size() > 1) {
  if (!mpi_) return;
  std::int64_t* base = nullptr;
  MPI_Win win;
  const MPI_Aint bytes = world.rank() == 0 ? sizeof(std::int64_t) : 0;
  check(MPI_Win_allocate(bytes, sizeof(std::int64_t), MPI_INFO_NULL, MPI_COMM_WORLD, &base, &win), "window");
  if (world.rank() == 0) *base = 0;
  window_ = new MPI_Win(win);
  check(MPI_Win_lock_all(0, win), "window lock");
  MPI_Barrier(MPI_COMM_WORLD);  // rank 0's zero is in place before anyone draws
}

SharedCounter::~SharedCounter() {
  if (!mpi_) return;
  auto* win = static_cast<MPI_Win*>(window_);
  MPI_Win_unlock_all(*win);
  MPI_Win_free(win);
  delete win;
}

std::int64_t SharedCounter::draw() {
  if (!mpi_) return local_++;
  MPI_Win win = *static_cast<MPI_Win*>(window_);
  const std::int64_t one = 1;
  std::int64_t got = 0;
  check(MPI_Fetch_and_op(&one, &got, MPI_INT64_T, 0, 0, MPI_SUM, win), "fetch-and-add");
  check(MPI_Win_flush(0, win), "window flush");
  return got;
}

#else  // built without MPI: always the one process

SharedCounter::SharedCounter(const World&) {}
SharedCounter::~SharedCounter() {}
std::int64_t SharedCounter::draw() { return local_++; }

void World::init(int&, char**&) {
  if (started_by_launcher())
    throw Error("this isocurv was built without MPI, so it cannot run under mpirun (install libopenmpi-dev and rebuild)");
}
void World::finalize() {}
std::string World::agree(const std::string& error) const { return error; }
std::vector<double> World::sum(const std::vector<double>& values) const { return values; }
std::vector<std::int64_t> World::sum(const std::vector<std::int64_t>& values) const { return values; }
std::vector<double> World::max(const std::vector<double>& values) const { return values; }
std::vector<std::vector<char>> World::gather(const std::vector<char>& bytes, int) const { return {bytes}; }
std::vector<char> World::broadcast(std::vector<char> bytes, int) const { return bytes; }
void World::barrier() const {}

#endif

std::string guarded(const std::function<void()>& work) {
  try {
    work();
    return "";
  } catch (const std::bad_alloc&) {
    return "out of memory";
  } catch (const std::exception& e) {
    const std::string m = one_line(e.what());
    return m.empty() ? "failed" : m;
  } catch (...) {
    return "failed";
  }
}

void together(const World& world, const std::function<void()>& work) {
  std::string agreed;  // set when a collective inside `work` learnt of another rank's failure
  const std::string mine = guarded([&] {
    try {
      work();
    } catch (const AgreedFailure& e) {
      agreed = e.what();
    }
  });
  if (!agreed.empty()) throw Error(agreed);
  const std::string error = world.agree(mine);
  if (!error.empty()) throw Error(error);
}

void check_peers(const World& world) {
  const std::string error = world.agree("");
  if (!error.empty()) throw AgreedFailure(error);
}

}  // namespace isocurv::dist
