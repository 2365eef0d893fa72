// The checkpoint container (docs/checkpoint.md): a header, then tagged sections, each with its
// length and a CRC-32, ending with an END section. This file knows the container only; what the
// sections hold is the run layer's (src/run/checkpoint.hpp).
//
//   header   "SEISMPMCHK" (10 bytes), format version (u16), reserved (u32, 0)
//   section  tag (8 bytes, ASCII, NUL-padded), payload length (u64), payload, CRC-32 (u32) of tag,
//            length and payload
//   last     the section "END" with an empty payload
//
// Numbers are little-endian; doubles are IEEE 754 binary64 written bit for bit. A reader never trusts
// a count: every count is checked against the bytes left in its section before anything is allocated.
#pragma once

#include <cstdint>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace seismpm {

// A checkpoint that cannot be read (missing, truncated, corrupt, another format version) or restored;
// the message names the file.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr std::string_view kCheckpointMagic = "SEISMPMCHK";
// Version 3 added Rayleigh damping (each deformable material's alpha and beta, the particles' damping
// stress); version 2 files are still read, as undamped.
inline constexpr std::uint16_t kCheckpointVersion = 3;
inline constexpr std::uint16_t kOldestCheckpointVersion = 2;

// CRC-32 (IEEE 802.3, the one of zlib and Python's zlib.crc32) of `size` bytes, continuing from `crc`.
std::uint32_t crc32(const void* data, std::size_t size, std::uint32_t crc = 0);

// One section's payload, built value by value.
class SectionWriter {
 public:
  void u8(std::uint8_t v) { raw(&v, 1); }
  void u16(std::uint16_t v) { raw(&v, 2); }
  void u32(std::uint32_t v) { raw(&v, 4); }
  void i32(std::int32_t v) { raw(&v, 4); }
  void i64(std::int64_t v) { raw(&v, 8); }
  void f64(double v) { raw(&v, 8); }
  void boolean(bool v) { u8(v ? 1 : 0); }
  void text(std::string_view s);  // u32 length, bytes
  void count(std::size_t n) { i64(static_cast<std::int64_t>(n)); }
  // u64 count, then the elements' bytes (numbers only).
  template <class T>
  void array(const std::vector<T>& v) {
    static_assert(std::is_arithmetic_v<T>);
    count(v.size());
    raw(v.data(), v.size() * sizeof(T));
  }
  void raw(const void* p, std::size_t n);
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

class CheckpointWriter {
 public:
  // A new section; tags are at most 8 ASCII characters, each used once.
  SectionWriter& section(std::string_view tag);
  // Writes the file whole or not at all: to a temporary name unique to this process and call
  // (PATH.tmp.<pid>.<n>), flushed to the disk (fsync), then renamed over PATH; the directory is synced
  // too, so the rename survives a power cut. A previous file at PATH stays valid until the rename.
  // Throws OutputError naming the path.
  void write(const std::string& path) const;
  // The whole file as it would be written.
  std::string bytes() const;

 private:
  std::vector<std::pair<std::string, SectionWriter>> sections_;
};

// One section's payload, read value by value; every read past its end, and every count that the bytes
// left cannot hold, is a CheckpointError naming the file and the section.
class SectionReader {
 public:
  SectionReader(std::string_view data, std::string file, std::string tag)
      : data_(data), file_(std::move(file)), tag_(std::move(tag)) {}
  std::uint8_t u8() { return value<std::uint8_t>(); }
  std::uint16_t u16() { return value<std::uint16_t>(); }
  std::uint32_t u32() { return value<std::uint32_t>(); }
  std::int32_t i32() { return value<std::int32_t>(); }
  std::int64_t i64() { return value<std::int64_t>(); }
  double f64() { return value<double>(); }
  bool boolean();
  std::string text();
  // A count of items that take at least `bytes_each` bytes each (>= 1): at most what is left.
  std::size_t count(std::size_t bytes_each);
  template <class T>
  std::vector<T> array() {
    static_assert(std::is_arithmetic_v<T>);
    std::vector<T> v(count(sizeof(T)));
    raw(v.data(), v.size() * sizeof(T));
    return v;
  }
  void raw(void* p, std::size_t n);
  std::size_t left() const { return data_.size() - at_; }
  // Every byte read (a section longer than its reader expects is from another writer).
  void finish() const;
  [[noreturn]] void fail(const std::string& what) const;
  const std::string& file() const { return file_; }

 private:
  template <class T>
  T value() {
    T v;
    raw(&v, sizeof v);
    return v;
  }
  std::string_view data_;
  std::size_t at_ = 0;
  std::string file_, tag_;
};

class CheckpointReader {
 public:
  // Reads and checks the whole file: magic, version (kOldestCheckpointVersion to kCheckpointVersion),
  // every section's length and CRC, the END section.
  explicit CheckpointReader(const std::string& path);
  CheckpointReader(const CheckpointReader&) = delete;  // the sections point into bytes_
  CheckpointReader& operator=(const CheckpointReader&) = delete;
  bool has(std::string_view tag) const { return sections_.count(std::string(tag)) != 0; }
  // Throws CheckpointError when the section is missing.
  SectionReader section(std::string_view tag) const;
  const std::string& path() const { return path_; }
  std::uint16_t version() const { return version_; }

 private:
  std::string path_;
  std::uint16_t version_ = 0;
  std::string bytes_;
  std::map<std::string, std::string_view> sections_;
};

}  // namespace seismpm
