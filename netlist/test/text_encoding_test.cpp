// Netlists in the encodings simulators' front ends save them in (netlist/text_encoding.h).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "netlist/text_encoding.h"

namespace lcs {
namespace {

namespace fs = std::filesystem;

const std::string kDeck = "lt\nV1 a 0 SIN(0 1 1k)\nR1 a b 1k\nC1 b 0 10\xc2\xb5\n.tran 10u 2m\n.end\n";

std::string utf16le(const std::string& ascii_or_utf8, bool bom) {
  std::string out = bom ? std::string("\xff\xfe") : std::string();
  for (std::size_t k = 0; k < ascii_or_utf8.size(); ++k) {
    unsigned c = static_cast<unsigned char>(ascii_or_utf8[k]);
    if (c == 0xC2) c = static_cast<unsigned char>(ascii_or_utf8[++k]);  // the deck's only non-ASCII: µ
    out += static_cast<char>(c);
    out += '\0';
  }
  return out;
}

std::string utf16be(const std::string& ascii_or_utf8) {
  std::string out = utf16le(ascii_or_utf8, false);
  for (std::size_t k = 0; k + 1 < out.size(); k += 2) std::swap(out[k], out[k + 1]);
  return out;
}

Netlist parse_bytes(const std::string& name, const std::string& bytes) {
  const fs::path path = fs::temp_directory_path() / ("lcspice_encoding_" + name + ".cir");
  std::ofstream(path, std::ios::binary) << bytes;
  Netlist n = parse_netlist_file(path.string());
  fs::remove(path);
  return n;
}

// LTspice XVII's UTF-16 (with and without a byte order mark), a Windows-1252 micro sign (the
// byte 0xB5) and UTF-8 all read as the same deck: C1 = 10 uF, the title and the lines' text in
// UTF-8 for the messages. Before, UTF-16 failed at line 2 ("unknown element type '\x00'") and
// 0xB5 at the value ("invalid number").
TEST(TextEncoding, Utf16AndWindows1252DecksReadAsUtf8) {
  for (const auto& [name, bytes] :
       {std::pair<std::string, std::string>{"utf8", kDeck}, {"utf16_bom", utf16le(kDeck, true)},
        {"utf16", utf16le(kDeck, false)}, {"utf16be", utf16be(kDeck)},
        {"cp1252", "lt\nV1 a 0 SIN(0 1 1k)\nR1 a b 1k\nC1 b 0 10\xb5\n.tran 10u 2m\n.end\n"}}) {
    SCOPED_TRACE(name);
    const Netlist n = parse_bytes(name, bytes);
    EXPECT_EQ(n.title, "lt");
    ASSERT_EQ(n.elements.size(), 3u);
    EXPECT_DOUBLE_EQ(n.elements[2].value, 10e-6);
    EXPECT_EQ(n.elements[2].loc.line_text, "C1 b 0 10\xc2\xb5");
  }
}

TEST(TextEncoding, ConversionsOfTheRawBytes) {
  EXPECT_EQ(parse::to_utf8("abc"), "abc");
  EXPECT_EQ(parse::to_utf8("\xef\xbb\xbf" "a"), "\xef\xbb\xbf" "a");  // UTF-8 with its mark: as it is
  EXPECT_EQ(parse::to_utf8(std::string("\xfe\xff\x00" "a\x00\xb5", 6)), "a\xc2\xb5");  // UTF-16BE
  // UTF-16BE without a mark (before: read as Windows-1252, "unknown element type '\x00'").
  EXPECT_EQ(parse::to_utf8(std::string("\x00" "a\x00\n\x00" "b", 6)), "a\nb");
  EXPECT_EQ(parse::to_utf8(std::string("\x00" "a", 2)), std::string("\x00" "a", 2));  // too short to tell
  EXPECT_EQ(parse::to_utf8(std::string("\xff\xfe\x3d\xd8\x00\xde", 6)), "\xf0\x9f\x98\x80");  // a surrogate pair
  EXPECT_EQ(parse::to_utf8("\x80 10\xb5"), "\xe2\x82\xac 10\xc2\xb5");  // Windows-1252: the euro sign, micro
  // Mixed: a UTF-8 micro sign kept, a Latin-1 degree sign (0xB0) beside it read as Windows-1252.
  EXPECT_EQ(parse::to_utf8("1\xc2\xb5" "F * 25\xb0" "C"), "1\xc2\xb5" "F * 25\xc2\xb0" "C");
  EXPECT_EQ(parse::to_utf8("a\xc2"), "a\xc3\x82");  // a sequence cut off at the end
}

}  // namespace
}  // namespace lcs
