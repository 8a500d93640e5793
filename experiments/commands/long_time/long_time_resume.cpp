// lgi long-time --resume: checkpoints and reopening (long_time_resume.hpp).
#include "experiments/commands/long_time/long_time_resume.hpp"

#include <hdf5.h>

#include <cstdio>
#include <iostream>

#include "experiments/errors/exit_status.hpp"
#include "experiments/io/h5md_writer.hpp"  // OutputFileError
#include "experiments/io/hdf5_inspection.hpp"
#include "experiments/io/hdf5_support.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

constexpr const char* resume_group = "resume";
constexpr const char* record_name = "checkpoint";

/// Whether the HDF5 file at `path` (opened read-only, after inspect_in_child) has the object `name`.
bool has_object(const std::string& path, const char* name) {
  const hdf5::QuietHdf5Errors quiet;
  hdf5::Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  return file.valid() && H5Lexists(file.get(), name, H5P_DEFAULT) > 0;
}

/// Every bit of x: a hexadecimal float.
std::string exact(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", x);
  return buf;
}

}  // namespace

std::string long_time_fingerprint(const system::Scene& scene, const integrators::SchemeInfo& scheme,
                                  const integrators::RunConfig& cfg, int samples, const std::vector<Column>& columns) {
  std::string f = "lgi long-time checkpoints 1\nlgi " + std::string(build_info::version) + "; " +
                  build_info::compiler + "; " + build_info::cxx_flags + "; " + build_info::build_type +
                  "\nscheme " + scheme.name + "\nt0 " + exact(cfg.t0) + " t_end " + exact(cfg.t_end) + " dt " +
                  exact(cfg.dt) + " tol " + exact(cfg.tol) + "\nsamples " + std::to_string(samples) + "\ncolumns";
  for (const Column& c : columns) f += " " + c.name;
  return f + "\nscene\n" + scene.toml_text;
}

void create_resume_record(ResultsFile& file, const std::string& fingerprint) {
  ResultAttributes a;
  a.fixed_text["fingerprint"] = fingerprint;
  file.write_group(resume_group, a);
  file.create_record(resume_group, record_name, 2 * checkpoint_slot_bytes);
  file.keep_row_hashes(resume_group);
}

template <class S>
ResumedResults<S> reopen_for_resume(const std::string& out, bool force, const std::vector<Column>& columns,
                                 const ResultsFileOptions& options, const std::string& fingerprint,
                                 std::size_t error_columns) {
  const std::string partial = out + ".partial", csv = results_csv_path(out);
  if (!hdf5::path_exists(partial))
    throw UsageError("--resume: there is no " + partial + " to resume" +
                     (hdf5::path_exists(out) ? " (" + out + " is complete)" : ""));
  // A finish publishes <csv>.partial as <csv>, then <out>.partial as <out>: a
  // run stopped between the two renames left <csv> and no <csv>.partial. That
  // CSV is the run's own, so the first rename is undone and the run resumed.
  if (!hdf5::path_exists(csv + ".partial") && hdf5::path_exists(csv) && hdf5::path_exists(partial) &&
      std::rename(csv.c_str(), (csv + ".partial").c_str()) == 0)
    std::cerr << "lgi: " << csv << " is taken back to " << csv << ".partial: its run's finish was interrupted\n";
  for (const std::string& p : {out, csv})
    hdf5::check_output_target(p, force);
  ResumedResults<S> r;
  if (const std::string why = hdf5::inspect_in_child(partial); !why.empty())
    throw OutputFileError("cannot resume results '" + partial + "': " + why + " (damaged); remove it");
  bool readable = false;
  const std::optional<std::string> stored =
      hdf5::read_fixed_string_attribute(partial, std::string("/") + resume_group, "fingerprint", &readable);
  if (!readable)
    throw OutputFileError("cannot resume results '" + partial + "': not an HDF5 file (damaged); remove it");
  // No fingerprint: a long-time run killed as it started (its table is there: start again), or
  // another command's file (a sweep's .partial), which is refused and left as it is.
  if (!stored && !has_object(partial, "/series"))
    throw UsageError("--resume: " + partial + " is not a partial lgi long-time file (no /series table, no "
                     "checkpoint); it is left as it is: remove it or choose another --out");
  if (!stored) return r;  // nothing to go on from
  if (*stored != fingerprint)
    throw UsageError("--resume: " + partial +
                     " was started with another scene, scheme, step, t_end, --samples or lgi build; remove it or "
                     "run without --resume");
  r.file = std::make_unique<ResultsFile>(out, force, columns, options, ResultsFile::Reopen{});
  if (r.file->text_attribute(resume_group, "fingerprint") != fingerprint)  // changed since it was read
    throw OutputFileError("cannot resume results '" + partial + "': its fingerprint cannot be read (damaged)");
  r.file->reopen_row_hashes(resume_group);
  r.checkpoint = newest_checkpoint<S>(r.file->read_record(resume_group, record_name), error_columns, r.file->rows(),
                                   r.next_sequence);
  // Every row the run keeps against its checksum: a damaged one is refused (both files left as they are).
  const std::int64_t kept = r.checkpoint ? r.checkpoint->rows : 0;
  if (const std::int64_t bad = r.file->first_damaged_row(kept); bad >= 0)
    throw OutputFileError("--resume: " + partial + ": row " + std::to_string(bad) + " of /series (or its line in " +
                          r.file->csv_partial_path() +
                          ") does not match the checksum written with it (changed or damaged since); both files are "
                          "left as they are: remove them and run again without --resume");
  r.file->keep_rows(kept);
  return r;
}

template <class S>
LongTimeCheckpoints<S>::LongTimeCheckpoints(ResultsFile& file, double interval_seconds,
                                            std::function<void(BasicRunCheckpoint<S>&)> fill,
                                            std::uint64_t next_sequence)
    : file_(file),
      interval_(interval_seconds),
      fill_(std::move(fill)),
      sequence_(next_sequence),
      last_(std::chrono::steady_clock::now()) {}

template <class S>
bool LongTimeCheckpoints<S>::due(std::int64_t /*step*/) {
  return std::chrono::steady_clock::now() - last_ >= interval_;
}

template <class S>
void LongTimeCheckpoints<S>::save(const integrators::BasicLoopCheckpoint<S>& checkpoint) {
  file_.flush();  // the rows first: a checkpoint never counts rows that are not in the file
  BasicRunCheckpoint<S> c;
  c.rows = file_.rows();
  c.loop = checkpoint;
  fill_(c);
  const std::size_t slot = static_cast<std::size_t>(sequence_ % 2) * checkpoint_slot_bytes;
  file_.write_record(resume_group, record_name, slot, encode_checkpoint(c, sequence_));
  ++sequence_;
  last_ = std::chrono::steady_clock::now();
}

// The two state spaces a long run is checkpointed on.
template ResumedResults<system::State> reopen_for_resume<system::State>(const std::string&, bool,
                                                                        const std::vector<Column>&,
                                                                        const ResultsFileOptions&, const std::string&,
                                                                        std::size_t);
template ResumedResults<system::TorusState> reopen_for_resume<system::TorusState>(
    const std::string&, bool, const std::vector<Column>&, const ResultsFileOptions&, const std::string&,
    std::size_t);
template class LongTimeCheckpoints<system::State>;
template class LongTimeCheckpoints<system::TorusState>;

}  // namespace lgi::experiments
