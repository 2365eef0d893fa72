// Reading the input files (records, tables) line by line: a UTF-8 byte order mark at the start and a
// CR before each LF are dropped, a line is capped at kMaxLine bytes (read in chunks, so a file without
// line breaks costs no more than the cap), and numbers are whole cells or errors. Messages quote the
// file's text with printable() and name FILE:LINE.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

namespace seismpm {

class TextLines {
 public:
  static constexpr std::size_t kMaxLine = std::size_t(1) << 20;  // 1 MiB

  // Throws InputError "FILE: cannot open (...)".
  explicit TextLines(std::string file);
  // The next line without its line break; false at the end of the file. Throws InputError naming
  // FILE:LINE for a line over kMaxLine bytes.
  bool next(std::string& line);
  const std::string& file() const { return file_; }
  int number() const { return number_; }  // of the line last read (1-based)
  // "FILE:LINE: " of the line last read.
  std::string where() const;
  // The file's size in bytes (0 when it cannot be told: a pipe).
  std::uintmax_t size() const { return size_; }

 private:
  bool fill();
  std::string file_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> in_;
  std::uintmax_t size_ = 0;
  std::string chunk_;
  std::size_t pos_ = 0, end_ = 0;
  int number_ = 0;
  bool eof_ = false;
};

// `text` as it can be shown in a message: control characters, NUL and bytes over 0x7e as \xNN (\t,
// \r, \n by name), cut after `max` characters with "...".
std::string printable(std::string_view text, std::size_t max = 60);

// A whole cell as a finite number: false for an empty cell, one with anything after the number
// (NUL bytes included), an overflow, inf or nan.
bool parse_number(std::string_view text, double& out);

}  // namespace seismpm
