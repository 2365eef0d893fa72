#include "text_lines.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "core/error.hpp"

namespace seismpm {

namespace {
constexpr std::size_t kChunk = 64 * 1024;
constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
}  // namespace

TextLines::TextLines(std::string file) : file_(std::move(file)), in_(std::fopen(file_.c_str(), "rb"), &std::fclose) {
  if (!in_) throw InputError(file_ + ": cannot open (" + std::strerror(errno) + ")");
  struct stat st {};
  if (fstat(fileno(in_.get()), &st) == 0 && S_ISREG(st.st_mode)) size_ = static_cast<std::uintmax_t>(st.st_size);
  chunk_.resize(kChunk);
}

std::string TextLines::where() const { return file_ + ":" + std::to_string(number_) + ": "; }

bool TextLines::fill() {
  if (eof_) return false;
  end_ = std::fread(chunk_.data(), 1, chunk_.size(), in_.get());
  pos_ = 0;
  if (end_ == 0) {
    if (std::ferror(in_.get())) throw InputError(file_ + ": read error (" + std::strerror(errno) + ")");
    eof_ = true;
    return false;
  }
  return true;
}

bool TextLines::next(std::string& line) {
  line.clear();
  bool any = false;
  for (;;) {
    if (pos_ == end_ && !fill()) break;
    any = true;
    const char* start = chunk_.data() + pos_;
    const auto* nl = static_cast<const char*>(std::memchr(start, '\n', end_ - pos_));
    const std::size_t n = nl ? static_cast<std::size_t>(nl - start) : end_ - pos_;
    if (line.size() + n > kMaxLine) {
      ++number_;
      throw InputError(where() + "line longer than 1 MiB (it starts '" +
                       printable(line + std::string(start, n < 40 ? n : 40)) + "'): not a text record or table");
    }
    line.append(start, n);
    pos_ += n;
    if (nl) {
      ++pos_;
      break;
    }
  }
  if (!any) return false;
  ++number_;
  if (number_ == 1 && line.compare(0, kByteOrderMark.size(), kByteOrderMark) == 0) line.erase(0, kByteOrderMark.size());
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return true;
}

std::string printable(std::string_view text, std::size_t max) {
  std::string out;
  std::size_t shown = 0;
  for (const char ch : text) {
    if (shown++ == max) {
      out += "...";
      break;
    }
    const auto c = static_cast<unsigned char>(ch);
    if (c == '\t')
      out += "\\t";
    else if (c == '\r')
      out += "\\r";
    else if (c == '\n')
      out += "\\n";
    else if (c < 0x20 || c > 0x7e) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else
      out += ch;
  }
  return out;
}

bool parse_number(std::string_view text, double& out) {
  if (text.empty() || text.size() > 256) return false;
  const std::string cell(text);  // strtod needs the terminating NUL; a NUL inside ends the number early
  char* end = nullptr;
  errno = 0;
  out = std::strtod(cell.c_str(), &end);
  return end == cell.c_str() + cell.size() && errno != ERANGE && std::isfinite(out) &&
         !std::isspace(static_cast<unsigned char>(cell[0]));
}

}  // namespace seismpm
