#include "directory_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>

#include "atomic_file.hpp"

namespace seismpm {

struct DirectoryLock::Held {
  int fd = -1;
  ~Held() {
    if (fd >= 0) close(fd);  // releases the flock
  }
};

namespace {

// The locks this process holds, by the directory's canonical path: flock would refuse a second
// descriptor of this same process.
std::mutex registry_mutex;
std::map<std::string, std::weak_ptr<void>>& registry() {
  static std::map<std::string, std::weak_ptr<void>> held;
  return held;
}

std::string holder_of(int fd) {
  char buf[32] = {};
  const ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
  std::string pid = n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : "";
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid.find_first_not_of("0123456789") == std::string::npos && !pid.empty() ? pid : "unknown";
}

}  // namespace

DirectoryLock::DirectoryLock(const std::string& dir) : dir_(dir) {
  std::error_code ec;
  const std::string key = std::filesystem::canonical(dir, ec).string();
  if (ec) throw OutputError("cannot lock the output directory " + dir + ": " + ec.message());
  std::lock_guard<std::mutex> guard(registry_mutex);
  if (auto existing = std::static_pointer_cast<Held>(registry()[key].lock())) {
    held_ = std::move(existing);
    return;
  }
  const std::string path = key + "/" + kFileName;
  auto held = std::make_shared<Held>();
  held->fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (held->fd < 0) throw OutputError("cannot create the lock file " + path + ": " + std::strerror(errno));
  if (flock(held->fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno == EWOULDBLOCK)
      throw OutputError("the output directory " + dir + " is in use by another seismpm run (process " +
                        holder_of(held->fd) + ", see " + path +
                        "): wait for it to end, or give this run another directory (--out)");
    throw OutputError("cannot lock " + path + ": " + std::strerror(errno));
  }
  const std::string pid = std::to_string(getpid()) + "\n";
  if (ftruncate(held->fd, 0) != 0 || pwrite(held->fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size()))
    throw OutputError("cannot write the lock file " + path + ": " + std::strerror(errno));
  registry()[key] = held;
  held_ = std::move(held);
}

}  // namespace seismpm
