// Files written whole or not at all: write to a temporary name beside NAME (unique to the process and
// the write), then rename over NAME. Tables that grow by rows (probes.csv) are extended in place
// instead, each change one write call.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace seismpm {

// An output that could not be written; the message names the path and the reason.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Creates `dir` and its parents; throws OutputError naming it when that fails or it is not writable.
void ensure_directory(const std::string& dir);
// A fresh temporary name for `path`: PATH.tmp.<pid>.<counter>, so two writers (threads, processes)
// never share one.
std::string temporary_name(const std::string& path);
// Writes `text` to `path` atomically.
void write_file_atomically(const std::string& path, const std::string& text);
// Renames a finished temporary file over `path`; throws OutputError naming both.
void commit_file(const std::string& temporary, const std::string& path);
// Replaces what `path` holds from byte `offset` on with `text` (offset = the size: appends), in one
// write call, when the file is `size` bytes long as expected. False, changing nothing, when it is
// missing or has another size (someone else changed it: the caller writes it whole); throws
// OutputError when the write fails (the file is then cut back to `size`).
bool replace_file_tail(const std::string& path, std::uint64_t size, std::uint64_t offset, const std::string& text);

}  // namespace seismpm
