#include "experiments/io/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>

#include "experiments/errors/input_error.hpp"

namespace lgi::experiments {
namespace {

/// Closes the descriptor on every path out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "is a directory";
  if (S_ISCHR(mode)) return "is a character device, not a regular file";
  if (S_ISBLK(mode)) return "is a block device, not a regular file";
  if (S_ISFIFO(mode)) return "is a FIFO, not a regular file";
  if (S_ISSOCK(mode)) return "is a socket, not a regular file";
  return "is not a regular file";
}

std::string mib(std::size_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

}  // namespace

std::string read_text_input(const std::string& path, const std::string& what) {
  const std::string where = path + ": cannot read " + what + ": ";
  const Descriptor d{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (d.fd < 0) throw InputError(where + std::strerror(errno));
  struct stat st {};
  if (::fstat(d.fd, &st) != 0) throw InputError(where + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw InputError(where + "is a directory");
  if (S_ISREG(st.st_mode) && static_cast<std::size_t>(st.st_size) > text_input_limit)
    throw InputError(where + "larger than " + mib(text_input_limit) + " (the limit of a text input)");
  std::string text;
  std::array<char, 1 << 16> buf{};
  for (;;) {
    const ssize_t got = ::read(d.fd, buf.data(), buf.size());
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw InputError(where + std::strerror(errno));
    if (got == 0) break;
    text.append(buf.data(), static_cast<std::size_t>(got));
    // A pipe or a device has no size up front: read to the cap, then refuse.
    if (text.size() > text_input_limit)
      throw InputError(where + "more than " + mib(text_input_limit) + " of input (the limit of a text input)" +
                       (S_ISREG(st.st_mode) ? "" : "; it " + kind_of(st.st_mode)));
  }
  return text;
}

std::string regular_file_problem(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::strerror(errno);
  return S_ISREG(st.st_mode) ? std::string() : kind_of(st.st_mode);
}

std::string hdf5_input_problem(const std::string& path) {
  if (std::string why = regular_file_problem(path); !why.empty()) return why;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::strerror(errno);
  const Descriptor d{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
  if (d.fd < 0) return std::strerror(errno);
  // The superblock signature, at 0 or a power of two from 512 (HDF5 File Format Specification, §II.A).
  static constexpr char signature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
  for (off_t at = 0; at + 8 <= st.st_size; at = at == 0 ? 512 : 2 * at) {
    char head[8];
    if (::pread(d.fd, head, sizeof head, at) != static_cast<ssize_t>(sizeof head)) break;
    if (std::memcmp(head, signature, sizeof head) == 0) return {};
  }
  return st.st_size < 8 ? "too short to be an HDF5 file (" + std::to_string(st.st_size) + " bytes)"
                        : "not an HDF5 file (no HDF5 signature)";
}

}  // namespace lgi::experiments
