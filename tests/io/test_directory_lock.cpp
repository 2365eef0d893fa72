// One run per output directory: another process that holds the directory's lock is named in the
// error, a killed holder never blocks the next run, and within one process the lock is shared (two
// Output objects on one directory). Temporary names are unique, so writers never share one.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/directory_lock.hpp"
#include "io/output.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using namespace seismpm;

using seismpm::test::fresh_dir;

namespace {

// A child process that takes the lock of `dir`, reports on a pipe, and holds it until killed.
struct Holder {
  pid_t pid = -1;
  explicit Holder(const std::string& dir) {
    int ready[2];
    REQUIRE(pipe(ready) == 0);
    pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      close(ready[0]);
      try {
        DirectoryLock lock(dir);
        const char ok = 1;
        if (write(ready[1], &ok, 1) != 1) _exit(2);
        for (;;) pause();
      } catch (...) {
        _exit(1);
      }
    }
    close(ready[1]);
    char ok = 0;
    const bool locked = read(ready[0], &ok, 1) == 1 && ok == 1;
    close(ready[0]);
    REQUIRE(locked);
  }
  void kill_it() {
    if (pid > 0) {
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
      pid = -1;
    }
  }
  ~Holder() { kill_it(); }
};

// Another program tries the lock of `dir`: this test binary again (a fork would share this process's
// lock: the descriptor and the registry come with it), running the hidden case below. Its error
// message, or "" when it got the lock.
std::string other_process_tries(const std::string& dir) {
  const std::string report = dir + ".report";
  fs::remove(report);
  const std::string command = "SEISMPM_LOCK_DIR='" + dir + "' SEISMPM_LOCK_REPORT='" + report + "' /proc/" +
                              std::to_string(getpid()) + "/exe '[lock_child]' >/dev/null 2>&1";
  REQUIRE(std::system(command.c_str()) == 0);
  std::ifstream in(report, std::ios::binary);
  REQUIRE(in);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST_CASE("directory lock: another process holding it is named, a killed one blocks nothing",
          "[io][lock][robustness]") {
  const std::string dir = fresh_dir("lock_other");
  Holder holder(dir);
  SECTION("this process is refused, with the holder's process id and the way out") {
    CAPTURE(holder.pid);
    CHECK_THROWS_WITH(DirectoryLock(dir),
                      Catch::Contains("the output directory " + dir + " is in use by another seismpm run (process " +
                                      std::to_string(holder.pid) + ", see ") &&
                          Catch::Contains("--out"));
    OutputSettings s;
    s.dir = dir;
    CHECK_THROWS_AS(Output<2>(s), OutputError);
    CHECK_THROWS_AS(Output<3>(s), OutputError);
    // A path naming the same directory another way is the same directory.
    CHECK_THROWS_AS(DirectoryLock(dir + "/./"), OutputError);
  }
  SECTION("once the holder is killed (SIGKILL), the lock is free and names this process") {
    holder.kill_it();
    DirectoryLock lock(dir);
    CHECK(read_text(dir + "/" + DirectoryLock::kFileName) == std::to_string(getpid()) + "\n");
  }
}

TEST_CASE("directory lock: shared within one process, held as long as one holder lives", "[io][lock][robustness]") {
  const std::string dir = fresh_dir("lock_shared");
  OutputSettings s;
  s.dir = dir;
  SECTION("two Output objects on one directory, then none") {
    {
      auto first = std::make_unique<Output<2>>(s);
      Output<2> second(s);  // the same directory again: no error (a script that sets its output twice)
      CHECK_THAT(other_process_tries(dir), Catch::Contains("process " + std::to_string(getpid())));
      first.reset();  // the other still holds it
      CHECK_THAT(other_process_tries(dir), Catch::Contains("in use by another seismpm run"));
    }
    CHECK(other_process_tries(dir) == "");  // all gone: free for the next run
  }
  SECTION("a lock and an Output on the same directory, 2D and 3D") {
    DirectoryLock lock(dir);
    Output<3> three(s);
    CHECK_THAT(other_process_tries(dir), Catch::Contains("in use by another seismpm run"));
  }
  SECTION("a missing directory is an error naming it") {
    CHECK_THROWS_WITH(DirectoryLock(dir + "/missing"),
                      Catch::Contains("cannot lock the output directory " + dir + "/missing"));
  }
}

TEST_CASE("temporary names are unique: concurrent writers of one file never mix", "[io][lock][robustness]") {
  const std::string dir = fresh_dir("tmp_names");
  const std::string path = dir + "/table.csv";
  const std::string a = temporary_name(path), b = temporary_name(path);
  CHECK(a != b);
  CHECK_THAT(a, Catch::StartsWith(path + ".tmp." + std::to_string(getpid()) + "."));
  // Four threads write the same file over and over, each its own text of 256 KiB: with one shared
  // temporary name (PATH.tmp) their writes would interleave in it, or a rename would find it gone.
  std::vector<std::thread> writers;
  std::vector<std::string> errors(4);
  for (int w = 0; w < 4; ++w)
    writers.emplace_back([&, w] {
      const std::string text(256 * 1024, static_cast<char>('a' + w));
      try {
        for (int k = 0; k < 40; ++k) write_file_atomically(path, text);
      } catch (const std::exception& e) {
        errors[w] = e.what();
      }
    });
  int mixed = 0, reads = 0;
  for (int k = 0; k < 200; ++k) {
    const std::string text = read_text(path);
    if (text.empty()) continue;  // not written yet
    ++reads;
    mixed += text.size() != 256 * 1024 || text.find_first_not_of(text[0]) != std::string::npos;
  }
  for (auto& t : writers) t.join();
  CHECK(errors == std::vector<std::string>(4));
  CHECK(mixed == 0);
  CAPTURE(reads);
  const std::string last = read_text(path);
  CHECK((last.size() == 256 * 1024 && last.find_first_not_of(last[0]) == std::string::npos));
  int leftovers = 0;
  for (const auto& e : fs::directory_iterator(dir)) leftovers += e.path().filename() != "table.csv";
  CHECK(leftovers == 0);
}

// Run by other_process_tries in a separate process.
TEST_CASE("directory lock: the other process of other_process_tries", "[.][lock_child]") {
  const char* dir = std::getenv("SEISMPM_LOCK_DIR");
  const char* report = std::getenv("SEISMPM_LOCK_REPORT");
  REQUIRE(dir);
  REQUIRE(report);
  std::string message;
  try {
    DirectoryLock lock(dir);
  } catch (const std::exception& e) {
    message = e.what();
  }
  std::ofstream(report, std::ios::binary) << message;
}
