// CSV tables: fields quoted as RFC 4180 writes them and read back, the same columns however the file
// is encoded (BOM, CRLF), a header-less file keeping its first row, and errors that name FILE:LINE.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/csv_table.hpp"
#include "io/text_lines.hpp"

using namespace seismpm;
using namespace std::string_literals;

namespace {

std::string write_temp(const std::string& name, const std::string& bytes) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

}  // namespace

TEST_CASE("csv fields: names with commas, quotes and spaces are quoted and read back whole", "[io][csv][robustness]") {
  const std::vector<std::string> names = {"plain", "a,b", "say \"hi\"", " padded ", "\"", "", "line\nbreak", "x.y"};
  std::string line;
  for (const auto& n : names) line += (line.empty() ? "" : ",") + csv_field(n);
  CAPTURE(line);
  CHECK(csv_field("plain") == "plain");
  CHECK(csv_field("a,b") == "\"a,b\"");
  CHECK(csv_field("say \"hi\"") == "\"say \"\"hi\"\"\"");
  // Everything but the line break reads back from one line (a line break inside quotes is refused).
  std::string one_line;
  for (std::size_t k = 0; k + 2 < names.size(); ++k) one_line += (k ? "," : "") + csv_field(names[k]);
  const auto back = split_csv_fields(one_line);
  CHECK(back == std::vector<std::string>(names.begin(), names.end() - 2));
  CHECK_THROWS_WITH(split_csv_fields("a,\"b,c"), Catch::Contains("not closed"));
  CHECK_THROWS_WITH(split_csv_fields("\"a\"x,b"), Catch::Contains("text after a quoted field"));
  CHECK(split_csv_fields(" 1 , 2,3 ") == std::vector<std::string>{"1", "2", "3"});
  CHECK(split_csv_fields("1,,") == std::vector<std::string>{"1", "", ""});
}

TEST_CASE("csv columns: the same table with a BOM, CRLF, quoted names, or no header", "[io][csv][robustness]") {
  const std::string table = "# a comment\n\"t\",\"a,b\",\"q\"\"\"\n0,10,20\n1,11,21\n";
  SECTION("by name, in every encoding") {
    for (const auto& [name, bytes] : std::vector<std::pair<std::string, std::string>>{
             {"plain", table},
             {"bom", "\xEF\xBB\xBF" + table},
             {"crlf", "\xEF\xBB\xBF# a comment\r\n\"t\",\"a,b\",\"q\"\"\"\r\n0,10,20\r\n1,11,21\r\n"}}) {
      CAPTURE(name);
      const auto c = read_csv_columns(write_temp("seismpm_csv_" + name + ".csv", bytes), {"t", "a,b", "q\""});
      CHECK(c.columns[0] == std::vector<double>{0, 1});
      CHECK(c.columns[1] == std::vector<double>{10, 11});
      CHECK(c.columns[2] == std::vector<double>{20, 21});
      CHECK(c.lines == std::vector<int>{3, 4});
    }
  }
  SECTION("by number: a header-less file with a BOM keeps its first row") {
    const auto c = read_csv_columns(write_temp("seismpm_csv_nohead.csv",
                                               "\xEF\xBB\xBF"
                                               "0,5\r\n1,6\r\n"),
                                    {CsvColumn::numbered(1), CsvColumn::numbered(2)});
    CHECK(c.columns[0] == std::vector<double>{0, 1});
    CHECK(c.columns[1] == std::vector<double>{5, 6});
    CHECK(c.lines == std::vector<int>{1, 2});
  }
  SECTION("by number, with a header line of names") {
    const auto c = read_csv_columns(write_temp("seismpm_csv_numhead.csv", table), {CsvColumn::numbered(3)});
    CHECK(c.columns[0] == std::vector<double>{20, 21});
  }
}

TEST_CASE("csv columns: bad cells are errors naming FILE:LINE", "[io][csv][robustness]") {
  auto error_of = [](const std::string& name, const std::string& bytes, std::vector<CsvColumn> columns) {
    try {
      read_csv_columns(write_temp(name, bytes), columns);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string dir = std::filesystem::temp_directory_path().string() + "/";
  SECTION("NUL bytes after a number (strtod stopped at the first one)") {
    const auto e = error_of("seismpm_csv_nul.csv", "t,v\n0,1\n1,1.5\0\0\n"s, {"t", "v"});
    CHECK_THAT(e, Catch::Contains(dir + "seismpm_csv_nul.csv:3: column 'v' is not a number ('1.5\\x00\\x00')"));
  }
  SECTION("a header-less file whose first row is broken: an error there, not a header skipped") {
    const std::vector<CsvColumn> both = {CsvColumn::numbered(1), CsvColumn::numbered(2)};
    CHECK_THAT(error_of("seismpm_csv_nul1.csv", "0,1.5\0\0\n1,2\n"s, both),
               Catch::Contains("seismpm_csv_nul1.csv:1: column 2 is not a number ('1.5\\x00\\x00')"));
    CHECK_THAT(error_of("seismpm_csv_tail1.csv", "0,1.5x\n1,2\n", both),
               Catch::Contains("seismpm_csv_tail1.csv:1: column 2 is not a number ('1.5x')"));
  }
  SECTION("a non-numeric tail") {
    const auto e = error_of("seismpm_csv_tail.csv", "t,v\r\n0,1\r\n1,2.5 m/s\r\n", {"t", "v"});
    CHECK_THAT(e, Catch::Contains(dir + "seismpm_csv_tail.csv:3: column 'v' is not a number ('2.5 m/s')"));
  }
  SECTION("a missing cell, a missing column, an unclosed quote, no rows") {
    CHECK_THAT(error_of("seismpm_csv_short.csv", "t,v\n0,1\n1\n", {"t", "v"}),
               Catch::Contains("seismpm_csv_short.csv:3: column 'v' is missing"));
    CHECK_THAT(error_of("seismpm_csv_nocol.csv", "t,\"a,b\"\n0,1\n", {"t", "a"}),
               Catch::Contains("seismpm_csv_nocol.csv:1: no column 'a' in the header"));
    CHECK_THAT(error_of("seismpm_csv_quote.csv", "t,v\n0,\"1\n", {"t", "v"}),
               Catch::Contains("seismpm_csv_quote.csv:2: a quoted field is not closed"));
    CHECK_THAT(error_of("seismpm_csv_norows.csv", "\xEF\xBB\xBFt,v\r\n", {"t", "v"}),
               Catch::Contains("seismpm_csv_norows.csv:1: no data rows after the header"));
    CHECK_THAT(error_of("seismpm_csv_empty.csv", "", {"t", "v"}), Catch::Contains("seismpm_csv_empty.csv: empty file"));
    CHECK_THAT(error_of("seismpm_csv_col3.csv", "t,v\n3,4\n", {CsvColumn::numbered(3)}),
               Catch::Contains("seismpm_csv_col3.csv:2: column 3 is missing"));
  }
  SECTION("a line over the cap, with a short message") {
    const auto e = error_of("seismpm_csv_long.csv", "t,v\n0,1\n" + std::string(3u << 20, '9'), {"t", "v"});
    CHECK_THAT(e, Catch::Contains("seismpm_csv_long.csv:3: line longer than 1 MiB"));
    CHECK(e.size() < 400);
  }
}
