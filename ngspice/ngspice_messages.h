// What ngspice prints, captured and read for failure signs. Internal to the bridge.
//
// ngspice reports through its SendChar callback one line at a time, as "stdout <text>" or
// "stderr <text>"; progress lines ending in '\r' ("Reference value : ...") come without a prefix.
// Data never comes from here (vectors are read through ngGet_Vec_Info); only the verdict does,
// because ngspice has no other channel for "the deck did not load" or "the analysis gave up".
// The patterns below are the messages of ngspice 39 (see ngspice/README.md for the full texts).
#pragma once

#include <cstddef>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

namespace lcs::ngspice_messages {

enum class Stream { Out, Err, Other };

struct Line {
  Stream stream = Stream::Other;
  std::string text;  // without the "stdout "/"stderr " prefix and trailing '\r'/'\n'
};

// Splits a SendChar string into stream and text.
Line parse(std::string_view raw);

// All lines of one run, bounded: beyond `head + tail` lines the first `head` and the last `tail`
// are kept (errors come at the end) with one marker line between them.
class Log {
 public:
  explicit Log(size_t head = 5000, size_t tail = 5000) : head_(head), tail_(tail) {}
  void add(Line line);
  void clear();
  size_t size() const { return total_; }  // lines added, including dropped ones
  // Lines added since `mark` (a previous size()), as far as they are still kept.
  std::vector<Line> since(size_t mark) const;
  // Every kept line's text, in order, with the marker where lines were dropped.
  std::vector<std::string> texts() const;

 private:
  size_t head_, tail_;
  size_t total_ = 0;
  std::vector<Line> first_;  // lines 0 .. head_-1
  std::deque<Line> last_;    // the last tail_ lines after them: lines total_-last_.size() ..
};

// Verdict on the lines printed by ngSpice_Circ: did the deck fail to load? `evidence` gets the
// lines that say why (ngspice's error lines and the offending card it quotes).
bool load_failed(const std::vector<Line>& lines, std::vector<std::string>& evidence);

// ngspice's own announcement that it called ControlledExit ("Error: ngspice.dll cannot recover
// and awaits to be detached", "Note: 'quit' asks for detaching ngspice.dll."). It is printed
// before the callbacks run, so it closes the window in which the background thread has reported
// its end but not yet called ControlledExit.
bool announces_detach(const std::vector<Line>& lines);

enum class RunVerdict {
  Completed,    // no failure sign (the plot decides whether there is data)
  NotLoaded,    // "circuit not parsed", "there aren't any circuits loaded"
  Convergence,  // "Timestep too small", "Transient op failed", "simulation(s) aborted", ...
  Interrupted,  // "simulation interrupted" / "pause requested" not caused by the bridge
};

// Verdict on the lines printed while the analysis ran; `evidence` gets the telling lines.
RunVerdict classify_run(const std::vector<Line>& lines, std::vector<std::string>& evidence);

}  // namespace lcs::ngspice_messages
