// Where something came from in the input, and the errors that point at it.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace lcs {

struct SourceLocation {
  std::string file;       // path as given (or as resolved for .include)
  int line = 0;           // 1-based; 0: unknown
  int column = 0;         // 1-based column of the offending token; 0: whole line
  int length = 1;         // length of the token, for the caret underline
  std::string line_text;  // the physical source line, without newline

  bool known() const { return line > 0; }
};

// "FILE:LINE:COL: <severity>: message", then the line and a caret (^~~~) under the token.
// Without a known location: "FILE: <severity>: message" (or just "<severity>: message").
std::string format_diagnostic(const SourceLocation& loc, const std::string& severity,
                              const std::string& message);

// An error in the user's input: exit code 2 (SPEC §4).
class NetlistError : public std::runtime_error {
 public:
  NetlistError(SourceLocation loc, const std::string& message);
  const SourceLocation& location() const { return loc_; }
  const std::string& message() const { return message_; }
  std::string formatted() const { return format_diagnostic(loc_, "error", message_); }

 private:
  SourceLocation loc_;
  std::string message_;
};

// A file that cannot be read at the top level (missing netlist): a usage error, exit 1.
class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace lcs
