// Atomic output files: a reader of PATH sees the old file or the whole new one, never a part, and
// no temporary is left behind. Every output file polarview writes goes through here: each format's
// writer writes to a std::ostream (OBJ, .bv, STEP, IGES) or makes its bytes first (PLY, glb, PNG),
// and writeFileAtomically makes the file of it. POSIX.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>

namespace polarview {

// One output file written atomically to `path`.
//  - The bytes go to an unnamed temporary in path's directory (Linux O_TMPFILE), linked in as
//    `path` once complete, so nothing is visible before then and even kill -9 leaves nothing
//    (where `path` exists, linked under a fresh name and renamed over it: that name only ever
//    holds the whole file, and is removed on signals as below).
//  - Where the file system has no O_TMPFILE (or POLARVIEW_NAMED_TEMPORARIES=1 is set, for tests),
//    to a fresh file "PATH.XXXXXXXX.tmp" created with O_EXCL|O_NOFOLLOW: never an existing file,
//    never through a symlink; removed on SIGINT, SIGTERM and SIGHUP (see below).
//  - commit() fsyncs and renames over `path` (a symlink at `path` is replaced, not followed).
//  - Concurrent writers to one path each write their own temporary: `path` ends as one whole file.
//  - An existing `path` keeps its permission bits. One nobody may write (no w bit, or access()
//    says no) is refused, even for root: a read-only output is never replaced.
//  - An existing `path` that is a FIFO, a character device or anything in /dev or /proc (after
//    symlinks: /dev/stdout to a pipe, a terminal or the shell's file) is written into directly, as
//    cp does, never replaced: not atomic then, but the node stays. Sockets and block devices are
//    refused.
// On any error, and on destruction before commit(), the temporary is removed. Errors throw
// InputError(path, 0, what). Not thread-safe per object; separate objects are.
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(const std::string& path);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  // Appends bytes to the temporary. [O(bytes)]
  void write(std::string_view bytes);
  // Makes the temporary `path`: fsync, then link or rename. Call once, after the last write.
  void commit();

 private:
  void openNamedTemporary();
  bool openExistingNode();
  void discard() noexcept;
  [[noreturn]] void fail(const std::string& what, int err);

  std::string path_, directory_;
  std::string tempName_;  // the temporary's name; empty while it has none (O_TMPFILE)
  int fd_ = -1;
  int registrySlot_ = -1;  // in the signal handler's list of names to remove, or -1
  int keptMode_ = -1;      // an existing regular file's permission bits, given to the new one
  bool direct_ = false;    // writing into an existing FIFO or character device, not a temporary
  bool committed_ = false;
};

// Writes `bytes` to `path` with an AtomicFileWriter. [O(bytes)]
void writeFileAtomically(const std::string& path, std::string_view bytes);
// Runs `write` on a stream into an AtomicFileWriter for `path` (in 64 KiB blocks) and commits it:
// any exception, from `write` or the file, leaves nothing behind. The stream throws on bad writes.
// [O(bytes)]
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// Signals that remove the named temporaries in progress before the process dies of them: SIGINT,
// SIGTERM, SIGHUP, each only while its disposition is the default (an ignored SIGINT stays
// ignored, another handler stays in place). The handler is installed when a named temporary is
// created; it uses only atomic loads, unlink, signal and raise (async-signal-safe).

}  // namespace polarview
