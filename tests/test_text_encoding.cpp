// Names that are not UTF-8 (issue 28): is_utf8 follows RFC 3629, utf8_from_windows1252 reads
// the other bytes as Windows-1252 (expected code points from unicode.org's CP1252.TXT), and the
// log reader makes header names UTF-8 once, says so, and still finds a column by either name.
#include <fstream>
#include <string>

#include "sigmatau/error.hpp"
#include "sigmatau/log_reader.hpp"
#include "sigmatau/text_encoding.hpp"
#include "temp_dir.hpp"
#include "test_support.hpp"

using namespace sigmatau;

TEST_CASE("is_utf8 accepts well-formed UTF-8 and refuses every other byte sequence") {
  CHECK(is_utf8(""));
  CHECK(is_utf8("gyro_x deg/s"));
  CHECK(is_utf8("temp \xC2\xB0"
                "C"));                           // U+00B0 DEGREE SIGN
  CHECK(is_utf8("\xE2\x82\xAC"));                // U+20AC EURO SIGN
  CHECK(is_utf8("\xF0\x9F\x98\x80"));            // U+1F600, 4 bytes
  CHECK_FALSE(is_utf8("temp \xB0"
                      "C"));                     // Latin-1 degree sign
  CHECK_FALSE(is_utf8("\xC0\xAF"));              // overlong '/'
  CHECK_FALSE(is_utf8("\xE0\x80\xAF"));          // overlong, 3 bytes
  CHECK_FALSE(is_utf8("\xED\xA0\x80"));          // U+D800, a surrogate
  CHECK_FALSE(is_utf8("\xF4\x90\x80\x80"));      // above U+10FFFF
  CHECK_FALSE(is_utf8("\xE2\x82"));              // cut short
  CHECK_FALSE(is_utf8("\x80"));                  // a lone continuation byte
}

TEST_CASE("bytes that are not UTF-8 are read as Windows-1252, UTF-8 is kept") {
  CHECK(utf8_from_windows1252("temp \xB0"
                              "C") == "temp \xC2\xB0"
                                      "C");                          // ° U+00B0
  CHECK(utf8_from_windows1252("\xB5g") == "\xC2\xB5g");              // µ U+00B5
  CHECK(utf8_from_windows1252("caf\xE9") == "caf\xC3\xA9");          // é U+00E9
  CHECK(utf8_from_windows1252("\x80") == "\xE2\x82\xAC");            // € U+20AC
  CHECK(utf8_from_windows1252("\x92") == "\xE2\x80\x99");            // ’ U+2019
  CHECK(utf8_from_windows1252("\x9F") == "\xC5\xB8");                // Ÿ U+0178
  CHECK(utf8_from_windows1252("\x81\x8D\x8F\x90\x9D") ==
        "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD");  // undefined: U+FFFD
  // Mixed: the UTF-8 degree sign stays, the Latin-1 one is transcoded.
  CHECK(utf8_from_windows1252("\xC2\xB0/\xB0") == "\xC2\xB0/\xC2\xB0");
  const std::string utf8 = "\xCE\xBC"
                           "rad \xE2\x88\x9A"
                           "h";
  CHECK(utf8_from_windows1252(utf8) == utf8);
  for (int b = 0x80; b <= 0xFF; ++b) {
    const std::string one(1, static_cast<char>(b));
    INFO("byte " << b);
    CHECK(is_utf8(utf8_from_windows1252(one)));
  }
}

TEST_CASE("escape_non_utf8 shows the bytes a file holds, in UTF-8") {
  CHECK(escape_non_utf8("temp \xB0"
                        "C") == "temp \\xB0C");
  CHECK(escape_non_utf8("temp \xC2\xB0"
                        "C") == "temp \xC2\xB0"
                                "C");
  CHECK(escape_non_utf8("a\tb") == "a\\x09b");
}

TEST_CASE("a header name that is not UTF-8 is read as Windows-1252, said, and found both ways") {
  test::TempDir dir("sigmatau_test_text_encoding");
  const std::string path = dir.file("latin1.csv").string();
  {
    std::ofstream out(path, std::ios::binary);
    out << "t,gx,temp \xB0"
           "C\n0,1,25\n0.01,2,25.5\n0.02,3,26\n";
  }
  LogOptions options;
  options.path = path;
  options.time_column = "t";
  const Log all = read_log(options);
  REQUIRE(all.channel_names.size() == 2);
  CHECK(all.channel_names[1] == "temp \xC2\xB0"
                                "C");
  REQUIRE(all.timing.warnings.size() == 1);
  CHECK(all.timing.warnings[0] ==
        "the name of column 2, \"temp \\xB0C\", is not UTF-8: it is read as Windows-1252 "
        "(Latin-1), \"temp \xC2\xB0"
        "C\"");
  // As typed in a UTF-8 terminal, and as the bytes of the file.
  for (const std::string& name : {std::string("temp \xC2\xB0"
                                             "C"),
                                 std::string("temp \xB0"
                                             "C")}) {
    options.columns = {name};
    const Log one = read_log(options);
    REQUIRE(one.channels.size() == 1);
    CHECK(one.channels[0][2] == 26);
  }
  // An unselected column's name is not worth a warning.
  options.columns = {"gx"};
  CHECK(read_log(options).timing.warnings.empty());
  // An unknown name lists the columns in UTF-8 and quotes the asked one's bytes escaped.
  options.columns = {"x\xB0"};
  CHECK_THROWS_WITH_AS(read_log(options),
                       doctest::Contains("unknown column \"x\\xB0\" (available: t, gx, temp \xC2\xB0"
                                         "C)"),
                       ParseError);
}

TEST_CASE("a time column named in Windows-1252 is found by its name, with its unit") {
  test::TempDir dir("sigmatau_test_text_encoding");
  const std::string path = dir.file("latin1_time.csv").string();
  {
    std::ofstream out(path, std::ios::binary);
    out << "t [\xB5s],gx\n0,1\n10000,2\n20000,3\n";  // µ as the byte 0xB5: "t [µs]"
  }
  LogOptions options;
  options.path = path;
  options.find_time_column = true;
  const Log log = read_log(options);
  REQUIRE(log.channel_names.size() == 1);
  CHECK(log.channel_names[0] == "gx");
  REQUIRE(log.t_s.size() == 3);
  CHECK(log.t_s[2] == 0.02);  // 20000 us
  CHECK(log.timing.header.time_column_found == "t [\xC2\xB5s]");
}
