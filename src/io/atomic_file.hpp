// Files written whole or not at all: write to NAME.tmp, then rename over NAME.
#pragma once

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
// Writes `text` to `path` atomically.
void write_file_atomically(const std::string& path, const std::string& text);
// Renames a finished temporary file over `path`; throws OutputError naming both.
void commit_file(const std::string& temporary, const std::string& path);

}  // namespace seismpm
