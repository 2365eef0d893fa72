// An output directory held by one run at a time: DIR/.seismpm.lock, locked with flock and holding the
// process id. The kernel drops the lock when the process ends however it ends (kill -9 included), so
// a dead run never blocks the next; the file itself stays. Within one process a directory may be held
// any number of times (a script that sets the output again, two models writing side by side).
#pragma once

#include <memory>
#include <string>

namespace seismpm {

class DirectoryLock {
 public:
  static constexpr const char* kFileName = ".seismpm.lock";
  // Takes the lock of `dir` (which must exist). Throws OutputError naming the directory and the other
  // process's id when another process holds it.
  explicit DirectoryLock(const std::string& dir);
  const std::string& dir() const { return dir_; }

 private:
  struct Held;
  std::string dir_;
  std::shared_ptr<Held> held_;
};

}  // namespace seismpm
