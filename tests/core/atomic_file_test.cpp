// Atomic output files: whole or nothing, never through a symlink, never over someone's file, no
// temporary left by errors, early destruction or SIGTERM; both the O_TMPFILE path and the named
// temporaries of file systems without it (POLARVIEW_NAMED_TEMPORARIES=1).
#include <doctest/doctest.h>

#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>

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
