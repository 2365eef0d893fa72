// The line reader under the record and table readers: a byte order mark and CRLF dropped, a cap on
// the length of a line (a file without line breaks refused fast, in bounded memory, with a short
// printable message), numbers that are whole cells, and messages that show the file's bytes safely.
#include <sys/resource.h>

#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/text_lines.hpp"

using namespace seismpm;

namespace {

std::string write_temp(const std::string& name, const std::string& bytes) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

std::vector<std::string> all_lines(const std::string& path) {
  TextLines in(path);
  std::vector<std::string> out;
  for (std::string line; in.next(line);) out.push_back(line);
  return out;
}

long peak_rss_kib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

}  // namespace

TEST_CASE("text lines: a byte order mark and CRLF are dropped, nothing else", "[io][text_lines][robustness]") {
  SECTION("a BOM before the first line, CRLF line ends, no break after the last line") {
    const auto lines = all_lines(write_temp("seismpm_tl_bom.txt", "\xEF\xBB\xBFt,v\r\n0,1\r\n\r\n1,2"));
    CHECK(lines == std::vector<std::string>{"t,v", "0,1", "", "1,2"});
  }
  SECTION("a BOM is only dropped at the start of the file; a lone CR inside a line stays") {
    const auto lines = all_lines(write_temp("seismpm_tl_bom2.txt",
                                            "a\n\xEF\xBB\xBF"
                                            "b\nc\rd\n"));
    CHECK(lines == std::vector<std::string>{"a",
                                            "\xEF\xBB\xBF"
                                            "b",
                                            "c\rd"});
  }
  SECTION("lines that straddle the 64 KiB read chunks come back whole, with their numbers") {
    std::string text;
    for (int k = 0; k < 3000; ++k) text += std::string(50, 'a' + k % 26) + "\r\n";
    TextLines in(write_temp("seismpm_tl_chunks.txt", text));
    std::string line;
    int n = 0, wrong = 0;
    while (in.next(line)) {
      wrong += line != std::string(50, 'a' + n % 26);
      CHECK(in.number() == ++n);
    }
    CHECK(n == 3000);
    CHECK(wrong == 0);
    CHECK(in.where() == in.file() + ":3000: ");
  }
  SECTION("an empty file has no lines; a missing one is an error naming it") {
    CHECK(all_lines(write_temp("seismpm_tl_empty.txt", "")).empty());
    CHECK_THROWS_WITH(TextLines("/nonexistent/seismpm.txt"), Catch::Contains("/nonexistent/seismpm.txt: cannot open"));
  }
}

TEST_CASE("text lines: a line without a break is refused fast, in bounded memory, with a short printable message",
          "[io][text_lines][robustness]") {
  // 40 MiB of binary-looking bytes, no line break (a 2 GiB one is the same: the reader stops at the cap).
  std::string bytes(40u << 20, 'x');
  for (std::size_t k = 0; k < bytes.size(); k += 7) bytes[k] = static_cast<char>(k % 256 == '\n' ? 0 : k % 256);
  const std::string path = write_temp("seismpm_tl_long.bin", bytes);
  bytes = std::string();
  const long rss_before = peak_rss_kib();
  const auto start = std::chrono::steady_clock::now();
  std::string message;
  try {
    TextLines in(path);
    std::string line;
    while (in.next(line)) {
    }
  } catch (const InputError& e) {
    message = e.what();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const long grown_kib = peak_rss_kib() - rss_before;
  CAPTURE(message, seconds, grown_kib);
  CHECK_THAT(message, Catch::StartsWith(path + ":1: line longer than 1 MiB"));
  CHECK(seconds < 1.0);
  CHECK(message.size() < 300 + path.size());
  bool printable_only = true;
  for (const char c : message) printable_only = printable_only && c >= 0x20 && c < 0x7f;
  CHECK(printable_only);
  // A reader that gathered the whole line (std::getline) would have grown by 40 MiB. (When an earlier
  // test already peaked higher this reads 0, which proves nothing but fails nothing.)
  CHECK(grown_kib < 8 * 1024);
  std::filesystem::remove(path);
}

TEST_CASE("text lines: a line of exactly the cap is read, one byte more is not", "[io][text_lines][robustness]") {
  const std::string path = write_temp("seismpm_tl_cap.txt", std::string(TextLines::kMaxLine, '1') + "\n" +
                                                                std::string(TextLines::kMaxLine + 1, '2') + "\n");
  TextLines in(path);
  std::string line;
  REQUIRE(in.next(line));
  CHECK(line.size() == TextLines::kMaxLine);
  CHECK_THROWS_WITH(in.next(line), Catch::Contains(path + ":2: line longer than 1 MiB"));
}

TEST_CASE("parse_number takes whole cells only", "[io][text_lines][robustness]") {
  double v = 0;
  SECTION("numbers") {
    for (const char* text : {"1.5", "-2e-3", "+7", "0", "1E+5", ".5"}) {
      CAPTURE(text);
      CHECK(parse_number(text, v));
    }
    CHECK(parse_number("-2e-3", v));
    CHECK(v == -2e-3);
  }
  SECTION("not numbers: tails, NUL bytes, blanks, overflow, inf and nan") {
    using namespace std::string_literals;
    // strtod on c_str() stops at the first NUL and so took "1.5\0\0" for 1.5.
    for (const std::string& text : {"1.5\0\0"s, "1.5\0x"s, "\0"s, "1.5abc"s, "1.5 "s, " 1.5"s, "1,5"s, ""s, "1e999"s,
                                    "-1e999"s, "inf"s, "nan"s, "0x"s, std::string(300, '1')}) {
      CAPTURE(printable(text));
      CHECK_FALSE(parse_number(text, v));
    }
  }
}

TEST_CASE("printable shows control bytes and cuts long text", "[io][text_lines][robustness]") {
  using namespace std::string_literals;
  CHECK(printable("a\0b\tc\r\n\x7f\xff"s) == "a\\x00b\\tc\\r\\n\\x7f\\xff");
  CHECK(printable(std::string(100, 'a'), 10) == std::string(10, 'a') + "...");
  CHECK(printable(std::string(10, 'a'), 10) == std::string(10, 'a'));
}
