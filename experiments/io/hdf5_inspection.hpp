#pragma once
// A damaged HDF5 file read in a child process first. libhdf5 1.10 can crash
// (a null read in H5F__accum_read under H5Lexists) or loop forever (H5HG_read
// on a damaged global heap) on a damaged file; no check inside the process can
// stop that once the library is in. So before lgi opens a file it will resume
// (a long-time or sweep .partial), a forked child walks the whole file the way
// the readers will: every object (H5Ovisit), every attribute read, every
// dataset's space and type, every chunk of a chunked dataset looked up by its
// coordinates (as H5Dset_extent does when a resume shrinks the columns, where a
// damaged chunk index loops for ever: H5B_find), and the datasets themselves up to 64 MB. If the
// child dies by a signal, exits non-zero or takes longer than the timeout, the
// file is refused with one line and lgi never touches it
// (fuzz/fuzz_h5_readers.cpp found both failures).
#include <string>

namespace lgi::experiments::hdf5 {

/// Empty if `path` is not an HDF5 file (the reader's own open refuses it), or
/// if a child process read it through HDF5 without failing within
/// `timeout_seconds`; otherwise why not ("HDF5 crashed on it (signal 11)",
/// "HDF5 did not finish reading it in 10 s", ...).
std::string inspect_in_child(const std::string& path, int timeout_seconds = 10);

}  // namespace lgi::experiments::hdf5
