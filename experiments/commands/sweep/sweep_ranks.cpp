// SweepRanks (sweep_ranks.hpp), compiled twice: with LGI_WITH_MPI=0 (one rank,
// no MPI) into lgi_experiments, and with LGI_WITH_MPI=1 into an MPI build of lgi
// (and the lgi-mpi test executable), where it takes the place of the library's
// (experiments/CMakeLists.txt). Both variants define the same symbols.
#include "experiments/commands/sweep/sweep_ranks.hpp"

#ifndef LGI_WITH_MPI
#define LGI_WITH_MPI 0  // the library's build
#endif

#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <list>
#include <stdexcept>
#include <string>

#if LGI_WITH_MPI
#include <mpi.h>
#endif

namespace lgi::experiments {

namespace {
int environment_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v ? std::atoi(v) : fallback;
}
}  // namespace

int SweepRanks::default_threads() const {
  const int local = std::max(1, environment_int("OMPI_COMM_WORLD_LOCAL_SIZE", 1));
  return std::max(1, omp_get_num_procs() / (size_ > 1 ? local : 1));
}

SweepRanks& SweepRanks::world() {
  static SweepRanks ranks;
  return ranks;
}

#if LGI_WITH_MPI

namespace {
constexpr int tag_chunk = 1, tag_done = 2;
void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}
}  // namespace

struct SweepRanks::Mpi {
  MPI_Win counter_window = MPI_WIN_NULL;
  std::int64_t* counter = nullptr;
  struct Pending {
    MPI_Request request;
    std::vector<char> bytes;
  };
  std::list<Pending> sends;
  void reap(bool wait) {
    for (auto it = sends.begin(); it != sends.end();) {
      int done = 0;
      if (wait) MPI_Wait(&it->request, MPI_STATUS_IGNORE), done = 1;
      else MPI_Test(&it->request, &done, MPI_STATUS_IGNORE);
      it = done ? sends.erase(it) : std::next(it);
    }
  }
};

SweepRanks::SweepRanks() {
  // Launched by mpirun (OpenMPI's environment): join the world. Otherwise one
  // rank, without MPI_Init (no singleton start-up).
  if (!std::getenv("OMPI_COMM_WORLD_SIZE") && !std::getenv("PMIX_RANK")) return;
  int provided = 0;
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided), "MPI_Init_thread");
  if (provided < MPI_THREAD_SERIALIZED) throw std::runtime_error("MPI: MPI_THREAD_SERIALIZED is not available");
  mpi_ = new Mpi;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

SweepRanks::~SweepRanks() {
  if (!mpi_) return;
  if (mpi_->counter_window != MPI_WIN_NULL) {
    MPI_Win_unlock_all(mpi_->counter_window);
    MPI_Win_free(&mpi_->counter_window);
  }
  delete mpi_;
  MPI_Finalize();
}

std::int64_t SweepRanks::broadcast(std::int64_t value) {
  if (mpi_) check(MPI_Bcast(&value, 1, MPI_INT64_T, 0, MPI_COMM_WORLD), "MPI_Bcast");
  return value;
}

void SweepRanks::broadcast(std::vector<char>& bytes) {
  if (!mpi_) return;
  std::int64_t n = broadcast(static_cast<std::int64_t>(bytes.size()));
  bytes.resize(static_cast<std::size_t>(n));
  check(MPI_Bcast(bytes.data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD), "MPI_Bcast");
}

void SweepRanks::start_counter() {
  local_counter_ = 0;
  if (!mpi_) return;
  check(MPI_Win_allocate(root() ? static_cast<MPI_Aint>(sizeof(std::int64_t)) : 0, sizeof(std::int64_t),
                         MPI_INFO_NULL, MPI_COMM_WORLD, &mpi_->counter, &mpi_->counter_window),
        "MPI_Win_allocate");
  if (root()) *mpi_->counter = 0;
  MPI_Barrier(MPI_COMM_WORLD);
  check(MPI_Win_lock_all(0, mpi_->counter_window), "MPI_Win_lock_all");
}

std::int64_t SweepRanks::claim_chunk() {
  if (!mpi_) return local_counter_++;
  const std::int64_t one = 1;
  std::int64_t previous = 0;
  check(MPI_Fetch_and_op(&one, &previous, MPI_INT64_T, 0, 0, MPI_SUM, mpi_->counter_window), "MPI_Fetch_and_op");
  check(MPI_Win_flush(0, mpi_->counter_window), "MPI_Win_flush");
  return previous;
}

void SweepRanks::send_chunk(const SweepChunk& chunk) {
  mpi_->reap(false);
  mpi_->sends.push_back({MPI_REQUEST_NULL, pack_chunk(chunk)});
  auto& s = mpi_->sends.back();
  check(MPI_Isend(s.bytes.data(), static_cast<int>(s.bytes.size()), MPI_CHAR, 0, tag_chunk, MPI_COMM_WORLD,
                  &s.request),
        "MPI_Isend");
}

bool SweepRanks::receive_chunk(SweepChunk& chunk) {
  if (!mpi_ || size_ == 1) return false;
  for (;;) {
    int arrived = 0;
    MPI_Status status;
    check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status), "MPI_Iprobe");
    if (!arrived) return false;
    int count = 0;
    MPI_Get_count(&status, MPI_CHAR, &count);
    std::vector<char> bytes(static_cast<std::size_t>(count));
    check(MPI_Recv(bytes.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE),
          "MPI_Recv");
    if (status.MPI_TAG == tag_chunk) {
      chunk = unpack_chunk(bytes);
      return true;
    }
    // tag_done: the sender's CPU seconds and crossings; its chunks came before (non-overtaking).
    double cpu = 0.0;
    std::int64_t events = 0;
    std::memcpy(&cpu, bytes.data(), sizeof cpu);
    std::memcpy(&events, bytes.data() + sizeof cpu, sizeof events);
    others_cpu_ += cpu;
    others_events_ += events;
    ++finished_;
  }
}

void SweepRanks::finish(double cpu_seconds, std::int64_t events) {
  if (!mpi_ || root()) return;
  mpi_->reap(true);
  char bytes[sizeof(double) + sizeof(std::int64_t)];
  std::memcpy(bytes, &cpu_seconds, sizeof cpu_seconds);
  std::memcpy(bytes + sizeof cpu_seconds, &events, sizeof events);
  check(MPI_Send(bytes, sizeof bytes, MPI_CHAR, 0, tag_done, MPI_COMM_WORLD), "MPI_Send");
}

std::vector<double> SweepRanks::gather(const std::vector<double>& mine) {
  if (!mpi_) return mine;
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size_)), offsets(static_cast<std::size_t>(size_));
  check(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Gather");
  std::vector<double> all;
  if (root()) {
    std::size_t total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) offsets[r] = static_cast<int>(total), total += static_cast<std::size_t>(counts[r]);
    all.resize(total);
  }
  check(MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, 0,
                    MPI_COMM_WORLD),
        "MPI_Gatherv");
  return all;
}

bool SweepRanks::any(bool flag) {
  if (!mpi_) return flag;
  int mine = flag ? 1 : 0, all = 0;
  check(MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce");
  return all != 0;
}

void SweepRanks::abort(int status) {
  if (mpi_) MPI_Abort(MPI_COMM_WORLD, status);
  std::exit(status);
}

#else  // one rank, no MPI

struct SweepRanks::Mpi {};
SweepRanks::SweepRanks() = default;
SweepRanks::~SweepRanks() = default;
std::int64_t SweepRanks::broadcast(std::int64_t value) { return value; }
void SweepRanks::broadcast(std::vector<char>&) {}
void SweepRanks::start_counter() { local_counter_ = 0; }
std::int64_t SweepRanks::claim_chunk() { return local_counter_++; }
void SweepRanks::send_chunk(const SweepChunk&) { throw std::logic_error("send_chunk without MPI"); }
bool SweepRanks::receive_chunk(SweepChunk&) { return false; }
void SweepRanks::finish(double, std::int64_t) {}
std::vector<double> SweepRanks::gather(const std::vector<double>& mine) { return mine; }
bool SweepRanks::any(bool flag) { return flag; }
void SweepRanks::abort(int status) { std::exit(status); }

#endif

}  // namespace lgi::experiments
