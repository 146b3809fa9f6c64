#include "ngspice/ngspice_deck.h"

#include <cctype>

namespace lcs::ngspice_deck {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\f' || c == '\v' || c == '\r'; }

std::string_view trim_left(std::string_view s) {
  size_t i = 0;
  while (i < s.size() && is_blank(s[i])) ++i;
  return s.substr(i);
}

// Case-insensitive: does `line` (after leading blanks) start with the dot card `card`, followed
// by the end of the line or a blank?
bool starts_with_card(std::string_view line, std::string_view card) {
  line = trim_left(line);
  if (line.size() < card.size()) return false;
  for (size_t i = 0; i < card.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(line[i])) != card[i]) return false;
  return line.size() == card.size() || is_blank(line[card.size()]) || line[card.size()] == '\n';
}

void split_lines(const std::string& entry, std::vector<std::string>& out) {
  size_t start = 0;
  while (true) {
    size_t nl = entry.find('\n', start);
    std::string line = entry.substr(start, nl == std::string::npos ? std::string::npos : nl - start);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    out.push_back(std::move(line));
    if (nl == std::string::npos) return;
    start = nl + 1;
  }
}

}  // namespace

bool is_end_card(std::string_view line) { return starts_with_card(line, ".end"); }

PreparedDeck prepare(const std::vector<std::string>& deck) {
  PreparedDeck result;
  std::vector<std::string> lines;
  for (const std::string& entry : deck) split_lines(entry, lines);
  if (lines.empty() || (lines.size() == 1 && trim_left(lines[0]).empty())) {
    result.error = "the deck is empty";
    return result;
  }

  // The title: ngspice's collector drops blank lines (the next card would become the title) and
  // acts on a `.end` wherever it appears, even in the title.
  if (trim_left(lines[0]).empty() || is_end_card(lines[0])) lines[0] = "untitled";
  result.lines.push_back(lines[0]);

  bool ended = false;
  for (size_t i = 1; i < lines.size() && !ended; ++i) {
    const std::string& line = lines[i];
    if (starts_with_card(line, ".control") || starts_with_card(line, ".endc")) {
      result.error = "line " + std::to_string(i + 1) + ": `" + std::string(trim_left(line)) +
                     "`: .control blocks are not supported (the bridge runs the deck's .tran card; "
                     "ngspice would execute the block unbounded inside the load)";
      result.lines.clear();
      return result;
    }
    result.lines.push_back(line);
    ended = is_end_card(line);
  }
  if (!ended) result.lines.push_back(".end");
  return result;
}

}  // namespace lcs::ngspice_deck
