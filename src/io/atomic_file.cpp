#include "atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace seismpm {

void ensure_directory(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw OutputError("cannot create the output directory " + dir + ": " + ec.message());
  if (!std::filesystem::is_directory(dir)) throw OutputError("the output path " + dir + " is not a directory");
  if (access(dir.c_str(), W_OK) != 0) throw OutputError("the output directory " + dir + " is not writable");
}

std::string temporary_name(const std::string& path) {
  static std::atomic<unsigned long> counter{0};
  return path + ".tmp." + std::to_string(getpid()) + "." + std::to_string(counter++);
}

void write_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = temporary_name(path);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw OutputError("cannot write " + path + ": " + std::strerror(errno));
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size() && std::fflush(f) == 0;
  const int err = errno;
  if (std::fclose(f) != 0 || !ok) {
    std::remove(tmp.c_str());
    throw OutputError("cannot write " + path + ": " + std::strerror(ok ? errno : err) + " (disk full?)");
  }
  commit_file(tmp, path);
}

void commit_file(const std::string& temporary, const std::string& path) {
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(temporary.c_str());
    throw OutputError("cannot rename " + temporary + " to " + path + ": " + why);
  }
}

bool replace_file_tail(const std::string& path, std::uint64_t size, std::uint64_t offset, const std::string& text) {
  const int fd = open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return false;
  struct stat st {};
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || static_cast<std::uint64_t>(st.st_size) != size || offset > size) {
    close(fd);
    return false;
  }
  const ssize_t n = pwrite(fd, text.data(), text.size(), static_cast<off_t>(offset));
  const int err = errno;
  bool ok = n == static_cast<ssize_t>(text.size());
  if (ok && offset + text.size() < size) ok = ftruncate(fd, static_cast<off_t>(offset + text.size())) == 0;
  if (!ok && ftruncate(fd, static_cast<off_t>(size)) != 0) {
  }  // best effort: the rows written before stay whole
  close(fd);
  if (!ok) throw OutputError("cannot write " + path + ": " + std::strerror(n < 0 ? err : ENOSPC) + " (disk full?)");
  return true;
}

}  // namespace seismpm
