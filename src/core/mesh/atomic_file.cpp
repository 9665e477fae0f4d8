// Atomic output files through O_TMPFILE + linkat, or O_EXCL temporaries + rename (see atomic_file.h).
#include "core/mesh/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <ostream>
#include <streambuf>

#include "core/mesh/input_error.h"

namespace polarview {

namespace {

// [SECTION] Registry of named temporaries, emptied by a signal handler

// A fixed table: the handler may not allocate or lock, only read atomics and call unlink.
constexpr int kRegistrySlots = 64;
enum SlotState : int { kFree = 0, kFilling = 1, kActive = 2 };
struct RegistrySlot {
  std::atomic<int> state{kFree};
  char name[PATH_MAX];
};
RegistrySlot gRegistry[kRegistrySlots];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

constexpr int kCleanedSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void removeTemporariesAndDie(int signalNumber) {
  for (RegistrySlot& slot : gRegistry)
    if (slot.state.load() == kActive) ::unlink(slot.name);
  // Die of the same signal, so the parent sees what happened (exit status 128 + n).
  ::signal(signalNumber, SIG_DFL);
  ::raise(signalNumber);
}

// Installs the handler where a signal still has its default disposition. Checked at every
// registration (three sigaction calls), so a program that resets its signals is covered again.
void installSignalHandlers() {
  for (int signalNumber : kCleanedSignals) {
    struct sigaction current {};
    if (::sigaction(signalNumber, nullptr, &current) != 0) continue;
    // Leave an ignored signal ignored and someone else's handler in place.
    if ((current.sa_flags & SA_SIGINFO) || current.sa_handler != SIG_DFL) continue;
    struct sigaction action {};
    action.sa_handler = removeTemporariesAndDie;
    sigemptyset(&action.sa_mask);
    ::sigaction(signalNumber, &action, nullptr);
  }
}

// Registers a temporary the handler must remove; -1 when the name is too long or the table full
// (the temporary is then still removed on errors, just not on signals).
int registerTemporary(const std::string& name) {
  if (name.size() >= PATH_MAX) return -1;
  installSignalHandlers();
  for (int i = 0; i < kRegistrySlots; ++i) {
    int expected = kFree;
    if (gRegistry[i].state.compare_exchange_strong(expected, kFilling)) {
      std::memcpy(gRegistry[i].name, name.c_str(), name.size() + 1);
      gRegistry[i].state.store(kActive);
      return i;
    }
  }
  return -1;
}

void unregisterTemporary(int slot) {
  if (slot >= 0) gRegistry[slot].state.store(kFree);
}

// Blocks the cleaned signals on this thread while a temporary's name and its registry entry
// change together (created and registered, renamed and unregistered), so a signal never finds a
// name registered that is not ours, nor ours unregistered.
class SignalsBlocked {
 public:
  SignalsBlocked() {
    sigset_t set;
    sigemptyset(&set);
    for (int signalNumber : kCleanedSignals) sigaddset(&set, signalNumber);
    ::pthread_sigmask(SIG_BLOCK, &set, &previous_);
  }
  ~SignalsBlocked() { ::pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }
  SignalsBlocked(const SignalsBlocked&) = delete;
  SignalsBlocked& operator=(const SignalsBlocked&) = delete;

 private:
  sigset_t previous_;
};

// [SECTION] Names

// "PATH.XXXXXXXX.tmp" with 8 random letters and digits: distinct between processes and calls;
// O_EXCL settles the rare clash.
std::string uniqueTemporaryName(const std::string& path) {
  static std::atomic<uint64_t> counter{0};
  uint64_t x = uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()) ^
               (uint64_t(::getpid()) << 32) ^ (counter.fetch_add(1) * 0x9e3779b97f4a7c15ull);
  // splitmix64 finaliser: neighbouring inputs give unrelated names.
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  x ^= x >> 31;
  static constexpr char kAlphabet[] = "abcdefghijklmnopqrstuvwxyz0123456789";
  std::string name = path + ".";
  for (int i = 0; i < 8; ++i, x /= 36) name += kAlphabet[x % 36];
  return name + ".tmp";
}

std::string directoryOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

bool namedTemporariesForced() {
  const char* value = std::getenv("POLARVIEW_NAMED_TEMPORARIES");
  return value && *value && std::strcmp(value, "0") != 0;
}

constexpr int kNameAttempts = 100;
// rw for everyone the umask allows, as fopen creates files.
constexpr mode_t kFileMode = 0666;

// True where `directory` is in /dev or /proc (after symlinks): their entries are the system's
// (/dev/stdout, /proc/self/fd/1 are links to whatever the shell opened), written into, never replaced.
bool isSystemDirectory(const std::string& directory) {
  char resolved[PATH_MAX];
  if (!::realpath(directory.c_str(), resolved)) return false;
  const std::string_view dir(resolved);
  for (std::string_view root : {std::string_view("/dev"), std::string_view("/proc")})
    if (dir.substr(0, root.size()) == root && (dir.size() == root.size() || dir[root.size()] == '/')) return true;
  return false;
}

}  // namespace

// [SECTION] AtomicFileWriter

AtomicFileWriter::AtomicFileWriter(const std::string& path) : path_(path), directory_(directoryOf(path)) {
  if (path.empty() || path.back() == '/') throw InputError(path, 0, "cannot write: not a file name");
  if (openExistingNode()) return;
#ifdef O_TMPFILE
  if (!namedTemporariesForced()) {
    fd_ = ::open(directory_.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, kFileMode);
    // The file is linked in through /proc/self/fd (linkat's AT_EMPTY_PATH needs a capability):
    // without /proc, use a named temporary.
    if (fd_ >= 0 && ::access("/proc/self/fd", X_OK) != 0) {
      ::close(fd_);
      fd_ = -1;
    }
  }
#endif
  // No O_TMPFILE here (or a directory that refuses it): the named temporary reports real errors.
  if (fd_ < 0) openNamedTemporary();
  if (keptMode_ >= 0 && ::fchmod(fd_, mode_t(keptMode_)) != 0) fail("cannot keep the file's permissions", errno);
}

// What is at `path` already (through symlinks): nothing or a regular file to replace (false), or a
// node to write into directly, opened (true): a FIFO, a character device, or anything in /dev or /proc.
bool AtomicFileWriter::openExistingNode() {
  struct stat existing {};
  if (::stat(path_.c_str(), &existing) != 0) return false;
  const mode_t type = existing.st_mode & S_IFMT;
  if (type == S_IFDIR) throw InputError(path_, 0, "cannot write: it is a directory");
  if (type == S_IFSOCK || type == S_IFBLK)
    throw InputError(path_, 0, std::string("cannot write: it is a ") + (type == S_IFSOCK ? "socket" : "block device") +
                                   " (outputs are regular files, FIFOs or character devices)");
  const bool direct = type != S_IFREG || isSystemDirectory(directory_);
  if (!direct) {
    // Root may write anything: the w bits say what the owner meant.
    if ((existing.st_mode & 0222) == 0 || ::access(path_.c_str(), W_OK) != 0)
      throw InputError(path_, 0, "cannot write: the file is read-only (it is not replaced)");
    keptMode_ = int(existing.st_mode & 0777);
    return false;
  }
  // A FIFO blocks here until it has a reader, as with cp; a regular file (the shell's redirection
  // behind /dev/stdout) is truncated as the shell would.
  fd_ = ::open(path_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC | (type == S_IFREG ? O_TRUNC : 0));
  if (fd_ < 0) fail("cannot write", errno);
  direct_ = true;
  return true;
}

AtomicFileWriter::~AtomicFileWriter() {
  if (!committed_) discard();
}

void AtomicFileWriter::openNamedTemporary() {
  for (int attempt = 0; attempt < kNameAttempts; ++attempt) {
    const std::string name = uniqueTemporaryName(path_);
    SignalsBlocked blocked;
    fd_ = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, kFileMode);
    if (fd_ >= 0) {
      tempName_ = name;
      registrySlot_ = registerTemporary(name);
      return;
    }
    if (errno != EEXIST) fail("cannot write", errno);
  }
  fail("cannot create a temporary file next to it", EEXIST);
}

void AtomicFileWriter::write(std::string_view bytes) {
  if (fd_ < 0) throw InputError(path_, 0, "write after commit");
  const char* data = bytes.data();
  size_t left = bytes.size();
  while (left > 0) {
    const ssize_t written = ::write(fd_, data, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      fail("write failed", errno);
    }
    data += written;
    left -= size_t(written);
  }
}

void AtomicFileWriter::commit() {
  if (fd_ < 0) throw InputError(path_, 0, "commit twice");
  if (direct_) {
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("write failed", errno);
    committed_ = true;
    return;
  }
  if (::fsync(fd_) != 0 && errno != EINVAL) fail("write failed", errno);
  if (tempName_.empty()) {
    // Unnamed (O_TMPFILE): link it in as `path` directly when nothing is there; otherwise under a
    // fresh name, renamed over `path` below (linkat never replaces).
    const std::string self = "/proc/self/fd/" + std::to_string(fd_);
    if (::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, path_.c_str(), AT_SYMLINK_FOLLOW) == 0) {
      committed_ = true;
    } else if (errno != EEXIST) {
      fail("cannot write", errno);
    } else {
      for (int attempt = 0; attempt < kNameAttempts && tempName_.empty(); ++attempt) {
        const std::string name = uniqueTemporaryName(path_);
        SignalsBlocked blocked;
        if (::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0) {
          tempName_ = name;
          registrySlot_ = registerTemporary(name);
        } else if (errno != EEXIST) {
          fail("cannot write", errno);
        }
      }
      if (tempName_.empty()) fail("cannot create a temporary file next to it", EEXIST);
    }
  }
  if (!committed_) {
    SignalsBlocked blocked;
    if (::rename(tempName_.c_str(), path_.c_str()) != 0) fail("cannot replace the file", errno);
    unregisterTemporary(registrySlot_);
    registrySlot_ = -1;
    tempName_.clear();
    committed_ = true;
  }
  ::close(fd_);
  fd_ = -1;
  // Make the new directory entry durable too; a failure here loses nothing already written.
  const int directory = ::open(directory_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (directory >= 0) {
    ::fsync(directory);
    ::close(directory);
  }
}

void AtomicFileWriter::discard() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (tempName_.empty()) return;
  SignalsBlocked blocked;
  ::unlink(tempName_.c_str());
  unregisterTemporary(registrySlot_);
  registrySlot_ = -1;
  tempName_.clear();
}

void AtomicFileWriter::fail(const std::string& what, int err) {
  discard();
  throw InputError(path_, 0, what + ": " + std::strerror(err));
}

void writeFileAtomically(const std::string& path, std::string_view bytes) {
  AtomicFileWriter file(path);
  file.write(bytes);
  file.commit();
}

namespace {

// A stream buffer that hands its bytes to an AtomicFileWriter in blocks (its errors propagate
// through the ostream, whose exceptions() must include badbit).
class AtomicFileBuffer : public std::streambuf {
 public:
  explicit AtomicFileBuffer(AtomicFileWriter& file) : file_(file) { setp(block_, block_ + sizeof block_); }

 protected:
  int_type overflow(int_type c) override {
    drain();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  // Short pieces (a number, a keyword) join the block; only pieces as large as it go straight
  // to the file (a write per `<<` cost most of a STEP export: docs/performance.md, Exports).
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n < epptr() - pptr()) {
      std::memcpy(pptr(), s, size_t(n));
      pbump(int(n));
      return n;
    }
    drain();
    if (size_t(n) < sizeof block_) {
      std::memcpy(pptr(), s, size_t(n));
      pbump(int(n));
    } else {
      file_.write(std::string_view(s, size_t(n)));
    }
    return n;
  }
  int sync() override {
    drain();
    return 0;
  }

 private:
  void drain() {
    if (pptr() > pbase()) file_.write(std::string_view(pbase(), size_t(pptr() - pbase())));
    setp(block_, block_ + sizeof block_);
  }
  AtomicFileWriter& file_;
  char block_[1 << 16];
};

}  // namespace

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  AtomicFileWriter file(path);
  AtomicFileBuffer buffer(file);
  std::ostream stream(&buffer);
  stream.exceptions(std::ios::badbit | std::ios::failbit);
  write(stream);
  stream.flush();
  file.commit();
}

}  // namespace polarview
