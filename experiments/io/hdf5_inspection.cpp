#include "experiments/io/hdf5_inspection.hpp"

#include <hdf5.h>
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>
#include <vector>

#include "experiments/io/input_file.hpp"

// Set by a sanitizer runtime when one is linked (then libFuzzer registers its
// crash report here); absent, and so null, otherwise.
extern "C" void __sanitizer_set_death_callback(void (*)(void)) __attribute__((weak));

namespace lgi::experiments::hdf5 {
namespace {

constexpr hsize_t max_read_bytes = hsize_t{64} << 20;

herr_t read_attribute(hid_t obj, const char* name, const H5A_info_t*, void*) {
  const hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  if (a < 0) return -1;
  const hid_t type = H5Aget_type(a), space = H5Aget_space(a);
  herr_t status = type < 0 || space < 0 ? -1 : 0;
  if (status == 0) {
    const hssize_t n = H5Sget_simple_extent_npoints(space);
    const size_t size = H5Tget_size(type);
    const hid_t memory = H5Tget_native_type(type, H5T_DIR_DEFAULT);
    if (n < 0 || memory < 0 || static_cast<hsize_t>(n) * size > max_read_bytes) {
      status = -1;
    } else if (H5Tis_variable_str(type) > 0) {
      std::vector<char*> text(static_cast<std::size_t>(n) + 1, nullptr);
      status = H5Aread(a, memory, text.data());
      if (status >= 0) H5Dvlen_reclaim(memory, space, H5P_DEFAULT, text.data());
    } else if (H5Tget_class(type) != H5T_VLEN) {
      std::vector<unsigned char> buffer(static_cast<std::size_t>(n) * size + 16);
      status = H5Aread(a, memory, buffer.data());
    }
    if (memory >= 0) H5Tclose(memory);
  }
  if (space >= 0) H5Sclose(space);
  if (type >= 0) H5Tclose(type);
  H5Aclose(a);
  return status < 0 ? -1 : 0;
}

// Chunk lookups in one dataset at the most: an lgi file holds far fewer (10⁸ rows
// in chunks of hundreds), so a dataset needing more has a damaged extent.
constexpr hsize_t max_chunk_lookups = hsize_t{1} << 22;

/// Every chunk of a chunked dataset looked up by its coordinates, which is how
/// H5Dset_extent finds the chunks it drops when a resume shrinks the columns
/// (H5D__chunk_prune_by_extent → H5B_find). A damaged chunk index can loop
/// there for ever while a read of the whole dataset finishes
/// (fuzz/fuzz_h5_readers.cpp found it on a long-time .partial;
/// tests/fuzz_regressions/h5_readers/libhdf5_loop_in_chunk_prune.h5).
herr_t look_up_chunks(hid_t dset, hid_t space) {
  const hid_t plist = H5Dget_create_plist(dset);
  if (plist < 0) return -1;
  herr_t status = 0;
  const int rank = H5Sget_simple_extent_ndims(space);
  if (H5Pget_layout(plist) == H5D_CHUNKED && rank != 0) {
    constexpr int max_rank = 8;
    hsize_t chunk[max_rank], dims[max_rank], counts[max_rank], at[max_rank] = {}, offset[max_rank] = {};
    hsize_t total = 1;
    status = rank < 0 || rank > max_rank || H5Pget_chunk(plist, rank, chunk) != rank ||
                     H5Sget_simple_extent_dims(space, dims, nullptr) != rank
                 ? -1
                 : 0;
    for (int d = 0; status == 0 && d < rank; ++d) {
      counts[d] = chunk[d] == 0 ? 0 : (dims[d] + chunk[d] - 1) / chunk[d];
      if (chunk[d] == 0 || (counts[d] > 0 && total > max_chunk_lookups / counts[d])) status = -1;
      total *= counts[d];
    }
    for (hsize_t k = 0; status == 0 && k < total; ++k) {  // the chunk coordinates, last dimension fastest
      for (int d = 0; d < rank; ++d) offset[d] = at[d] * chunk[d];
      unsigned filter_mask = 0;
      haddr_t address = 0;
      hsize_t bytes = 0;
      if (H5Dget_chunk_info_by_coord(dset, offset, &filter_mask, &address, &bytes) < 0) status = -1;
      for (int d = rank - 1; d >= 0 && ++at[d] == counts[d]; --d) at[d] = 0;
    }
  }
  H5Pclose(plist);
  return status;
}

herr_t visit_object(hid_t root, const char* name, const H5O_info_t* info, void*) {
  const hid_t obj = H5Oopen(root, name, H5P_DEFAULT);
  if (obj < 0) return -1;
  hsize_t index = 0;
  herr_t status = H5Aiterate2(obj, H5_INDEX_NAME, H5_ITER_NATIVE, &index, read_attribute, nullptr);
  if (status >= 0 && info->type == H5O_TYPE_DATASET) {
    const hid_t type = H5Dget_type(obj), space = H5Dget_space(obj);
    const hid_t memory = type >= 0 ? H5Tget_native_type(type, H5T_DIR_DEFAULT) : -1;
    const hssize_t n = space >= 0 ? H5Sget_simple_extent_npoints(space) : -1;
    if (type < 0 || space < 0 || memory < 0 || n < 0 || look_up_chunks(obj, space) < 0) {
      status = -1;
    } else if (H5Tget_class(type) != H5T_VLEN && H5Tis_variable_str(type) <= 0 &&
               static_cast<hsize_t>(n) * H5Tget_size(type) <= max_read_bytes) {
      std::vector<unsigned char> buffer(static_cast<std::size_t>(n) * H5Tget_size(type) + 16);
      status = H5Dread(obj, memory, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data());
    }
    if (memory >= 0) H5Tclose(memory);
    if (space >= 0) H5Sclose(space);
    if (type >= 0) H5Tclose(type);
  }
  H5Oclose(obj);
  return status < 0 ? -1 : 0;
}

/// The child: 0 if the walk succeeded, 1 if HDF5 reported an error.
[[noreturn]] void inspect_and_exit(const std::string& path) {
  // A crash here is the answer, not a finding: the default actions (no sanitizer
  // report, no crash file from an inherited fuzzer callback), and the parent reads the signal.
  for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP}) signal(sig, SIG_DFL);
  if (__sanitizer_set_death_callback != nullptr) __sanitizer_set_death_callback(nullptr);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  int code = 1;
  if (file >= 0) {
    code = H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_NATIVE, visit_object, nullptr, H5O_INFO_BASIC) < 0 ? 1 : 0;
    if (H5Fclose(file) < 0) code = 1;
  }
  _exit(code);  // no atexit handlers, HDF5's or the parent's
}

}  // namespace

std::string inspect_in_child(const std::string& path, int timeout_seconds) {
  // A FIFO or device never reaches HDF5 (input_file.hpp); a regular file without the signature
  // is refused by the reader's own open, with its own message.
  if (std::string why = regular_file_problem(path); !why.empty()) return why;
  if (H5Fis_hdf5(path.c_str()) <= 0) return {};
  const pid_t child = fork();
  if (child < 0) return {};  // no process to spare: the readers' own checks remain
  if (child == 0) inspect_and_exit(path);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_seconds);
  int status = 0;
  for (auto pause = std::chrono::microseconds(200);; pause = std::min(2 * pause, std::chrono::microseconds(50000))) {
    const pid_t done = waitpid(child, &status, WNOHANG);
    if (done == child) break;
    if (done < 0) return {};
    if (std::chrono::steady_clock::now() > deadline) {
      kill(child, SIGKILL);
      waitpid(child, &status, 0);
      return "HDF5 did not finish reading it in " + std::to_string(timeout_seconds) + " s";
    }
    std::this_thread::sleep_for(pause);
  }
  if (WIFSIGNALED(status)) return "HDF5 crashed reading it (signal " + std::to_string(WTERMSIG(status)) + ")";
  if (WIFEXITED(status) && WEXITSTATUS(status) != 0) return "HDF5 cannot read all of it";
  return {};
}

}  // namespace lgi::experiments::hdf5
