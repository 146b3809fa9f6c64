// Netlists as simulators' front ends write them, read as UTF-8. LTspice XVII saves in UTF-16
// (little-endian, usually with a byte order mark) and older Windows tools in Windows-1252, where
// the micro sign is the single byte 0xB5; the parser reads UTF-8 (its µ is C2 B5).
#pragma once

#include <string>

namespace lcs::parse {

// `bytes` as UTF-8: UTF-16 with a byte order mark (either order) or without one (an ASCII first
// character followed by a zero byte: little-endian) is decoded; otherwise valid UTF-8 sequences
// are kept and each byte that starts none is read as Windows-1252 (its 0x80-0x9F as that code
// page's letters, the rest as Latin-1); a UTF-8 byte order mark is kept (the lexer skips it).
std::string to_utf8(const std::string& bytes);

}  // namespace lcs::parse
