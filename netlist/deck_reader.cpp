#include "netlist/deck_reader.h"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <system_error>

#include "netlist/text_encoding.h"

namespace lcs::parse {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxIncludeDepth = 64;
// Work bounds over the whole deck, so that includes repeating each other (40 files of 40
// `.include` lines each, nested four deep, open 40^4 files) cannot run for minutes.
constexpr std::size_t kMaxIncludeOpens = 10'000;
constexpr std::size_t kMaxIncludedBytes = std::size_t{64} << 20;

std::string identity(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::path(path), ec);
  return ec ? fs::path(path).lexically_normal().string() : p.string();
}

// `.include FILE`: the file name, quoted or bare (a bare name runs to the end of the card, so
// names with parentheses or `=` survive tokenization).
std::string include_target(const Card& card) {
  if (card.size() < 2) throw NetlistError(card.after_last(), "missing file name after " + quote(card[0].text));
  const Token& t = card[1];
  if (t.is(Token::Kind::Quoted)) {
    if (card.size() > 2) throw NetlistError(card.at(2), "unexpected extra token " + quote(card[2].text));
    return t.text;
  }
  return card.text(t.begin, card.tokens.back().end);
}

std::string resolve_relative(const std::string& includer, const std::string& name) {
  fs::path p(name);
  if (p.is_absolute()) return name;
  fs::path dir = fs::path(includer).parent_path();
  if (dir.empty()) return p.lexically_normal().string();
  return (dir / p).lexically_normal().string();
}

// `.lib FILE SECTION`: the file (quoted or bare) and the section name.
struct LibReference {
  std::string file, section;
  SourceLocation file_loc;
};

std::optional<LibReference> lib_reference(const Card& card) {
  if (card.size() != 3 || !card[2].is_word()) return std::nullopt;
  if (!card[1].is_word() && !card[1].is(Token::Kind::Quoted)) return std::nullopt;
  return LibReference{card[1].text, card[2].lower, card.at(1)};
}

bool is_lib(const Card& card) { return card[0].is_word(".lib"); }

// LTspice's `.lib FILE` of a file that cannot be opened: a warning, not an error.
std::string missing_library_warning(const SourceLocation& loc, const std::string& name) {
  return warning_line(loc, "cannot open library file '" + name +
                               "': lcspice goes on with the models and subcircuits the deck defines itself (LTspice "
                               "and PSpice write their own libraries' paths into every deck)");
}

// A path with a space, a directory separator and an extension at its end (".dio", ".lib").
bool is_spaced_library_path(const std::string& text) {
  if (text.find(' ') == std::string::npos || text.find_first_of("/\\") == std::string::npos) return false;
  if (text.find('"') != std::string::npos || text.find('\'') != std::string::npos) return false;
  const std::size_t dot = text.rfind('.');
  if (dot == std::string::npos || dot + 1 == text.size() || dot < text.find_last_of("/\\")) return false;
  for (std::size_t k = dot + 1; k < text.size(); ++k)
    if (!std::isalnum(static_cast<unsigned char>(text[k]))) return false;
  return true;
}
bool is_endl(const Card& card) { return card[0].is_word(".endl"); }

// The `.endl` closing the section that starts at cards[begin] (a `.lib SECTION` card), or
// cards.size() when none follows.
std::size_t find_section_end(const std::vector<Card>& cards, std::size_t begin) {
  for (std::size_t k = begin + 1; k < cards.size(); ++k)
    if (is_endl(cards[k])) return k;
  return cards.size();
}

std::size_t section_end(const std::vector<Card>& cards, std::size_t begin) {
  const std::size_t end = find_section_end(cards, begin);
  if (end < cards.size()) return end;
  throw NetlistError(cards[begin].at(0), "missing '.endl' for '.lib " + cards[begin][1].lower + "'");
}

class Reader {
 public:
  Reader(std::vector<std::string>& warnings, std::vector<ControlBlock>& controls,
         std::vector<NetlistError>& unopened)
      : warnings_(warnings), controls_(controls), unopened_(unopened) {}

  void expand(const SourceFilePtr& file, bool has_title, std::vector<Card>& out) {
    stack_.push_back(identity(file->path));
    std::vector<Card> cards = split_cards(file, has_title, warnings_, &controls_);
    splice(file, cards, 0, cards.size(), out);
    stack_.pop_back();
  }

 private:
  // Copies cards [begin, end) of `file` to `out`, expanding `.include` and `.lib FILE SECTION`
  // and leaving out `.lib SECTION` ... `.endl` blocks (a library's sections are read on request).
  void splice(const SourceFilePtr& file, std::vector<Card>& cards, std::size_t begin, std::size_t end,
              std::vector<Card>& out) {
    out.reserve(out.size() + (end - begin));
    for (std::size_t k = begin; k < end; ++k) {
      Card& card = cards[k];
      if (is_endl(card)) throw NetlistError(card.at(0), "'.endl' without '.lib'");
      if (is_lib(card)) {
        // `.lib NAME` ... `.endl`: a section definition not asked for here. `.lib FILE` with no
        // `.endl` after it is LTspice's library include (the whole file; ngspice has no such form).
        if (card.size() == 2 && card[1].is_word() && find_section_end(cards, k) < cards.size()) {
          k = section_end(cards, k);
          continue;
        }
        if (card.size() == 2 && (card[1].is_word() || card[1].is(Token::Kind::Quoted))) {
          // A name with an extension or a directory is a file (LTspice's libraries: standard.dio,
          // ...\lib\cmp\standard.bjt); a bare word is more likely a section missing its .endl.
          const std::string& name = card[1].text;
          const bool file_like = name.find_first_of("./\\") != std::string::npos;
          std::string text;
          bool missing = false;
          const std::string path =
              open_nested(file, name, card.at(1), "library", text,
                          file_like ? std::string()
                                    : " ('.lib FILE' reads FILE, as LTspice does; a section '.lib " + card[1].lower +
                                          "' ends at '.endl')",
                          file_like ? &missing : nullptr);
          if (missing) {
            warnings_.push_back(missing_library_warning(card.at(1), name));
            continue;
          }
          expand(make_source_file(path, text), false, out);
          continue;
        }
        // LTspice IV writes its install path unquoted, spaces and all (`.lib C:\Program Files
        // (x86)\LTC\LTspiceIV\lib\cmp\standard.dio`): the rest of the card is one file name where
        // it has a directory and ends in an extension (a section name has none).
        if (card.size() >= 3) {
          const std::string rest = card.text(card[1].begin, card.tokens.back().end);
          if (is_spaced_library_path(rest)) {
            std::string text;
            bool missing = false;
            const SourceLocation loc = card.span(card[1].begin, card.tokens.back().end);
            const std::string path = open_nested(file, rest, loc, "library", text, "", &missing);
            if (missing) {
              warnings_.push_back(missing_library_warning(loc, rest));
              continue;
            }
            expand(make_source_file(path, text), false, out);
            continue;
          }
        }
        std::optional<LibReference> ref = lib_reference(card);
        if (!ref) throw NetlistError(card.at(0), "expected '.lib FILE SECTION' or '.lib SECTION'");
        read_section(file, *ref, card, out);
        continue;
      }
      if (!card[0].is_word(".include") && !card[0].is_word(".inc")) {
        out.push_back(std::move(card));
        continue;
      }
      std::string name = include_target(card);
      SourceLocation loc = card.span(card[1].begin, card.tokens.back().end);
      std::string text;
      std::string path = open_nested(file, name, loc, "include", text);
      expand(make_source_file(path, text), false, out);
    }
  }

  // Checks the bounds and reads the file `name` names relative to `file`; returns its path.
  // With `missing`, a file that cannot be read is not an error: its error is kept in unopened_,
  // *missing is set and the path returned is empty.
  std::string open_nested(const SourceFilePtr& file, const std::string& name, const SourceLocation& loc,
                          const char* what, std::string& text, const std::string& unopened_hint = "",
                          bool* missing = nullptr) {
    std::string path = resolve_relative(file->path, name);
    std::string id = identity(path);
    for (const std::string& open : stack_)
      if (open == id) throw NetlistError(loc, std::string(what) + " cycle: " + quote(name) + " is already being included");
    if (stack_.size() >= kMaxIncludeDepth) throw NetlistError(loc, "include files nested too deeply");
    if (++opens_ > kMaxIncludeOpens)
      throw NetlistError(loc, "more than " + std::to_string(kMaxIncludeOpens) +
                                  " .include files read for one netlist (includes that repeat each other?)");
    if (!read_file(path, text, true)) {
      NetlistError error(loc, "cannot open " + std::string(what) + " file '" + name + "'" + unopened_hint);
      if (!missing) throw error;
      unopened_.push_back(std::move(error));
      *missing = true;
      return "";
    }
    bytes_ += text.size();
    if (bytes_ > kMaxIncludedBytes)
      throw NetlistError(loc, "included text exceeds " + std::to_string(kMaxIncludedBytes >> 20) +
                                  " MiB for one netlist");
    return path;
  }

  // `.lib FILE SECTION`: the cards of section SECTION of FILE (ngspice: only that section is
  // read; a section may itself reference sections of the same or other files).
  void read_section(const SourceFilePtr& file, const LibReference& ref, const Card& card, std::vector<Card>& out) {
    std::string text;
    std::string path = open_nested(file, ref.file, ref.file_loc, "library", text);
    const std::string key = identity(path) + "#" + ref.section;
    for (const std::string& open : stack_)
      if (open == key)
        throw NetlistError(card.at(2), "library cycle: section " + quote(ref.section) + " of " + quote(ref.file) +
                                           " is already being read");
    SourceFilePtr lib = make_source_file(path, text);
    std::vector<Card> cards = split_cards(lib, false, warnings_, &controls_);
    std::string sections;
    for (std::size_t k = 0; k < cards.size(); ++k) {
      if (!is_lib(cards[k]) || cards[k].size() != 2 || !cards[k][1].is_word()) continue;
      const std::size_t end = section_end(cards, k);
      if (cards[k][1].lower == ref.section) {
        stack_.push_back(key);
        splice(lib, cards, k + 1, end, out);
        stack_.pop_back();
        return;
      }
      sections += (sections.empty() ? "" : ", ") + cards[k][1].lower;
      k = end;
    }
    throw NetlistError(card.at(2), "library " + quote(ref.file) + " has no section " + quote(ref.section) +
                                       (sections.empty() ? std::string(" (it has no sections)")
                                                         : " (its sections: " + sections + ")"));
  }

  std::vector<std::string>& warnings_;
  std::vector<ControlBlock>& controls_;
  std::vector<NetlistError>& unopened_;
  std::vector<std::string> stack_;  // identities of the files (and library sections) being read, outermost first
  std::size_t opens_ = 0, bytes_ = 0;
};

}  // namespace

bool read_file(const std::string& path, std::string& text, bool regular_only) {
  std::error_code ec;
  fs::file_status st = fs::status(fs::path(path), ec);
  if (ec || fs::is_directory(st) || (regular_only && !fs::is_regular_file(st))) return false;
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  // Bounded, so a device that never ends (/dev/zero) cannot make the reader hang.
  constexpr std::size_t kMaxBytes = std::size_t{256} << 20;
  text.clear();
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    text.append(buf, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxBytes) return false;
  }
  text = to_utf8(text);
  return true;
}

Deck read_deck(const SourceFilePtr& top, std::vector<std::string>& warnings) {
  Deck deck;
  if (!top->lines.empty()) deck.title = top->lines.front();
  Reader(warnings, deck.controls, deck.unopened_libraries).expand(top, true, deck.cards);
  return deck;
}

}  // namespace lcs::parse
