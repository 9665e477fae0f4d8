// Atomic output files: whole or nothing, never through a symlink, never over someone's file, no
// temporary left by errors, early destruction or SIGTERM; both the O_TMPFILE path and the named
// temporaries of file systems without it (POLARVIEW_NAMED_TEMPORARIES=1).
#include <doctest/doctest.h>

#include <signal.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "temp_dir.h"
#include "core/mesh/atomic_file.h"
#include "core/mesh/input_error.h"

using namespace polarview;
namespace fs = std::filesystem;

namespace {

struct TempDir : test::TempDir {
  TempDir() : test::TempDir("polarview_atomic_test_") {}
};

// Runs the test body with named temporaries forced (true) or the default O_TMPFILE path (false).
class TemporaryMode {
 public:
  explicit TemporaryMode(bool named) {
    if (named) ::setenv("POLARVIEW_NAMED_TEMPORARIES", "1", 1);
    else ::unsetenv("POLARVIEW_NAMED_TEMPORARIES");
  }
  ~TemporaryMode() { ::unsetenv("POLARVIEW_NAMED_TEMPORARIES"); }
};

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The names in `dir` (symlinks included, not followed).
std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename().string());
  return names;
}

}  // namespace

TEST_CASE("atomic file: the whole content replaces the file, and nothing else is left") {
  for (bool named : {false, true}) {
    CAPTURE(named);
    TemporaryMode mode(named);
    TempDir dir;
    const fs::path out = dir.path / "out.obj";
    writeFileAtomically(out.string(), "first\n");
    CHECK(readFile(out) == "first\n");
    const std::string big(3 << 20, 'x');  // several write() calls
    {
      AtomicFileWriter file(out.string());
      file.write(big.substr(0, 1 << 20));
      file.write(big.substr(1 << 20));
      CHECK(readFile(out) == "first\n");  // the old file until commit
      file.commit();
    }
    CHECK(readFile(out) == big);
    CHECK(listing(dir.path) == std::set<std::string>{"out.obj"});
    // A relative path writes into the current directory.
    const fs::path cwd = fs::current_path();
    fs::current_path(dir.path);
    writeFileAtomically("relative.txt", "r");
    fs::current_path(cwd);
    CHECK(readFile(dir.path / "relative.txt") == "r");
  }
}

TEST_CASE("atomic file: a stream's pieces of every size arrive whole and in order") {
  // Short pieces join the 64 KiB block; pieces filling it, or larger than it, go around it.
  TempDir dir;
  const fs::path out = dir.path / "pieces.txt";
  std::mt19937 random(7);
  std::string expected;
  std::vector<std::string> pieces;
  for (size_t size : {size_t(1), size_t(65535), size_t(3), size_t(65536), size_t(65537), size_t(0), size_t(200000), size_t(17)}) {
    std::string piece(size, ' ');
    for (char& c : piece) c = char('a' + random() % 26);
    pieces.push_back(piece);
  }
  for (int i = 0; i < 5000; ++i) pieces.push_back(std::to_string(i) + ' ');
  writeFileAtomically(out.string(), [&](std::ostream& stream) {
    for (const std::string& piece : pieces) {
      stream << piece;
      stream.put('|');
      expected += piece + '|';
    }
  });
  CHECK(readFile(out) == expected);
}

TEST_CASE("atomic file: a user's OUT.tmp and symlinks named like temporaries are never touched") {
  for (bool named : {false, true}) {
    CAPTURE(named);
    TemporaryMode mode(named);
    TempDir dir;
    const fs::path victim = dir.path / "victim.txt";
    { std::ofstream(victim) << "keep me"; }
    { std::ofstream(dir.path / "a.obj.tmp") << "mine"; }
    fs::create_symlink(victim, dir.path / "b.obj.tmp");
    fs::create_symlink(dir.path / "nowhere.txt", dir.path / "c.obj.tmp");  // dangling
    for (const char* name : {"a.obj", "b.obj", "c.obj"}) writeFileAtomically((dir.path / name).string(), "new");
    CHECK(readFile(dir.path / "a.obj.tmp") == "mine");
    CHECK(fs::is_symlink(dir.path / "b.obj.tmp"));
    CHECK(fs::read_symlink(dir.path / "b.obj.tmp") == victim);
    CHECK(readFile(victim) == "keep me");
    CHECK(fs::is_symlink(dir.path / "c.obj.tmp"));
    CHECK_FALSE(fs::exists(dir.path / "nowhere.txt"));
    for (const char* name : {"a.obj", "b.obj", "c.obj"}) CHECK(readFile(dir.path / name) == "new");
    CHECK(listing(dir.path) == std::set<std::string>{"victim.txt", "a.obj.tmp", "b.obj.tmp", "c.obj.tmp", "a.obj", "b.obj", "c.obj"});
  }
}

TEST_CASE("atomic file: a symlink at the output is replaced, not written through") {
  for (bool named : {false, true}) {
    CAPTURE(named);
    TemporaryMode mode(named);
    TempDir dir;
    const fs::path victim = dir.path / "victim.txt";
    { std::ofstream(victim) << "keep me"; }
    fs::create_symlink(victim, dir.path / "out.png");
    writeFileAtomically((dir.path / "out.png").string(), "png");
    CHECK_FALSE(fs::is_symlink(dir.path / "out.png"));
    CHECK(readFile(dir.path / "out.png") == "png");
    CHECK(readFile(victim) == "keep me");
  }
}

TEST_CASE("atomic file: a FIFO at the output is written into and stays a FIFO") {
  for (bool named : {false, true}) {
    CAPTURE(named);
    TemporaryMode mode(named);
    TempDir dir;
    const fs::path fifo = dir.path / "out.png";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    std::string received;
    std::thread reader([&] { received = readFile(fifo); });  // opening blocks until the writer opens
    const std::string bytes(200000, 'p');                     // more than a pipe's buffer
    writeFileAtomically(fifo.string(), bytes);
    if (!fs::is_fifo(fs::symlink_status(fifo))) {
      reader.detach();  // blocked for good on the replaced FIFO: fail rather than hang
      FAIL("the FIFO was replaced");
    }
    reader.join();
    CHECK(received == bytes);
    CHECK(listing(dir.path) == std::set<std::string>{"out.png"});
  }
}

TEST_CASE("atomic file: a read-only output is refused, a writable one keeps its permissions") {
  for (bool named : {false, true}) {
    CAPTURE(named);
    TemporaryMode mode(named);
    TempDir dir;
    const fs::path readOnly = dir.path / "ro.obj", privateFile = dir.path / "private.obj";
    writeFileAtomically(readOnly.string(), "old\n");
    ::chmod(readOnly.c_str(), 0444);
    CHECK_THROWS_WITH_AS(writeFileAtomically(readOnly.string(), "new\n"), doctest::Contains("read-only"), InputError);
    CHECK(readFile(readOnly) == "old\n");  // even for root, who could write it
    writeFileAtomically(privateFile.string(), "old\n");
    ::chmod(privateFile.c_str(), 0600);
    writeFileAtomically(privateFile.string(), "new\n");
    CHECK(readFile(privateFile) == "new\n");
    struct stat after {};
    REQUIRE(::stat(privateFile.c_str(), &after) == 0);
    CHECK((after.st_mode & 0777) == 0600);
    CHECK(listing(dir.path) == std::set<std::string>{"private.obj", "ro.obj"});
  }
}

TEST_CASE("atomic file: a directory or a socket at the output is refused and left as it is") {
  TempDir dir;
  const fs::path sub = dir.path / "sub", socketPath = dir.path / "sock";
  fs::create_directory(sub);
  CHECK_THROWS_WITH_AS(writeFileAtomically(sub.string(), "x"), doctest::Contains("is a directory"), InputError);
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  REQUIRE(fd >= 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::snprintf(address.sun_path, sizeof address.sun_path, "%s", socketPath.c_str());
  REQUIRE(::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0);
  CHECK_THROWS_WITH_AS(writeFileAtomically(socketPath.string(), "x"), doctest::Contains("socket"), InputError);
  ::close(fd);
  CHECK(fs::is_socket(fs::symlink_status(socketPath)));
  CHECK(fs::is_directory(sub));
}

TEST_CASE("atomic file: no commit, or an error, leaves the old file and no temporary") {
  for (bool named : {false, true}) {
    CAPTURE(named);
    TemporaryMode mode(named);
    TempDir dir;
    const fs::path out = dir.path / "out.obj";
    { std::ofstream(out) << "old"; }
    {
      AtomicFileWriter file(out.string());
      file.write("half of a new fi");
    }  // destroyed before commit, as when an exception unwinds
    CHECK(readFile(out) == "old");
    CHECK(listing(dir.path) == std::set<std::string>{"out.obj"});

    // Errors name the path: a missing directory, a directory in the way.
    const std::string missing = (dir.path / "no" / "such" / "out.obj").string();
    try {
      writeFileAtomically(missing, "x");
      FAIL("wrote into a missing directory");
    } catch (const InputError& e) {
      CHECK(e.file() == missing);
    }
    fs::create_directories(dir.path / "adir" / "child");
    CHECK_THROWS_AS(writeFileAtomically((dir.path / "adir").string(), "x"), InputError);
    CHECK(fs::is_directory(dir.path / "adir" / "child"));
    CHECK(listing(dir.path) == std::set<std::string>{"out.obj", "adir"});
  }
}

TEST_CASE("atomic file: concurrent writers to one path leave one whole file") {
  for (bool named : {false, true}) {
    CAPTURE(named);
    TemporaryMode mode(named);
    TempDir dir;
    const std::string out = (dir.path / "out.obj").string();
    const std::string a(1 << 20, 'a'), b(3 << 19, 'b');
    for (int round = 0; round < 10; ++round) {
      std::thread other([&] { writeFileAtomically(out, a); });
      writeFileAtomically(out, b);
      other.join();
      const std::string result = readFile(out);
      CHECK((result == a || result == b));
    }
    CHECK(listing(dir.path) == std::set<std::string>{"out.obj"});
  }
}

TEST_CASE("atomic file: SIGTERM during a write removes the temporary and kills the process") {
  for (bool named : {false, true}) {
    CAPTURE(named);
    TemporaryMode mode(named);
    TempDir dir;
    const std::string out = (dir.path / "out.obj").string();
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      // The test runner has its own SIGTERM handler: the default is what a program starts with.
      ::signal(SIGTERM, SIG_DFL);
      try {
        AtomicFileWriter file(out);
        file.write("part of the file");
        ::raise(SIGTERM);
      } catch (...) {
      }
      ::_exit(3);  // only reached when the signal did not end the process
    }
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    CHECK(WIFSIGNALED(status));
    if (WIFSIGNALED(status)) CHECK(WTERMSIG(status) == SIGTERM);
    CHECK(listing(dir.path).empty());
  }
}
