// Physical lines -> logical cards -> tokens. Internal to the netlist reader.
//
// A card is one logical line: a first line plus its `+` continuation lines, with comments removed.
// Every character of a card remembers its physical line and column, so a token (or a position
// inside a `{expression}`) is reported where it was written even after lines are joined.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "netlist/source_location.h"

namespace lcs::parse {

// One file as read: the path used in diagnostics and its physical lines (without newlines).
struct SourceFile {
  std::string path;
  std::vector<std::string> lines;
};
using SourceFilePtr = std::shared_ptr<const SourceFile>;

SourceFilePtr make_source_file(std::string path, const std::string& text);

struct Token {
  enum class Kind {
    Word,    // anything else: names, nodes, numbers, keywords, `.cards`
    LParen,  // (
    RParen,  // )
    Equals,  // =
    Comma,   // ,
    Braced,  // {expression}
    Quoted,  // "text" or 'text' (a file name, or an expression as in ngspice)
  };
  Kind kind = Kind::Word;
  std::string text;   // as written; Braced/Quoted: the contents without the delimiters
  std::string lower;  // text in lower case
  int begin = 0;      // [begin, end) in Card::chars, delimiters included
  int end = 0;

  bool is(Kind k) const { return kind == k; }
  bool is_word() const { return kind == Kind::Word; }
  bool is_word(const char* w) const { return kind == Kind::Word && lower == w; }
  bool is_expression() const { return kind == Kind::Braced || kind == Kind::Quoted; }
};

struct Card {
  SourceFilePtr file;
  std::string chars;                     // the logical line, continuations joined by one space
  std::vector<std::pair<int, int>> pos;  // physical (line, column), 1-based, of every char
  std::vector<Token> tokens;             // never empty for a card handed out by split_cards

  const Token& operator[](std::size_t i) const { return tokens[i]; }
  std::size_t size() const { return tokens.size(); }
  const std::string& keyword() const { return tokens.front().lower; }

  // Location of chars [begin, end); the underline stops at the end of the first physical line.
  SourceLocation span(int begin, int end) const;
  SourceLocation at(const Token& t) const { return span(t.begin, t.end); }
  SourceLocation at(std::size_t token_index) const { return at(tokens[token_index]); }
  // Just past the last token: where a missing field should have been.
  SourceLocation after_last() const;
  int line() const { return pos.empty() ? 0 : pos.front().first; }
  // The raw text of chars [begin, end).
  std::string text(int begin, int end) const { return chars.substr(begin, end - begin); }
};

// One command line of a `.control` block: its first word (lower-case) and where it is. A `tran`
// command also has its tokens in `card` (same syntax as the `.tran` card).
struct ControlCommand {
  std::string name;
  SourceLocation loc;
  Card card;
};

// `.control` ... `.endc`: ngspice's interactive commands, kept for the parser to find `tran` in.
struct ControlBlock {
  SourceLocation loc;  // the `.control` line
  std::vector<ControlCommand> commands;
};

// Splits a file into cards: skips the title line (when `has_title`), blank lines, `*` comment
// lines and inline `;` and `$ ` comments, joins `+` continuation lines and stops at `.end`.
// `.control`...`.endc` blocks are taken out into `controls` (dropped when it is null). Throws NetlistError on lexical errors.
std::vector<Card> split_cards(const SourceFilePtr& file, bool has_title, std::vector<std::string>& warnings,
                              std::vector<ControlBlock>* controls = nullptr);

// "FILE:LINE:COL: warning: message" on one line (no source line, no caret).
std::string warning_line(const SourceLocation& loc, const std::string& message);

// A token as it appears inside a message: 'text', with control bytes escaped and long text cut.
std::string quote(const std::string& text);

std::string to_lower(std::string s);

// KiCad names a net it was given no name for after a pin, `Net-(R1-Pad1)` (also
// `unconnected-(U1-Pad3)`): a word ending in '-' right before '(', then only name characters up to
// ')'. For the word at [b, i) of `s`, returns the end of that ')' (the node name's end), or `i`
// when the word does not continue so. (No SPICE keyword ends in '-' before a parenthesis.) The
// lexer and the probe parser read node names with it.
int kicad_net_name_end(const std::string& s, int b, int i);

}  // namespace lcs::parse
