#include "netlist/deck_reader.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

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

class Reader {
 public:
  explicit Reader(std::vector<std::string>& warnings) : warnings_(warnings) {}

  void expand(const SourceFilePtr& file, bool has_title, std::vector<Card>& out) {
    stack_.push_back(identity(file->path));
    for (Card& card : split_cards(file, has_title, warnings_)) {
      if (!card[0].is_word(".include") && !card[0].is_word(".inc")) {
        out.push_back(std::move(card));
        continue;
      }
      std::string name = include_target(card);
      SourceLocation loc = card.span(card[1].begin, card.tokens.back().end);
      std::string path = resolve_relative(file->path, name);
      std::string id = identity(path);
      for (const std::string& open : stack_)
        if (open == id) throw NetlistError(loc, "include cycle: " + quote(name) + " is already being included");
      if (stack_.size() >= kMaxIncludeDepth) throw NetlistError(loc, "include files nested too deeply");
      if (++opens_ > kMaxIncludeOpens)
        throw NetlistError(loc, "more than " + std::to_string(kMaxIncludeOpens) +
                                    " .include files read for one netlist (includes that repeat each other?)");
      std::string text;
      if (!read_file(path, text, true)) throw NetlistError(loc, "cannot open include file " + quote(name));
      bytes_ += text.size();
      if (bytes_ > kMaxIncludedBytes)
        throw NetlistError(loc, "included text exceeds " + std::to_string(kMaxIncludedBytes >> 20) +
                                    " MiB for one netlist");
      expand(make_source_file(path, text), false, out);
    }
    stack_.pop_back();
  }

 private:
  std::vector<std::string>& warnings_;
  std::vector<std::string> stack_;  // identities of the files being read, outermost first
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
  return true;
}

Deck read_deck(const SourceFilePtr& top, std::vector<std::string>& warnings) {
  Deck deck;
  if (!top->lines.empty()) deck.title = top->lines.front();
  Reader(warnings).expand(top, true, deck.cards);
  return deck;
}

}  // namespace lcs::parse
