#include "ngspice/ngspice_messages.h"

#include <algorithm>
#include <cctype>
#include <initializer_list>

namespace lcs::ngspice_messages {
namespace {

std::string lower_trimmed(std::string_view s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  std::string out(s.substr(b, e - b));
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool contains_any(const std::string& lower, std::initializer_list<const char*> needles) {
  for (const char* n : needles)
    if (lower.find(n) != std::string::npos) return true;
  return false;
}

void add_evidence(std::vector<std::string>& evidence, const std::string& text, size_t cap = 12) {
  if (evidence.size() >= cap) return;
  if (std::find(evidence.begin(), evidence.end(), text) == evidence.end()) evidence.push_back(text);
}

// Run-phase signs, all as ngspice 39 prints them (lower-cased here).
constexpr std::initializer_list<const char*> kNotLoaded = {
    "circuit not parsed", "aren't any circuits loaded", "no circuit loaded"};
constexpr std::initializer_list<const char*> kGaveUp = {
    "timestep too small",       // "doAnalyses: TRAN:  Timestep too small; time = ..., timestep = ..."
    "simulation(s) aborted",    // "run simulation(s) aborted"
    "simulation aborted",       //
    "transient solution failed",  // "Transient solution failed -" (+ last node voltages)
    "op failed"};               // "Error: Transient op failed, timestep too small"
constexpr std::initializer_list<const char*> kContext = {
    "trouble with", "singular matrix", "iteration limit", "gmin stepping failed",
    "source stepping failed"};
constexpr std::initializer_list<const char*> kInterrupted = {
    "simulation interrupted", "pause requested"};

}  // namespace

Line parse(std::string_view raw) {
  Line line;
  if (raw.substr(0, 7) == "stdout ") {
    line.stream = Stream::Out;
    raw.remove_prefix(7);
  } else if (raw.substr(0, 7) == "stderr ") {
    line.stream = Stream::Err;
    raw.remove_prefix(7);
  } else if (raw == "stdout" || raw == "stderr") {  // an empty line
    line.stream = raw == "stdout" ? Stream::Out : Stream::Err;
    raw = {};
  }
  while (!raw.empty() && (raw.back() == '\r' || raw.back() == '\n')) raw.remove_suffix(1);
  line.text = std::string(raw);
  return line;
}

void Log::add(Line line) {
  ++total_;
  if (first_.size() < head_) {
    first_.push_back(std::move(line));
    return;
  }
  if (tail_ == 0) return;
  if (last_.size() == tail_) last_.pop_front();
  last_.push_back(std::move(line));
}

void Log::clear() {
  total_ = 0;
  first_.clear();
  last_.clear();
}

std::vector<Line> Log::since(size_t mark) const {
  std::vector<Line> out;
  for (size_t i = mark; i < first_.size(); ++i) out.push_back(first_[i]);
  const size_t last_begin = total_ - last_.size();
  for (size_t i = std::max(mark, last_begin); i < total_; ++i) out.push_back(last_[i - last_begin]);
  return out;
}

std::vector<std::string> Log::texts() const {
  std::vector<std::string> out;
  out.reserve(first_.size() + last_.size() + 1);
  for (const Line& l : first_) out.push_back(l.text);
  const size_t dropped = total_ - first_.size() - last_.size();
  if (dropped > 0)
    out.push_back("[lcspice: " + std::to_string(dropped) + " ngspice lines not kept]");
  for (const Line& l : last_) out.push_back(l.text);
  return out;
}

bool load_failed(const std::vector<Line>& lines, std::vector<std::string>& evidence) {
  bool failed = false;
  for (const Line& line : lines) {
    const std::string lower = lower_trimmed(line.text);
    // "Error on line 4 or its substitute:", "Error: not enough parameters in line",
    // "Error: Could not find include file ...", "No circuit loaded!"
    if (lower.rfind("error", 0) == 0 || contains_any(lower, kNotLoaded)) failed = true;
  }
  if (failed)
    for (const Line& line : lines)  // on stderr: the errors, the quoted card, the reason, warnings
      if (line.stream == Stream::Err && !lower_trimmed(line.text).empty())
        add_evidence(evidence, line.text);
  return failed;
}

bool announces_detach(const std::vector<Line>& lines) {
  for (const Line& line : lines) {
    const std::string lower = lower_trimmed(line.text);
    if (contains_any(lower, {"awaits to be detached", "asks for detaching"})) return true;
  }
  return false;
}

RunVerdict classify_run(const std::vector<Line>& lines, std::vector<std::string>& evidence) {
  bool not_loaded = false, gave_up = false, interrupted = false;
  std::vector<std::string> primary, context;
  for (const Line& line : lines) {
    const std::string lower = lower_trimmed(line.text);
    if (contains_any(lower, kNotLoaded)) {
      not_loaded = true;
      add_evidence(primary, line.text);
    } else if (contains_any(lower, kGaveUp)) {
      gave_up = true;
      add_evidence(primary, line.text);
    } else if (contains_any(lower, kInterrupted)) {
      interrupted = true;
      add_evidence(primary, line.text);
    } else if (contains_any(lower, kContext)) {
      add_evidence(context, line.text, 6);
    }
  }
  // The most specific line first: "Timestep too small; time = ..." says when and where.
  std::stable_partition(primary.begin(), primary.end(), [](const std::string& s) {
    return lower_trimmed(s).find("timestep too small") != std::string::npos;
  });
  for (const std::string& s : primary) add_evidence(evidence, s);
  for (const std::string& s : context) add_evidence(evidence, s);
  if (not_loaded) return RunVerdict::NotLoaded;
  if (gave_up) return RunVerdict::Convergence;
  if (interrupted) return RunVerdict::Interrupted;
  return RunVerdict::Completed;
}

}  // namespace lcs::ngspice_messages
