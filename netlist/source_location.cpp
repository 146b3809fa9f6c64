#include "netlist/source_location.h"

#include <algorithm>

namespace lcs {

std::string format_diagnostic(const SourceLocation& loc, const std::string& severity,
                              const std::string& message) {
  std::string out;
  if (!loc.file.empty()) out += loc.file + ":";
  if (loc.known()) {
    out += std::to_string(loc.line) + ":";
    if (loc.column > 0) out += std::to_string(loc.column) + ":";
  }
  if (!out.empty()) out += " ";
  out += severity + ": " + message;
  if (loc.known() && !loc.line_text.empty()) {
    out += "\n" + loc.line_text;
    if (loc.column > 0) {
      // Keep tabs so the caret lines up under the token however the terminal expands them.
      std::string pad;
      for (int i = 0; i + 1 < loc.column && i < static_cast<int>(loc.line_text.size()); ++i)
        pad += loc.line_text[i] == '\t' ? '\t' : ' ';
      out += "\n" + pad + "^" + std::string(std::max(0, loc.length - 1), '~');
    }
  }
  return out;
}

NetlistError::NetlistError(SourceLocation loc, const std::string& message)
    : std::runtime_error(format_diagnostic(loc, "error", message)),
      loc_(std::move(loc)),
      message_(message) {}

}  // namespace lcs
