#include "netlist/text_encoding.h"

#include <cstdint>

namespace lcs::parse {
namespace {

void append_utf8(std::string& out, std::uint32_t c) {
  if (c < 0x80) {
    out += static_cast<char>(c);
  } else if (c < 0x800) {
    out += static_cast<char>(0xC0 | (c >> 6));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    out += static_cast<char>(0xE0 | (c >> 12));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (c >> 18));
    out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  }
}

std::string from_utf16(const std::string& bytes, std::size_t start, bool little_endian) {
  std::string out;
  out.reserve(bytes.size() / 2);
  auto unit = [&](std::size_t k) -> std::uint32_t {
    const auto lo = static_cast<unsigned char>(bytes[k + (little_endian ? 0 : 1)]);
    const auto hi = static_cast<unsigned char>(bytes[k + (little_endian ? 1 : 0)]);
    return static_cast<std::uint32_t>(hi) << 8 | lo;
  };
  for (std::size_t k = start; k + 1 < bytes.size(); k += 2) {
    std::uint32_t c = unit(k);
    if (c >= 0xD800 && c < 0xDC00 && k + 3 < bytes.size()) {  // a surrogate pair
      const std::uint32_t low = unit(k + 2);
      if (low >= 0xDC00 && low < 0xE000) {
        c = 0x10000 + ((c - 0xD800) << 10) + (low - 0xDC00);
        k += 2;
      }
    }
    append_utf8(out, c);
  }
  return out;
}

// The length of the valid UTF-8 sequence at s[k], 0 where none starts there.
std::size_t utf8_sequence(const std::string& s, std::size_t k) {
  const auto b = static_cast<unsigned char>(s[k]);
  const std::size_t extra = b < 0x80 ? 0 : (b >> 5) == 0x6 ? 1 : (b >> 4) == 0xE ? 2 : (b >> 3) == 0x1E ? 3 : 4;
  if (extra == 4 || k + extra >= s.size()) return extra == 0 ? 1 : 0;
  for (std::size_t j = 1; j <= extra; ++j)
    if ((static_cast<unsigned char>(s[k + j]) & 0xC0) != 0x80) return 0;
  return 1 + extra;
}

// Windows-1252's 0x80-0x9F; the rest of its upper half is Latin-1 (the code point is the byte).
constexpr std::uint16_t kCp1252High[32] = {
    0x20AC, 0x81,   0x201A, 0x0192, 0x201E, 0x2026, 0x2020, 0x2021, 0x02C6, 0x2030, 0x0160,
    0x2039, 0x0152, 0x8D,   0x017D, 0x8F,   0x90,   0x2018, 0x2019, 0x201C, 0x201D, 0x2022,
    0x2013, 0x2014, 0x02DC, 0x2122, 0x0161, 0x203A, 0x0153, 0x9D,   0x017E, 0x0178};

}  // namespace

std::string to_utf8(const std::string& bytes) {
  if (bytes.size() >= 2) {
    const auto b0 = static_cast<unsigned char>(bytes[0]), b1 = static_cast<unsigned char>(bytes[1]);
    if (b0 == 0xFF && b1 == 0xFE) return from_utf16(bytes, 2, true);
    if (b0 == 0xFE && b1 == 0xFF) return from_utf16(bytes, 2, false);
    // Without a mark: a deck starts with an ASCII character (a title or a comment), whose
    // zero high byte comes second in little-endian order and first in big-endian.
    if (bytes.size() >= 4 && b0 != 0 && b0 < 0x80 && b1 == 0 && bytes[3] == 0) return from_utf16(bytes, 0, true);
    if (bytes.size() >= 4 && b0 == 0 && b1 != 0 && b1 < 0x80 && bytes[2] == 0) return from_utf16(bytes, 0, false);
  }
  // UTF-8 sequences are kept; each byte that starts none is a Windows-1252 character (a deck with
  // a UTF-8 "1µF" and a Latin-1 degree sign in a comment keeps both).
  std::string out;
  out.reserve(bytes.size() + bytes.size() / 8);
  for (std::size_t k = 0; k < bytes.size();) {
    const std::size_t length = utf8_sequence(bytes, k);
    if (length > 0) {
      out.append(bytes, k, length);
      k += length;
      continue;
    }
    const auto b = static_cast<unsigned char>(bytes[k++]);
    append_utf8(out, b >= 0x80 && b < 0xA0 ? kCp1252High[b - 0x80] : b);
  }
  return out;
}

}  // namespace lcs::parse
