#pragma once
// An HDF5 file driver that makes each open-to-close session of a file
// all-or-nothing when the process dies (kill -9, OOM killer, a node taken
// away): POSIX I/O like HDF5's sec2 driver, plus a rollback journal.
//
// HDF5 updates a file in place (chunk index, object headers, heap, the
// superblock) in no crash-safe order, so a process killed during a write can
// leave earlier, finished data unreadable. This driver never lets a session
// change a byte the file held when the session began without first
// appending that byte range's old contents to FILE.journal (records with a
// checksum, written with write(2) before the overwrite is issued; bytes
// past the old end of the file need no record: dropping them is the undo).
// A clean close deletes the journal. So after a kill the file plus its
// journal always describe the state after the last clean close:
//   - an open for writing first rolls the dead session back (puts the old
//     bytes back, truncates to the old size, deletes the journal);
//   - an open for reading changes nothing and reads that state through the
//     journal (the old bytes over the new, the old size as the end).
// A torn last record (the process died while appending it) is ignored: its
// overwrite had not been issued. The driver holds flock(2) on the file for
// the whole session (exclusive to write, shared to read), so a reader never
// sees a session in progress. Covers process death, not an operating-system
// crash or power loss (nothing is fsync'ed). Files are plain HDF5: any HDF5
// reader (h5py, h5dump) opens them; only a file with a pending journal needs
// this driver (or one write-open by it) to be read as of its last close.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/store/h5_id.hpp"

namespace chaosweep {

// A new file-access property list that selects the driver (close it with
// H5Pclose). Thread-compatible like HDF5 itself.
H5Id rollback_fapl();

// FILE's journal: FILE + ".journal".
std::string journal_path(const std::string& file);

// Rolls back an interrupted session of `file` now (what an open for writing
// does first); no-op without a journal. Throws std::runtime_error.
void roll_back(const std::string& file);

// Marks the session of `file` (an open HDF5 file of this driver) as
// failed: its close keeps the journal, so roll_back() (or the next open for
// writing) undoes the session. For a write that failed without an I/O error
// the driver could see (an HDF5 error after the extent grew).
void abandon_session(H5Id file);

// Reads the bytes [addr, addr + n) of `file` (an open HDF5 file of this
// driver; addresses as the driver sees them, the user block included) as
// HDF5 reads them, through a pending journal too. False when `file` is not
// of this driver or the read fails. For a reader that parses a structure
// of the file HDF5 has no call for (global_heap_text.hpp).
bool read_file_bytes(H5Id file, std::uint64_t addr, std::size_t n, void* buf);

// Why the driver's last open failed in this thread ("" if it did not), e.g.
// that another process holds the file's lock; for error messages.
const std::string& rollback_open_error();

}  // namespace chaosweep
