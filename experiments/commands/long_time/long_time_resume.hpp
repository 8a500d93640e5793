#pragma once
// lgi long-time --resume (RESULTS.md, "long-time --resume"): the run's
// checkpoints in its results file, and the file reopened to go on from the
// last one.
//
// A fresh run writes /resume in <out>.partial: the attribute fingerprint (the
// scene's text, the scheme, the resolved t0, t_end, dt, tol, the samples per
// decade, the columns and the lgi build: what a resumed run must find
// unchanged to go on bit for bit) and the record checkpoint (two slots,
// io/run_checkpoint.hpp). At most every --flush-seconds (and only at a step
// that is a multiple of 4096) the loop offers a checkpoint
// (integrators/core/run_config.hpp): the buffered rows are written and flushed,
// then the checkpoint goes to the older slot and is flushed. --resume reopens
// both .partial files, keeps the rows up to the newest intact checkpoint and
// goes on from it; with no checkpoint yet, from step 0.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "experiments/io/results_file.hpp"
#include "experiments/io/run_checkpoint.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments {

/// The settings a resumed run must share with the run it continues.
std::string long_time_fingerprint(const system::Scene& scene, const integrators::SchemeInfo& scheme,
                                  const integrators::RunConfig& cfg, int samples, const std::vector<Column>& columns);

/// Writes /resume (fingerprint, empty checkpoint record) into a new results file.
void create_resume_record(ResultsFile& file, const std::string& fingerprint);

/// The results file of a run on states S to resume and the checkpoint it
/// goes on from (none: from step 0, every row dropped). No file: the partial
/// file holds no fingerprint (a run killed in its first moments, or made by
/// an lgi without checkpoints): nothing in it can be continued, and the run
/// starts anew.
template <class S>
struct ResumedResults {
  std::unique_ptr<ResultsFile> file;
  std::optional<BasicRunCheckpoint<S>> checkpoint;
  std::uint64_t next_sequence = 1;  // of the next checkpoint: above every one in the file
};
/// Checks the fingerprint of <out>.partial (read-only: a refused file is left
/// as it was), reopens it and its CSV (ResultsFile::Reopen) and keeps the
/// rows up to the newest checkpoint. Throws
/// UsageError (--resume: no partial file, an existing output without
/// --force, another run's file) or OutputFileError (a damaged file).
template <class S>
ResumedResults<S> reopen_for_resume(const std::string& out, bool force, const std::vector<Column>& columns,
                                 const ResultsFileOptions& options, const std::string& fingerprint,
                                 std::size_t error_columns);

/// Offers the loop's checkpoints to the results file (top of this file).
/// `fill` adds the command's part: the error maxima, CPU and output seconds.
template <class S>
class LongTimeCheckpoints final : public integrators::BasicCheckpoints<S> {
 public:
  LongTimeCheckpoints(ResultsFile& file, double interval_seconds, std::function<void(BasicRunCheckpoint<S>&)> fill,
                      std::uint64_t next_sequence);
  bool due(std::int64_t step) override;
  void save(const integrators::BasicLoopCheckpoint<S>& checkpoint) override;

 private:
  ResultsFile& file_;
  std::chrono::duration<double> interval_;
  std::function<void(BasicRunCheckpoint<S>&)> fill_;
  std::uint64_t sequence_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace lgi::experiments
