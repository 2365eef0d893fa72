#include "checkpoint_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <bit>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "atomic_file.hpp"

namespace seismpm {

// The values are copied as the machine holds them; the format is little-endian.
static_assert(std::endian::native == std::endian::little, "checkpoints are written on little-endian machines only");

namespace {

constexpr std::size_t kTagBytes = 8;
constexpr std::size_t kHeaderBytes = 16;                     // magic, version, reserved
constexpr std::size_t kSectionOverhead = kTagBytes + 8 + 4;  // tag, length, CRC
constexpr std::string_view kEndTag = "END";

std::array<std::uint32_t, 256> crc_table() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[n] = c;
  }
  return t;
}

std::string padded_tag(std::string_view tag) {
  std::string t(tag);
  t.resize(kTagBytes, '\0');
  return t;
}

template <class T>
void append(std::string& out, T v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

std::string section_bytes(std::string_view tag, const std::string& payload) {
  std::string s = padded_tag(tag);
  append<std::uint64_t>(s, payload.size());
  s += payload;
  append<std::uint32_t>(s, crc32(s.data(), s.size()));
  return s;
}

// write(2) until done; false on an error.
bool write_all(int fd, const std::string& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

std::uint32_t crc32(const void* data, std::size_t size, std::uint32_t crc) {
  static const auto table = crc_table();
  const auto* p = static_cast<const unsigned char*>(data);
  crc = ~crc;
  for (std::size_t k = 0; k < size; ++k) crc = table[(crc ^ p[k]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

// ---------------------------------------------------------------- writing

void SectionWriter::text(std::string_view s) {
  u32(static_cast<std::uint32_t>(s.size()));
  raw(s.data(), s.size());
}

void SectionWriter::raw(const void* p, std::size_t n) {
  if (n) bytes_.append(static_cast<const char*>(p), n);
}

SectionWriter& CheckpointWriter::section(std::string_view tag) {
  if (tag.empty() || tag.size() > kTagBytes || tag == kEndTag)
    throw std::invalid_argument("checkpoint: bad section tag '" + std::string(tag) + "'");
  for (const auto& s : sections_)
    if (s.first == tag) throw std::invalid_argument("checkpoint: section '" + std::string(tag) + "' written twice");
  sections_.emplace_back(std::string(tag), SectionWriter{});
  return sections_.back().second;
}

std::string CheckpointWriter::bytes() const {
  std::string out(kCheckpointMagic);
  append<std::uint16_t>(out, kCheckpointVersion);
  append<std::uint32_t>(out, 0);
  for (const auto& [tag, section] : sections_) out += section_bytes(tag, section.bytes());
  out += section_bytes(kEndTag, "");
  return out;
}

void CheckpointWriter::write(const std::string& path) const {
  static std::atomic<unsigned long> serial{0};
  const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(serial++);
  const std::string bytes = this->bytes();
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw OutputError("cannot write the checkpoint " + path + ": " + std::strerror(errno));
  const bool ok = write_all(fd, bytes) && ::fsync(fd) == 0;
  const int err = errno;
  if (::close(fd) != 0 || !ok) {
    std::remove(tmp.c_str());
    throw OutputError("cannot write the checkpoint " + path + ": " + std::strerror(ok ? errno : err) + " (disk full?)");
  }
  commit_file(tmp, path);
  // The rename itself reaches the disk with the directory.
  std::string dir = std::filesystem::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

// ---------------------------------------------------------------- reading

bool SectionReader::boolean() {
  const std::uint8_t v = u8();
  if (v > 1) fail("a truth value is " + std::to_string(v));
  return v == 1;
}

std::string SectionReader::text() {
  const std::size_t n = u32();
  if (n > left()) fail("a text of " + std::to_string(n) + " bytes runs past the section's end");
  std::string s(data_.substr(at_, n));
  at_ += n;
  return s;
}

std::size_t SectionReader::count(std::size_t bytes_each) {
  const std::int64_t n = i64();
  if (n < 0 || static_cast<std::uint64_t>(n) > left() / std::max<std::size_t>(bytes_each, 1))
    fail("a count of " + std::to_string(n) + " items is more than its " + std::to_string(left()) +
         " bytes left can hold");
  return static_cast<std::size_t>(n);
}

void SectionReader::raw(void* p, std::size_t n) {
  if (n > left()) fail("it ends early (" + std::to_string(left()) + " bytes left, " + std::to_string(n) + " wanted)");
  if (n) std::memcpy(p, data_.data() + at_, n);
  at_ += n;
}

void SectionReader::finish() const {
  if (left() != 0) fail(std::to_string(left()) + " bytes more than this version of seismpm reads");
}

void SectionReader::fail(const std::string& what) const {
  throw CheckpointError("checkpoint " + file_ + ": section " + tag_ + ": " + what);
}

CheckpointReader::CheckpointReader(const std::string& path) : path_(path) {
  const auto bad = [&](const std::string& what) { return CheckpointError("checkpoint " + path + ": " + what); };
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw bad("is a directory, not a checkpoint file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw bad(std::string("cannot open it: ") + std::strerror(errno));
  bytes_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (in.bad()) throw bad("cannot read it");
  if (bytes_.size() < kHeaderBytes)
    throw bad("too short for a checkpoint (" + std::to_string(bytes_.size()) + " bytes; truncated?)");
  if (std::string_view(bytes_).substr(0, kCheckpointMagic.size()) != kCheckpointMagic)
    throw bad("not a seismpm checkpoint (it does not start with SEISMPMCHK)");
  std::uint16_t version;
  std::memcpy(&version, bytes_.data() + kCheckpointMagic.size(), 2);
  if (version < kOldestCheckpointVersion || version > kCheckpointVersion)
    throw bad("format version " + std::to_string(version) + ", but this seismpm reads versions " +
              std::to_string(kOldestCheckpointVersion) + " to " + std::to_string(kCheckpointVersion));
  version_ = version;
  std::size_t at = kHeaderBytes;
  for (;;) {
    if (bytes_.size() - at < kSectionOverhead)
      throw bad("truncated: it ends at byte " + std::to_string(bytes_.size()) + " inside a section header (no END)");
    std::string tag(bytes_.data() + at, kTagBytes);
    tag.resize(tag.find('\0') == std::string::npos ? kTagBytes : tag.find('\0'));
    std::uint64_t length;
    std::memcpy(&length, bytes_.data() + at + kTagBytes, 8);
    if (length > bytes_.size() - at - kSectionOverhead)
      throw bad("truncated: section " + tag + " claims " + std::to_string(length) + " bytes, the file holds " +
                std::to_string(bytes_.size() - at - kSectionOverhead) + " more");
    const std::size_t payload = at + kTagBytes + 8;
    std::uint32_t stored;
    std::memcpy(&stored, bytes_.data() + payload + length, 4);
    if (crc32(bytes_.data() + at, kTagBytes + 8 + length) != stored)
      throw bad("section " + tag + " is corrupt (CRC-32 mismatch)");
    if (sections_.count(tag)) throw bad("section " + tag + " appears twice");
    at = payload + length + 4;
    if (tag == kEndTag) break;
    sections_[tag] = std::string_view(bytes_).substr(payload, length);
  }
  if (at != bytes_.size()) throw bad(std::to_string(bytes_.size() - at) + " bytes after the END section");
}

SectionReader CheckpointReader::section(std::string_view tag) const {
  const auto it = sections_.find(std::string(tag));
  if (it == sections_.end()) throw CheckpointError("checkpoint " + path_ + ": no section " + std::string(tag));
  return SectionReader(it->second, path_, std::string(tag));
}

}  // namespace seismpm
