#include "engine/store/rollback_driver.hpp"

#include <H5FDpublic.h>
#include <fcntl.h>
#include <hdf5.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#if !H5_VERSION_GE(1, 10, 0) || H5_VERSION_GE(1, 13, 0)
#error "rollback_driver.cpp implements HDF5 1.10/1.12's file-driver interface (H5FD_class_t)"
#endif

namespace chaosweep {

namespace {

// Journal layout (little-endian u64s): a header {magic, base, 0, checksum}
// where base is the file's size when the session began, then records
// {address, length, the `length` old bytes, checksum}. The checksums (FNV-1a
// over the preceding fields) tell a complete record from a torn one.
constexpr char journal_magic[8] = {'C', 'W', 'J', 'R', 'N', 'L', '0', '1'};
constexpr std::size_t header_size = 32;

struct Checksum {
  std::uint64_t h = 14695981039346656037ull;
  void add(const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  }
};

thread_local std::string last_open_error;

bool write_all(int fd, const void* buf, std::size_t n, off_t at = -1) {
  const char* p = static_cast<const char*>(buf);
  while (n > 0) {
    const ssize_t k = at < 0 ? ::write(fd, p, n) : ::pwrite(fd, p, n, at);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return false;
    p += k;
    n -= std::size_t(k);
    if (at >= 0) at += k;
  }
  return true;
}

// Reads n bytes at `at`; past the end of the file, zeros (as sec2 does).
bool read_all(int fd, void* buf, std::size_t n, off_t at) {
  char* p = static_cast<char*>(buf);
  while (n > 0) {
    const ssize_t k = ::pread(fd, p, n, at);
    if (k < 0 && errno == EINTR) continue;
    if (k < 0) return false;
    if (k == 0) {
      std::memset(p, 0, n);
      return true;
    }
    p += k;
    n -= std::size_t(k);
    at += k;
  }
  return true;
}

struct Journal {
  bool valid = false;  // a complete header: the session may have changed the file
  std::uint64_t base = 0;
  std::map<std::uint64_t, std::string> records;  // old bytes by address (disjoint)
};

// The journal's complete prefix. Throws when it exists but cannot be read.
Journal read_journal(const std::string& path) {
  Journal j;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) return j;
    throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
  }
  std::string bytes;
  char buf[1 << 16];
  for (;;) {
    const ssize_t k = ::read(fd, buf, sizeof buf);
    if (k < 0 && errno == EINTR) continue;
    if (k < 0) {
      const int err = errno;
      ::close(fd);
      throw std::runtime_error("cannot read " + path + ": " + std::strerror(err));
    }
    if (k == 0) break;
    bytes.append(buf, std::size_t(k));
  }
  ::close(fd);
  auto u64 = [&](std::size_t at) {
    std::uint64_t v;
    std::memcpy(&v, bytes.data() + at, 8);
    return v;
  };
  if (bytes.size() < header_size || std::memcmp(bytes.data(), journal_magic, 8) != 0) return j;
  Checksum hc;
  hc.add(bytes.data(), 24);
  if (hc.h != u64(24)) return j;
  j.valid = true;
  j.base = u64(8);
  for (std::size_t at = header_size; bytes.size() - at >= 24;) {
    const std::uint64_t addr = u64(at), len = u64(at + 8);
    if (len > bytes.size() - at - 24) break;  // torn: its overwrite was never issued
    Checksum rc;
    rc.add(bytes.data() + at, 16 + std::size_t(len));
    if (rc.h != u64(at + 16 + std::size_t(len))) break;
    j.records.emplace(addr, bytes.substr(at + 16, std::size_t(len)));
    at += 24 + std::size_t(len);
  }
  return j;
}

// Takes flock(op) on fd, waiting up to ~10 s for a session of another
// process to end (sessions last as long as one write of rows).
bool lock_file(int fd, int op) {
  for (int attempt = 0; attempt < 1000; ++attempt) {
    if (::flock(fd, op | LOCK_NB) == 0) return true;
    if (errno != EWOULDBLOCK && errno != EINTR) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  errno = EWOULDBLOCK;
  return false;
}

// Puts the old bytes back and the old size; the caller holds the lock.
void restore(int fd, const std::string& file, const Journal& j) {
  for (const auto& [addr, old] : j.records)
    if (!write_all(fd, old.data(), old.size(), off_t(addr)))
      throw std::runtime_error("cannot roll back " + file + ": " + std::strerror(errno));
  if (::ftruncate(fd, off_t(j.base)) != 0 || ::fsync(fd) != 0)
    throw std::runtime_error("cannot roll back " + file + ": " + std::strerror(errno));
}

struct Session {
  int fd = -1;
  bool writable = false;
  std::uint64_t eoa = 0, eof = 0;
  dev_t dev = 0;
  ino_t ino = 0;
  std::string journal;
  // Writing: bytes below `base` are journaled before they change.
  std::uint64_t base = 0;
  int jfd = -1;                                  // opened at the session's first change
  std::map<std::uint64_t, std::uint64_t> saved;  // journaled ranges [start, end), disjoint
  bool failed = false;                           // an I/O error: not committed at close
  // Reading through a pending journal: the old bytes over the file's, and
  // nothing at or past the old end (eof).
  bool viewing = false;
  std::map<std::uint64_t, std::string> overlay;
};

// What HDF5 holds: its public part first, as the driver interface requires.
struct DriverFile {
  H5FD_t pub;
  Session* s;
};

// Open sessions, to find one from its HDF5 file (abandon_session).
std::mutex sessions_mutex;
std::vector<Session*> open_sessions;

Session& session(const H5FD_t* f) { return *reinterpret_cast<const DriverFile*>(f)->s; }

// Journals [a, b) ∩ [0, base) (the parts not yet saved) before a change;
// the first change of a session writes the journal's header.
bool journal_before_change(Session& s, std::uint64_t a, std::uint64_t b) {
  if (s.jfd < 0) {
    s.jfd = ::open(s.journal.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (s.jfd < 0) return false;
    unsigned char h[header_size] = {};
    std::memcpy(h, journal_magic, 8);
    std::memcpy(h + 8, &s.base, 8);
    Checksum c;
    c.add(h, 24);
    std::memcpy(h + 24, &c.h, 8);
    if (!write_all(s.jfd, h, sizeof h)) return false;
  }
  b = std::min(b, s.base);
  std::vector<unsigned char> rec;
  for (std::uint64_t x = a; x < b;) {
    // Skip a saved range that covers x, else save up to the next saved one.
    auto it = s.saved.upper_bound(x);
    if (it != s.saved.begin() && std::prev(it)->second > x) {
      x = std::prev(it)->second;
      continue;
    }
    const std::uint64_t y = it == s.saved.end() ? b : std::min(b, it->first);
    const std::uint64_t len = y - x;
    rec.resize(24 + std::size_t(len));
    std::memcpy(rec.data(), &x, 8);
    std::memcpy(rec.data() + 8, &len, 8);
    if (!read_all(s.fd, rec.data() + 16, std::size_t(len), off_t(x))) return false;
    Checksum c;
    c.add(rec.data(), 16 + std::size_t(len));
    std::memcpy(rec.data() + 16 + len, &c.h, 8);
    if (!write_all(s.jfd, rec.data(), rec.size())) return false;
    // Record the range, merging with a neighbour that ends at x.
    auto prev = s.saved.lower_bound(x);
    if (prev != s.saved.begin() && std::prev(prev)->second == x) {
      std::prev(prev)->second = y;
    } else {
      s.saved[x] = y;
    }
    x = y;
  }
  return true;
}

H5FD_t* drv_open(const char* name, unsigned flags, hid_t, haddr_t maxaddr);
herr_t drv_close(H5FD_t* f);

int drv_cmp(const H5FD_t* a, const H5FD_t* b) {
  const Session &x = session(a), &y = session(b);
  if (x.dev != y.dev) return x.dev < y.dev ? -1 : 1;
  if (x.ino != y.ino) return x.ino < y.ino ? -1 : 1;
  return 0;
}

herr_t drv_query(const H5FD_t*, unsigned long* flags) {
  if (flags)
    *flags = H5FD_FEAT_AGGREGATE_METADATA | H5FD_FEAT_ACCUMULATE_METADATA | H5FD_FEAT_DATA_SIEVE |
             H5FD_FEAT_AGGREGATE_SMALLDATA | H5FD_FEAT_POSIX_COMPAT_HANDLE | H5FD_FEAT_DEFAULT_VFD_COMPATIBLE;
  return 0;
}

haddr_t drv_get_eoa(const H5FD_t* f, H5FD_mem_t) { return session(f).eoa; }

herr_t drv_set_eoa(H5FD_t* f, H5FD_mem_t, haddr_t addr) {
  session(f).eoa = addr;
  return 0;
}

haddr_t drv_get_eof(const H5FD_t* f, H5FD_mem_t) { return session(f).eof; }

herr_t drv_get_handle(H5FD_t* f, hid_t, void** handle) {
  if (!handle) return -1;
  *handle = &session(f).fd;
  return 0;
}

// The bytes [addr, addr + size) of the session's file as HDF5 sees them.
bool read_session(Session& s, std::uint64_t addr, std::size_t size, void* buf) {
  if (!read_all(s.fd, buf, size, off_t(addr))) return false;
  if (!s.viewing) return true;
  auto* out = static_cast<unsigned char*>(buf);
  const std::uint64_t end = addr + size;
  if (end > s.eof) {
    const std::uint64_t from = std::max<std::uint64_t>(addr, s.eof);
    std::memset(out + (from - addr), 0, std::size_t(end - from));
  }
  auto it = s.overlay.upper_bound(addr);
  if (it != s.overlay.begin()) --it;
  for (; it != s.overlay.end() && it->first < addr + size; ++it) {
    const std::uint64_t lo = std::max<std::uint64_t>(it->first, addr);
    const std::uint64_t hi = std::min<std::uint64_t>(it->first + it->second.size(), addr + size);
    if (lo < hi) std::memcpy(out + (lo - addr), it->second.data() + (lo - it->first), std::size_t(hi - lo));
  }
  return true;
}

herr_t drv_read(H5FD_t* f, H5FD_mem_t, hid_t, haddr_t addr, size_t size, void* buf) {
  return read_session(session(f), addr, size, buf) ? 0 : -1;
}

herr_t drv_write(H5FD_t* f, H5FD_mem_t, hid_t, haddr_t addr, size_t size, const void* buf) {
  Session& s = session(f);
  if (!s.writable || !journal_before_change(s, addr, addr + size) || !write_all(s.fd, buf, size, off_t(addr))) {
    s.failed = true;
    return -1;
  }
  s.eof = std::max<std::uint64_t>(s.eof, addr + size);
  return 0;
}

herr_t drv_truncate(H5FD_t* f, hid_t, hbool_t) {
  Session& s = session(f);
  if (!s.writable || s.eoa == s.eof) return 0;
  if (!journal_before_change(s, s.eoa, s.eof) || ::ftruncate(s.fd, off_t(s.eoa)) != 0) {
    s.failed = true;
    return -1;
  }
  s.eof = s.eoa;
  return 0;
}

// The session's lock is taken at open (HDF5's own lock calls are no-ops).
herr_t drv_lock(H5FD_t*, hbool_t) { return 0; }
herr_t drv_unlock(H5FD_t*) { return 0; }

const H5FD_class_t driver_class = {
    "chaosweep_rollback",
    (haddr_t(1) << 62),
    H5F_CLOSE_WEAK,
    nullptr,  // terminate
    nullptr,  // sb_size
    nullptr,  // sb_encode
    nullptr,  // sb_decode
    0,        // fapl_size
    nullptr,  // fapl_get
    nullptr,  // fapl_copy
    nullptr,  // fapl_free
    0,        // dxpl_size
    nullptr,  // dxpl_copy
    nullptr,  // dxpl_free
    drv_open,
    drv_close,
    drv_cmp,
    drv_query,
    nullptr,  // get_type_map
    nullptr,  // alloc
    nullptr,  // free
    drv_get_eoa,
    drv_set_eoa,
    drv_get_eof,
    drv_get_handle,
    drv_read,
    drv_write,
    nullptr,  // flush: nothing buffered here
    drv_truncate,
    drv_lock,
    drv_unlock,
    H5FD_FLMAP_DICHOTOMY,
};

H5FD_t* drv_open(const char* name, unsigned flags, hid_t, haddr_t maxaddr) {
  last_open_error.clear();
  if (!name || !*name || maxaddr == 0 || maxaddr == HADDR_UNDEF) {
    last_open_error = "no file name";
    return nullptr;
  }
  auto s = std::make_unique<Session>();
  s->writable = (flags & H5F_ACC_RDWR) != 0;
  s->journal = journal_path(name);
  const bool create = (flags & (H5F_ACC_TRUNC | H5F_ACC_CREAT)) != 0;
  int oflags = (s->writable ? O_RDWR : O_RDONLY) | O_CLOEXEC;
  if (flags & H5F_ACC_CREAT) oflags |= O_CREAT;
  if (flags & H5F_ACC_EXCL) oflags |= O_EXCL;
  s->fd = ::open(name, oflags, 0644);
  auto fail = [&](const std::string& why) -> H5FD_t* {
    last_open_error = why;
    if (s->fd >= 0) ::close(s->fd);
    return nullptr;
  };
  if (s->fd < 0) return fail(std::strerror(errno));
  if (!lock_file(s->fd, s->writable ? LOCK_EX : LOCK_SH))
    return fail(errno == EWOULDBLOCK ? "another process has it open (its lock is held)"
                                     : std::string("cannot lock it: ") + std::strerror(errno));
  try {
    if (create && (flags & H5F_ACC_TRUNC)) {
      // A new file: a journal left by an earlier file of this name is void.
      if (::ftruncate(s->fd, 0) != 0) return fail(std::strerror(errno));
      if (::unlink(s->journal.c_str()) != 0 && errno != ENOENT) return fail(std::strerror(errno));
    } else {
      const Journal j = read_journal(s->journal);
      if (s->writable) {
        if (j.valid) restore(s->fd, name, j);
        if (::unlink(s->journal.c_str()) != 0 && errno != ENOENT) return fail(std::strerror(errno));
      } else if (j.valid) {
        s->viewing = true;
        s->overlay = j.records;
        s->eof = j.base;
      }
    }
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  struct stat st {};
  if (::fstat(s->fd, &st) != 0) return fail(std::strerror(errno));
  s->dev = st.st_dev;
  s->ino = st.st_ino;
  if (!s->viewing) s->eof = std::uint64_t(st.st_size);
  s->base = std::uint64_t(st.st_size);
  auto* f = new DriverFile{};
  f->s = s.release();
  std::lock_guard<std::mutex> lock(sessions_mutex);
  open_sessions.push_back(f->s);
  return &f->pub;
}

herr_t drv_close(H5FD_t* f) {
  auto* df = reinterpret_cast<DriverFile*>(f);
  Session* s = df->s;
  herr_t rc = 0;
  if (s->jfd >= 0) {
    ::close(s->jfd);
    // Committed: the file holds the session's complete state.
    if (!s->failed && ::unlink(s->journal.c_str()) != 0) rc = -1;
  }
  if (::close(s->fd) != 0) rc = -1;  // releases the lock
  {
    std::lock_guard<std::mutex> lock(sessions_mutex);
    std::erase(open_sessions, s);
  }
  delete s;
  delete df;
  return rc;
}

std::mutex registration;
hid_t driver_id = -1;

}  // namespace

std::string journal_path(const std::string& file) { return file + ".journal"; }

hid_t rollback_fapl() {
  {
    std::lock_guard<std::mutex> lock(registration);
    if (driver_id < 0 || H5Iis_valid(driver_id) <= 0) driver_id = H5FDregister(&driver_class);
  }
  if (driver_id < 0) throw std::runtime_error("HDF5: cannot register the rollback file driver");
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl < 0 || H5Pset_driver(fapl, driver_id, nullptr) < 0) {
    if (fapl >= 0) H5Pclose(fapl);
    throw std::runtime_error("HDF5: cannot select the rollback file driver");
  }
  return fapl;
}

void roll_back(const std::string& file) {
  const std::string journal = journal_path(file);
  if (::access(journal.c_str(), F_OK) != 0) return;
  const int fd = ::open(file.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error("cannot roll back " + file + ": " + std::strerror(errno));
  try {
    if (!lock_file(fd, LOCK_EX)) throw std::runtime_error("cannot roll back " + file + ": another process holds it");
    const Journal j = read_journal(journal);
    if (j.valid) restore(fd, file, j);
    if (::unlink(journal.c_str()) != 0 && errno != ENOENT)
      throw std::runtime_error("cannot remove " + journal + ": " + std::strerror(errno));
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
}

void abandon_session(hid_t file) {
  void* handle = nullptr;
  if (H5Fget_vfd_handle(file, H5P_DEFAULT, &handle) < 0 || !handle) return;
  std::lock_guard<std::mutex> lock(sessions_mutex);
  for (Session* s : open_sessions)
    if (&s->fd == handle) s->failed = true;
}

bool read_file_bytes(hid_t file, std::uint64_t addr, std::size_t n, void* buf) {
  void* handle = nullptr;
  if (H5Fget_vfd_handle(file, H5P_DEFAULT, &handle) < 0 || !handle) return false;
  std::lock_guard<std::mutex> lock(sessions_mutex);
  for (Session* s : open_sessions)
    if (&s->fd == handle) return read_session(*s, addr, n, buf);
  return false;
}

const std::string& rollback_open_error() { return last_open_error; }

}  // namespace chaosweep
