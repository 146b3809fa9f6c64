// The in-process ngspice bridge: run a transient in libngspice (Debian's ngspice 39 shared
// library) and read every vector of the resulting plot back as numbers.
//
// libngspice is one global simulator per process. The bridge owns it as a singleton: it is
// loaded (dlopen, ngspice_library.h) and initialised on first use, every call is serialised by
// one mutex, and each run starts and ends with no circuit and no plot left behind (`remcirc`,
// `destroy all`), so repeated runs in one process neither mix nor pile up results. The deck is
// handed over in memory (ngSpice_Circ), the analysis runs in ngspice's background thread
// (`bg_run`) under a wall-clock limit, and the data is read through ngSpice_CurPlot /
// ngSpice_AllVecs / ngGet_Vec_Info -- printed output is only read for the verdict. See
// ngspice/README.md for what ngspice needs to behave.
#pragma once

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace lcs {

struct NgspiceRun {                      // what to simulate
  std::vector<std::string> deck;         // complete ngspice deck, one line per entry: title first,
                                         // `.end` last (entries holding several lines are split;
                                         // a missing `.end` is added; lines after `.end` dropped)
  double timeout_seconds = 60;           // wall-clock limit for the transient (finite, > 0)
  // Optional. Called on the caller's thread while the transient runs (every few ms, when it has
  // moved on), with the simulated time of ngspice's last accepted point.
  std::function<void(double simulated_time)> progress;
};

struct NgspiceResult {
  std::vector<double> time;              // the transient's time points (ngspice's accepted steps)
  // Every other vector of the tran plot, keyed lower-case as ngspice names them ("out" for a
  // node, "x1.n1" inside a subcircuit, "v1#branch", "@d1[id]" if saved), same length as time.
  // The scale vector "time" is not repeated here.
  std::map<std::string, std::vector<double>> vectors;
  double analysis_cpu_seconds = 0;       // process CPU time spent inside the run (bg_run to end)
  std::vector<std::string> messages;     // everything ngspice printed while loading and running
                                         // (stdout and stderr callbacks), in order, prefixes off
};

class NgspiceError : public std::runtime_error {
 public:
  enum class Kind {
    NoLibrary,    // libngspice could not be loaded (not installed, or not the library expected);
                  // what() names each file tried and the loader's reason
    Unavailable,  // ngspice cannot be used in this process (init failed, or an earlier Aborted /
                  // unstoppable run left it unusable)
    Load,         // the deck did not load: syntax error, unknown model, missing include, .control
    Convergence,  // ngspice gave up: "Timestep too small", transient op failed, ...
    Timeout,      // the transient exceeded timeout_seconds and was halted (the bridge stays usable)
    Aborted,      // ngspice asked to be unloaded (ControlledExit) or was interrupted from outside;
                  // after ControlledExit every later call is Unavailable
    NoData,       // the run produced no tran plot (no .tran card, only .op/.ac, empty plot)
  };

  NgspiceError(Kind kind, const std::string& what, std::vector<std::string> messages);
  Kind kind() const { return kind_; }
  // Everything ngspice printed for the failing run (as NgspiceResult::messages).
  const std::vector<std::string>& messages() const { return messages_; }

 private:
  Kind kind_;
  std::vector<std::string> messages_;
};

// "no-library", "unavailable", "load", "convergence", "timeout", "aborted", "no-data".
const char* to_string(NgspiceError::Kind kind);

// Loads `run.deck`, runs the analysis its `.tran` card defines, returns the tran plot. Thread-safe
// (calls are serialised). Throws NgspiceError; std::invalid_argument for a bad timeout_seconds.
NgspiceResult run_ngspice_transient(const NgspiceRun& run);

// What initialising ngspice printed and found (initialises it if needed; throws Unavailable).
struct NgspiceInfo {
  std::string version;                   // "ngspice-39", from the init banner
  std::string user_init_file;            // the .spiceinit ngspice sourced at init, or empty
  std::vector<std::string> init_messages;
};
NgspiceInfo ngspice_info();

// Loads libngspice if it is not loaded yet, without initialising it (ngspice_library.h). For
// commands that need ngspice, to fail before any other work. Throws NgspiceError (NoLibrary).
void require_ngspice_library();

}  // namespace lcs
