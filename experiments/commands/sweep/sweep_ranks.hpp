#pragma once
// The ranks of a sweep: MPI_COMM_WORLD when lgi is built with MPI
// (-DLGI_MPI=ON, or the lgi-mpi test executable) and launched by mpirun,
// else one rank. sweep_ranks.cpp is compiled once per variant; nothing else
// in lgi sees MPI.
//
// How work and results move (experiments/SWEEPS.md, "MPI"):
//  - every rank builds the same list of pending chunks from the done mask
//    that rank 0 read from the partial file and broadcast;
//  - a chunk is claimed with an atomic fetch-and-add on a counter held by
//    rank 0 (MPI_Fetch_and_op, passive target), so fast ranks take more
//    chunks (dynamic load balance, as OpenMP's dynamic schedule in a rank);
//  - other ranks send each completed chunk to rank 0 (MPI_Isend of a packed
//    buffer), which alone writes the partial and the final file.
// All MPI calls are made under one lock (MPI_THREAD_SERIALIZED).
#include <cstdint>
#include <vector>

#include "experiments/io/sweep_file.hpp"

namespace lgi::experiments {

class SweepRanks {
 public:
  /// The world, MPI initialised on first use if launched by mpirun.
  static SweepRanks& world();
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  /// Cores per rank on this node: all of them divided by the ranks sharing it.
  int default_threads() const;

  /// Rank 0's value, on every rank.
  std::int64_t broadcast(std::int64_t value);
  void broadcast(std::vector<char>& bytes);

  /// Starts the chunk counter at 0 (collective).
  void start_counter();
  /// The next chunk number, over all ranks and threads.
  std::int64_t claim_chunk();
  /// Not rank 0: hands a completed chunk to rank 0 (non-blocking).
  void send_chunk(const SweepChunk& chunk);
  /// Rank 0: a chunk another rank sent, if one has arrived.
  bool receive_chunk(SweepChunk& chunk);
  /// Not rank 0: waits for its sends, then tells rank 0 it is done (with its
  /// CPU seconds and crossings). Rank 0: whether every other rank is done.
  void finish(double cpu_seconds, std::int64_t events);
  bool others_finished() const { return finished_ == size_ - 1; }
  /// Sums over the other ranks reported with finish().
  double others_cpu_seconds() const { return others_cpu_; }
  std::int64_t others_events() const { return others_events_; }
  /// Collective: every rank's `mine`, concatenated in rank order, on rank 0
  /// (the other ranks get an empty vector). lgi chaos-map's results.
  std::vector<double> gather(const std::vector<double>& mine);
  /// Collective: whether any rank has `flag` set (a signal seen by one rank).
  bool any(bool flag);
  /// Ends every rank at once (an error on rank 0 after the run started).
  [[noreturn]] void abort(int status);

 private:
  SweepRanks();
  ~SweepRanks();
  struct Mpi;
  Mpi* mpi_ = nullptr;
  int rank_ = 0, size_ = 1, finished_ = 0;
  double others_cpu_ = 0.0;
  std::int64_t others_events_ = 0;
  std::int64_t local_counter_ = 0;
};

/// A chunk as bytes (and back), for sending between ranks.
std::vector<char> pack_chunk(const SweepChunk& chunk);
SweepChunk unpack_chunk(const std::vector<char>& bytes);

}  // namespace lgi::experiments
