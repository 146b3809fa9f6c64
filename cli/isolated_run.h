// A piece of work run in a forked child process, so that its peak memory can be read on its own
// (the child's ru_maxrss from wait4) and a run that takes too long can be killed.
//
// The child starts as a copy of the caller: its resident set starts at the caller's, so
// `run_isolated(idle)` (a child that does nothing) gives the baseline that every peak includes.
// The caller must be single-threaded (libngspice, for one, is first started in the child).
#pragma once

#include <functional>
#include <string>

namespace lcs {

struct IsolatedRun {
  enum class Outcome {
    Finished,  // the work returned (or threw: its report then starts "error: ")
    TimedOut,  // killed after the wall-clock limit
    Crashed,   // the child died otherwise (a signal, an exit before reporting)
  };
  Outcome outcome = Outcome::Crashed;
  std::string report;        // what the work returned (Finished)
  std::string why;           // TimedOut / Crashed: what happened, for a message
  double wall_seconds = 0;
  double peak_rss_mb = 0;    // the child's ru_maxrss, in MiB
  double child_cpu_seconds = 0;  // the child's user + system time
};

// Runs `work` in a child process and waits at most `timeout_seconds` of wall time for it; an
// exception from `work` becomes the report "error: <what>". The child's standard output and
// error go to /dev/null. Throws std::runtime_error when no child can be started.
IsolatedRun run_isolated(const std::function<std::string()>& work, double timeout_seconds);

}  // namespace lcs
