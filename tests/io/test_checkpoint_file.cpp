// The checkpoint container: values round-trip bit for bit, the file is written atomically, and every
// damaged file (missing, short, another magic or version, a CRC mismatch, truncated, a count larger
// than its bytes) is a CheckpointError naming the file, never a crash or a huge allocation.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "io/checkpoint_file.hpp"

using namespace seismpm;

namespace {

std::string temp_file(const char* name) {
  const auto dir = std::filesystem::temp_directory_path() / "seismpm_checkpoint_file";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

void write_bytes(const std::string& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << bytes;
}

CheckpointWriter sample() {
  CheckpointWriter w;
  SectionWriter& a = w.section("VALUES");
  a.u8(7);
  a.i32(-5);
  a.i64(1LL << 40);
  a.f64(-0.0);
  a.f64(std::numeric_limits<double>::denorm_min());
  a.text("caf\xc3\xa9");
  a.array(std::vector<double>{1.0, 0.1, 1e300});
  w.section("EMPTY");
  return w;
}

}  // namespace

TEST_CASE("checkpoint file: CRC-32 is zlib's", "[io][checkpoint]") {
  CHECK(crc32("123456789", 9) == 0xCBF43926u);
  CHECK(crc32("", 0) == 0u);
}

TEST_CASE("checkpoint file: values round-trip bit for bit", "[io][checkpoint]") {
  const std::string file = temp_file("values.chk");
  sample().write(file);
  const CheckpointReader r(file);
  CHECK(r.has("VALUES"));
  CHECK(r.has("EMPTY"));
  CHECK_FALSE(r.has("OTHER"));
  SectionReader s = r.section("VALUES");
  CHECK(s.u8() == 7);
  CHECK(s.i32() == -5);
  CHECK(s.i64() == (1LL << 40));
  const double z = s.f64();
  CHECK((z == 0.0 && std::signbit(z)));
  CHECK(s.f64() == std::numeric_limits<double>::denorm_min());
  CHECK(s.text() == "caf\xc3\xa9");
  CHECK(s.array<double>() == std::vector<double>{1.0, 0.1, 1e300});
  s.finish();
  CHECK_THROWS_WITH(s.u8(),
                    Catch::Contains(file) && Catch::Contains("section VALUES") && Catch::Contains("ends early"));
  CHECK_THROWS_WITH(r.section("OTHER"), Catch::Contains("no section OTHER"));
  // No temporary file is left beside it.
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(file).parent_path()))
    files += e.path().filename().string().rfind("values.chk", 0) == 0;
  CHECK(files == 1);
}

TEST_CASE("checkpoint file: damaged files are named errors", "[io][checkpoint][robustness]") {
  const std::string file = temp_file("damaged.chk");
  const std::string good = sample().bytes();
  const auto error_of = [&](const std::string& bytes) {
    write_bytes(file, bytes);
    try {
      CheckpointReader r(file);
      SectionReader s = r.section("VALUES");
      s.u8(), s.i32(), s.i64(), s.f64(), s.f64(), s.text(), s.array<double>(), s.finish();
    } catch (const CheckpointError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(error_of(good).empty());

  SECTION("missing") {
    std::filesystem::remove(file);
    CHECK_THROWS_WITH(CheckpointReader(file), Catch::Contains(file) && Catch::Contains("cannot open"));
  }
  SECTION("empty or shorter than the header") {
    CHECK_THAT(error_of(""), Catch::Contains(file) && Catch::Contains("too short"));
    CHECK_THAT(error_of(good.substr(0, 12)), Catch::Contains("too short"));
  }
  SECTION("another magic") {
    std::string bad = good;
    bad[3] = 'X';
    CHECK_THAT(error_of(bad), Catch::Contains("not a seismpm checkpoint"));
    CHECK_THAT(error_of(std::string(100, '\0')), Catch::Contains("not a seismpm checkpoint"));
  }
  SECTION("another format version") {
    std::string bad = good;
    bad[10] = 99;
    CHECK_THAT(error_of(bad), Catch::Contains("format version 99") && Catch::Contains("reads versions 2 to 3"));
    bad[10] = 1;  // before APIC
    CHECK_THAT(error_of(bad), Catch::Contains("format version 1"));
  }
  SECTION("a changed byte: CRC mismatch") {
    std::string bad = good;
    bad[16 + 8 + 8 + 2] ^= 0x10;  // inside the first payload
    CHECK_THAT(error_of(bad), Catch::Contains("section VALUES is corrupt (CRC-32 mismatch)"));
  }
  SECTION("truncated anywhere") {
    for (std::size_t n = 16; n < good.size(); ++n) {
      CAPTURE(n);
      const std::string e = error_of(good.substr(0, n));
      CHECK_THAT(e, Catch::Contains(file) && Catch::Contains("truncated"));
    }
  }
  SECTION("bytes after the end") { CHECK_THAT(error_of(good + "x"), Catch::Contains("1 bytes after the END section")); }
  SECTION("a length that claims more than the file") {
    std::string bad = good;
    const std::uint64_t huge = 1ull << 62;
    std::memcpy(&bad[16 + 8], &huge, 8);
    CHECK_THAT(error_of(bad), Catch::Contains("truncated: section VALUES claims"));
  }
  SECTION("a count larger than its bytes, CRC intact: refused before any allocation") {
    CheckpointWriter w;
    SectionWriter& s = w.section("VALUES");
    s.i64((std::int64_t{1} << 60) + 1000);  // "2^60 doubles follow"; read as a text length: 1000 bytes
    s.f64(1.0);
    write_bytes(file, w.bytes());
    const CheckpointReader r(file);
    SectionReader v = r.section("VALUES");
    CHECK_THROWS_WITH(v.array<double>(), Catch::Contains("is more than its 8 bytes left can hold"));
    SectionReader t = r.section("VALUES");
    CHECK_THROWS_WITH(t.text(), Catch::Contains("runs past the section's end"));
    SectionReader c = r.section("VALUES");
    CHECK_THROWS_WITH(c.count(1), Catch::Contains("more than"));
  }
}

TEST_CASE("checkpoint file: a failed write leaves the previous file as it was", "[io][checkpoint][robustness]") {
  const std::string file = temp_file("kept.chk");
  sample().write(file);
  const auto before = std::filesystem::file_size(file);
  CHECK_THROWS(sample().write(temp_file("no_such_dir/x.chk")));
  CHECK(std::filesystem::file_size(file) == before);
  CHECK_NOTHROW(CheckpointReader(file));
}
