#include "netlist/lexer.h"

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace lcs::parse {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Characters that end a word (and start a token of their own, except whitespace).
bool ends_word(char c) {
  return is_space(c) || c == ',' || c == '(' || c == ')' || c == '=' || c == '{' || c == '}';
}

}  // namespace

int kicad_net_name_end(const std::string& s, int b, int i) {
  const int n = static_cast<int>(s.size());
  if (i - b < 2 || s[i - 1] != '-' || i >= n || s[i] != '(') return i;
  int k = i + 1;
  while (k < n && (std::isalnum(static_cast<unsigned char>(s[k])) || s[k] == '_' || s[k] == '-' ||
                   s[k] == '+' || s[k] == '.' || s[k] == '/'))
    ++k;
  if (k == i + 1 || k >= n || s[k] != ')') return i;
  if (k + 1 < n && !ends_word(s[k + 1])) return i;
  return k + 1;
}

namespace {

// Whether the word at `i` (a '$') has the form of PSpice's generated names, `$N_0001`,
// `$G_DPWR`, `$D_HI`: letters, then '_'.
bool pspice_generated_name(const std::string& line, std::size_t i) {
  std::size_t j = i + 1;
  while (j < line.size() && std::isalpha(static_cast<unsigned char>(line[j]))) ++j;
  return j > i + 1 && j < line.size() && line[j] == '_';
}

// Index where the inline comment of a physical line starts (`;` anywhere, `$` followed by a blank
// or the end of the line, or, as ngspice reads it, a word after a blank that starts with `$`:
// `R1 a b 1k $load`; not PSpice's generated node names, `$N_0001`), or the line's length.
std::size_t comment_start(const std::string& line) {
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == ';') return i;
    if (line[i] != '$') continue;
    if (i + 1 == line.size() || is_space(line[i + 1])) return i;
    if (i > 0 && is_space(line[i - 1]) && !pspice_generated_name(line, i)) return i;
  }
  return line.size();
}

std::size_t first_non_space(const std::string& s, std::size_t end) {
  std::size_t i = 0;
  while (i < end && is_space(s[i])) ++i;
  return i;
}

// The first word of a physical line from `from`, lower-cased (to recognise .end/.control/.endc
// before the line is tokenized).
std::string first_word(const std::string& s, std::size_t from, std::size_t end) {
  std::size_t i = from;
  while (i < end && !ends_word(s[i])) ++i;
  return to_lower(s.substr(from, i - from));
}

SourceLocation physical(const SourceFilePtr& file, int line, int column, int length) {
  SourceLocation loc;
  loc.file = file->path;
  loc.line = line;
  loc.column = column;
  loc.length = std::max(1, length);
  loc.line_text = file->lines[line - 1];
  return loc;
}

void tokenize(Card& card) {
  const std::string& s = card.chars;
  const int n = static_cast<int>(s.size());
  int i = 0;
  card.tokens.reserve(8);  // an element card's usual count: one allocation, not four
  auto push = [&](Token::Kind kind, int begin, int end, std::string text) {
    Token t;
    t.kind = kind;
    t.lower = to_lower(text);
    t.text = std::move(text);
    t.begin = begin;
    t.end = end;
    card.tokens.push_back(std::move(t));
  };
  while (i < n) {
    char c = s[i];
    if (is_space(c)) {
      ++i;
    } else if (c == '(') {
      push(Token::Kind::LParen, i, i + 1, "(");
      ++i;
    } else if (c == ')') {
      push(Token::Kind::RParen, i, i + 1, ")");
      ++i;
    } else if (c == '=') {
      push(Token::Kind::Equals, i, i + 1, "=");
      ++i;
    } else if (c == ',') {
      push(Token::Kind::Comma, i, i + 1, ",");
      ++i;
    } else if (c == '}') {
      throw NetlistError(card.span(i, i + 1), "unmatched '}'");
    } else if (c == '{') {
      // Braces nest (`{ if(v(a) > {vth}, 1, 0) }` in vendor libraries).
      std::size_t close = i + 1;
      for (int depth = 1; close < s.size(); ++close) {
        if (s[close] == '{') ++depth;
        if (s[close] == '}' && --depth == 0) break;
      }
      if (close >= s.size()) throw NetlistError(card.span(i, i + 1), "missing '}'");
      int e = static_cast<int>(close);
      push(Token::Kind::Braced, i, e + 1, s.substr(i + 1, e - i - 1));
      i = e + 1;
    } else if (c == '"' || c == '\'') {
      std::size_t close = s.find(c, i + 1);
      if (close == std::string::npos)
        throw NetlistError(card.span(i, i + 1), "missing closing quote");
      int e = static_cast<int>(close);
      push(Token::Kind::Quoted, i, e + 1, s.substr(i + 1, e - i - 1));
      i = e + 1;
    } else {
      int b = i;
      while (i < n && !ends_word(s[i])) ++i;
      i = kicad_net_name_end(s, b, i);
      push(Token::Kind::Word, b, i, s.substr(b, i - b));
    }
  }
}

// The command lines of a `.control` block, physical lines [first, end). Only a `tran` command is
// tokenized (the others are shell syntax, not netlist syntax, and are only named in a warning).
ControlBlock read_control_block(const SourceFilePtr& file, const SourceLocation& loc, std::size_t first,
                                std::size_t end) {
  ControlBlock block;
  block.loc = loc;
  for (std::size_t k = first; k < end; ++k) {
    const std::string& line = file->lines[k];
    std::size_t f = first_non_space(line, line.size());
    if (f == line.size() || line[f] == '*' || line[f] == '#') continue;
    ControlCommand command;
    command.name = first_word(line, f, line.size());
    command.loc = physical(file, static_cast<int>(k) + 1, static_cast<int>(f) + 1, static_cast<int>(command.name.size()));
    if (command.name == "tran") {
      const std::size_t end_of_text = comment_start(line);
      command.card.file = file;
      for (std::size_t i = f; i < end_of_text; ++i) {
        command.card.chars += line[i];
        command.card.pos.emplace_back(static_cast<int>(k) + 1, static_cast<int>(i) + 1);
      }
      tokenize(command.card);
    }
    block.commands.push_back(std::move(command));
  }
  return block;
}

}  // namespace

std::string to_lower(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

std::string quote(const std::string& text) {
  constexpr std::size_t kMax = 40;
  std::string out = "'";
  std::size_t n = 0;
  for (unsigned char c : text) {
    if (n++ == kMax) {
      out += "...";
      break;
    }
    if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "'";
}

std::string warning_line(const SourceLocation& loc, const std::string& message) {
  SourceLocation one_line = loc;
  one_line.line_text.clear();
  return format_diagnostic(one_line, "warning", message);
}

SourceFilePtr make_source_file(std::string path, const std::string& text) {
  auto file = std::make_shared<SourceFile>();
  file->path = std::move(path);
  std::size_t start = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;  // a UTF-8 byte order mark
  while (start < text.size()) {
    std::size_t nl = text.find('\n', start);
    if (nl == std::string::npos) nl = text.size();
    std::string line = text.substr(start, nl - start);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    file->lines.push_back(std::move(line));
    start = nl + 1;
  }
  return file;
}

SourceLocation Card::span(int begin, int end) const {
  if (pos.empty()) {
    SourceLocation loc;
    loc.file = file->path;
    return loc;
  }
  if (begin >= static_cast<int>(pos.size())) {  // past the end: right after the last char
    auto [line, col] = pos.back();
    return physical(file, line, col + 1, 1);
  }
  auto [line, col] = pos[begin];
  int length = 0;
  for (int i = begin; i < end && i < static_cast<int>(pos.size()); ++i)
    if (pos[i].first == line) ++length;
  return physical(file, line, col, length);
}

SourceLocation Card::after_last() const {
  if (tokens.empty()) return span(0, 1);
  const Token& t = tokens.back();
  auto [line, col] = pos[t.end - 1];
  return physical(file, line, col + 1, 1);
}

std::vector<Card> split_cards(const SourceFilePtr& file, bool has_title, std::vector<std::string>& warnings,
                              std::vector<ControlBlock>* controls) {
  std::vector<Card> cards;
  const auto& lines = file->lines;
  cards.reserve(lines.size());  // at most one card a line
  Card current;
  bool open = false;
  auto flush = [&] {
    if (!open) return;
    tokenize(current);
    if (!current.tokens.empty()) cards.push_back(std::move(current));
    current = Card();
    open = false;
  };
  auto append = [&](const std::string& line, std::size_t from, std::size_t to, int line_no) {
    current.chars.reserve(current.chars.size() + (to - from));
    current.pos.reserve(current.pos.size() + (to - from));
    for (std::size_t i = from; i < to; ++i) {
      current.chars += line[i];
      current.pos.emplace_back(line_no, static_cast<int>(i) + 1);
    }
  };

  for (std::size_t li = has_title ? 1 : 0; li < lines.size(); ++li) {
    const std::string& line = lines[li];
    const int line_no = static_cast<int>(li) + 1;
    std::size_t end = comment_start(line);
    std::size_t f = first_non_space(line, end);
    if (f == end || line[f] == '*') continue;  // blank or comment line
    if (line[f] == '+') {
      if (!open)
        throw NetlistError(physical(file, line_no, static_cast<int>(f) + 1, 1),
                           "continuation line without a card to continue");
      current.chars += ' ';
      current.pos.emplace_back(line_no, static_cast<int>(f) + 1);
      append(line, f + 1, end, line_no);
      continue;
    }
    std::string word = first_word(line, f, end);
    if (word == ".end") break;
    if (word == ".control") {
      flush();
      SourceLocation loc = physical(file, line_no, static_cast<int>(f) + 1, 8);
      std::size_t k = li + 1;
      for (; k < lines.size(); ++k) {
        std::size_t kf = first_non_space(lines[k], lines[k].size());
        if (first_word(lines[k], kf, lines[k].size()) == ".endc") break;
      }
      if (k == lines.size()) throw NetlistError(loc, "missing '.endc' for '.control'");
      if (controls) controls->push_back(read_control_block(file, loc, li + 1, k));
      li = k;
      continue;
    }
    flush();
    open = true;
    current.file = file;
    append(line, f, end, line_no);
  }
  flush();
  return cards;
}

}  // namespace lcs::parse
