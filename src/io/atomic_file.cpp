#include "atomic_file.hpp"

#include <unistd.h>

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

void write_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
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

}  // namespace seismpm
