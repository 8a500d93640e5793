#pragma once
// Bounded input (README.md, "Limits"; issue 50): every text file lgi reads (a
// scene, a sweep spec, a seed or state CSV file) is read whole under a cap of
// 16 MiB, whatever it is: a regular file larger than that is refused before a
// byte is read, and a pipe, stdin or a device (/dev/zero, /dev/urandom) is
// read until the cap and then refused, so no input can exhaust memory. A
// directory is refused by name. HDF5 inputs (resume and state files) are
// handed to the library only when they are regular files that carry the HDF5
// signature, as the library itself looks for it (at byte 0, 512, 1024, ...).
#include <cstddef>
#include <string>

namespace lgi::experiments {

inline constexpr std::size_t text_input_limit = std::size_t{16} << 20;  // 16 MiB

/// The whole text of `path`; throws InputError "<path>: cannot read <what>: ..."
/// for a missing or unreadable file, a directory, or more than text_input_limit bytes.
std::string read_text_input(const std::string& path, const std::string& what);

/// Empty if `path` is a regular file (after symbolic links); otherwise why
/// not ("is a FIFO, not a regular file", the errno text).
std::string regular_file_problem(const std::string& path);

/// Empty if `path` is a regular file (after symbolic links) with the HDF5
/// signature; otherwise why not ("is a FIFO, not a regular file", "has no
/// HDF5 signature", the errno text). Opens nothing through HDF5.
std::string hdf5_input_problem(const std::string& path);

}  // namespace lgi::experiments
