#include "ngspice/ngspice_session.h"

#include <ngspice/sharedspice.h>
#include <pwd.h>
#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <iterator>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>
#include <utility>

#include "ngspice/ngspice_deck.h"
#include "ngspice/ngspice_library.h"
#include "ngspice/ngspice_messages.h"
#include "ngspice/passwd_fallback.h"

namespace lcs {

NgspiceError::NgspiceError(Kind kind, const std::string& what, std::vector<std::string> messages)
    : std::runtime_error(what), kind_(kind), messages_(std::move(messages)) {}

const char* to_string(NgspiceError::Kind kind) {
  switch (kind) {
    case NgspiceError::Kind::NoLibrary: return "no-library";
    case NgspiceError::Kind::Unavailable: return "unavailable";
    case NgspiceError::Kind::Load: return "load";
    case NgspiceError::Kind::Convergence: return "convergence";
    case NgspiceError::Kind::Timeout: return "timeout";
    case NgspiceError::Kind::Aborted: return "aborted";
    case NgspiceError::Kind::NoData: return "no-data";
  }
  return "unknown";
}

namespace {

using Kind = NgspiceError::Kind;
using ngspice_messages::Line;
using Clock = std::chrono::steady_clock;

// How long ngspice's background thread may take to appear after `bg_run`, and to end after
// `bg_halt` (which itself waits up to 1 s for the analysis to notice).
constexpr auto kThreadStartLimit = std::chrono::seconds(5);
constexpr auto kHaltLimit = std::chrono::seconds(5);
constexpr auto kPollInterval = std::chrono::milliseconds(5);

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

bool starts_with_ci(const char* s, const char* prefix) {
  for (; *prefix; ++s, ++prefix)
    if (!*s || std::tolower(static_cast<unsigned char>(*s)) != *prefix) return false;
  return true;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// ngSpice_Init installs its own SIGSEGV handler with signal() and puts the old one back with
// signal(), which loses sa_flags/sa_sigaction of a caller's handler; it also probes SIGILL.
// Every synchronous call into ngspice is wrapped so the process's dispositions come out intact
// (a disposition is only written back if ngspice changed it).
class SignalGuard {
 public:
  SignalGuard() {
    for (size_t i = 0; i < kCount; ++i) sigaction(kSignals[i], nullptr, &saved_[i]);
  }
  ~SignalGuard() {
    for (size_t i = 0; i < kCount; ++i) {
      struct sigaction now {};
      sigaction(kSignals[i], nullptr, &now);
      if (!same(now, saved_[i])) sigaction(kSignals[i], &saved_[i], nullptr);
    }
  }
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

 private:
  static bool same(const struct sigaction& a, const struct sigaction& b) {
    const bool info = a.sa_flags & SA_SIGINFO;
    return a.sa_flags == b.sa_flags &&
           (info ? a.sa_sigaction == b.sa_sigaction : a.sa_handler == b.sa_handler);
  }
  static constexpr int kSignals[] = {SIGINT, SIGSEGV, SIGILL, SIGFPE, SIGBUS, SIGABRT, SIGTERM,
                                     SIGPIPE};
  static constexpr size_t kCount = sizeof(kSignals) / sizeof(kSignals[0]);
  struct sigaction saved_[kCount];
};

std::string join(const std::vector<std::string>& lines, size_t max_lines) {
  std::string out;
  for (size_t i = 0; i < lines.size() && i < max_lines; ++i) {
    if (i) out += " | ";
    out += lines[i];
  }
  return out;
}

std::string with_evidence(std::string summary, const std::vector<std::string>& evidence) {
  if (!evidence.empty()) summary += ": " + join(evidence, 4);
  return summary;
}

std::string format_seconds(double s) {
  std::ostringstream os;
  os << s << " s";
  return os.str();
}

// The process's libngspice, or NoLibrary with the loader's reasons.
const NgspiceLibrary& loaded_library() {
  try {
    return ngspice_library();
  } catch (const NgspiceLibraryError& e) {
    throw NgspiceError(NgspiceError::Kind::NoLibrary, e.what(), {});
  }
}

// The single ngspice of this process.
class Engine {
 public:
  static Engine& instance() {
    static Engine* engine = new Engine();  // never destroyed: ngspice may still own a thread at exit
    return *engine;
  }

  NgspiceResult run(const NgspiceRun& run);
  NgspiceInfo info() {
    std::lock_guard<std::mutex> lock(run_mutex_);
    ensure_initialised();
    return info_;
  }

 private:
  Engine() = default;

  // ngspice callbacks (ngspice's threads; must not throw, must not call back into ngspice)
  static int on_char(char* text, int, void* self);
  // Every accepted point of a running analysis (ngspice's SendData), for progress: the scale.
  // ngspice fills what it sends only when a SendInitData callback is given too (sh_vecinit).
  static int on_data(pvecvaluesall values, int, int, void* self);
  static int on_init_data(pvecinfoall, int, void*) { return 0; }
  static int on_exit(int status, NG_BOOL immediate, NG_BOOL quit, int, void* self);
  static int on_bg_thread(NG_BOOL exited, int, void* self);

  void ensure_initialised();
  void command(const std::string& cmd);
  void clear_circuits_and_plots();
  // Until the thread's start (end) callbacks exceed `before`, or the deadline.
  bool wait_for_thread_start(long before, Clock::time_point deadline) { return wait_for_count(bg_starts_, before, deadline); }
  bool wait_for_thread_end(long before, Clock::time_point deadline) { return wait_for_count(bg_ends_, before, deadline); }
  bool wait_for_count(const long& counter, long before, Clock::time_point deadline);
  std::optional<std::string> tran_plot();
  double simulated_time_reached();
  void read_plot(const std::string& plot, NgspiceResult& result);

  size_t log_size() {
    std::lock_guard<std::mutex> lock(state_mutex_);
    return log_.size();
  }
  std::vector<Line> log_since(size_t mark) {
    std::lock_guard<std::mutex> lock(state_mutex_);
    return log_.since(mark);
  }
  std::vector<std::string> texts_since(size_t mark) {
    std::vector<std::string> out;
    for (const Line& line : log_since(mark)) out.push_back(line.text);
    return out;
  }
  std::vector<std::string> log_texts() {
    std::lock_guard<std::mutex> lock(state_mutex_);
    return log_.texts();
  }
  void reset_run_state() {
    std::lock_guard<std::mutex> lock(state_mutex_);
    log_.clear();
    simulated_time_ = 0;
  }
  bool exit_requested() {
    std::lock_guard<std::mutex> lock(state_mutex_);
    return exit_requested_;
  }
  // Did ngspice call (or announce) ControlledExit since `mark`? If it announced it, give the
  // background thread a moment to make the call, for the status.
  bool controlled_exit_after(size_t mark) {
    if (exit_requested()) return true;
    if (!ngspice_messages::announces_detach(log_since(mark))) return false;
    std::unique_lock<std::mutex> lock(state_mutex_);
    state_cv_.wait_for(lock, std::chrono::seconds(1), [this] { return exit_requested_; });
    return true;
  }

  // ngspice asked to be unloaded: its state is undefined from here on (after `quit` it frees
  // its vectors; after a numparam error every later deck fails the same way), and a linked
  // library cannot be reloaded. Every later call is Unavailable.
  [[noreturn]] void fail_aborted(const char* phase, const std::vector<Line>& lines);
  [[noreturn]] void fail(Kind kind, const std::string& what, bool clean_up = true) {
    std::vector<std::string> messages = log_texts();
    if (clean_up) clear_circuits_and_plots();
    throw NgspiceError(kind, what, std::move(messages));
  }

  std::mutex run_mutex_;  // one caller at a time, for the whole run

  std::mutex state_mutex_;  // what the callbacks write
  std::condition_variable state_cv_;
  ngspice_messages::Log log_;
  bool exit_requested_ = false;
  int exit_status_ = 0;
  bool exit_on_quit_ = false;
  long bg_starts_ = 0;
  long bg_ends_ = 0;
  std::atomic<double> simulated_time_{0};  // the scale of the last accepted point (on_data)

  const NgspiceLibrary* ngspice_ = nullptr;  // set once the library is loaded
  bool initialised_ = false;
  std::string unusable_;  // why ngspice cannot be used any more (empty: usable)
  NgspiceInfo info_;
};

int Engine::on_char(char* text, int, void* self) {
  try {
    auto* engine = static_cast<Engine*>(self);
    Line line = ngspice_messages::parse(text ? text : "");
    std::lock_guard<std::mutex> lock(engine->state_mutex_);
    engine->log_.add(std::move(line));
  } catch (...) {
  }
  return 0;
}

int Engine::on_data(pvecvaluesall values, int, int, void* self) {
  if (!values || !values->vecsa) return 0;
  for (int k = 0; k < values->veccount; ++k) {
    const pvecvalues v = values->vecsa[k];
    if (v && v->is_scale) {
      static_cast<Engine*>(self)->simulated_time_.store(v->creal, std::memory_order_relaxed);
      break;
    }
  }
  return 0;
}

int Engine::on_exit(int status, NG_BOOL, NG_BOOL quit, int, void* self) {
  auto* engine = static_cast<Engine*>(self);
  {
    std::lock_guard<std::mutex> lock(engine->state_mutex_);
    engine->exit_requested_ = true;
    engine->exit_status_ = status;
    engine->exit_on_quit_ = quit;
  }
  engine->state_cv_.notify_all();
  return 0;  // never exit(): ngspice then returns (longjmp) to the call in progress
}

int Engine::on_bg_thread(NG_BOOL exited, int, void* self) {
  auto* engine = static_cast<Engine*>(self);
  {
    std::lock_guard<std::mutex> lock(engine->state_mutex_);
    ++(exited ? engine->bg_ends_ : engine->bg_starts_);
  }
  engine->state_cv_.notify_all();
  return 0;
}

void Engine::ensure_initialised() {
  if (!unusable_.empty())
    throw NgspiceError(Kind::Unavailable, "ngspice is unavailable in this process: " + unusable_,
                       {});
  if (initialised_) return;
  ngspice_ = &loaded_library();

  // The user init file ngSpice_Init will source: ./.spiceinit if it exists, else the one in the
  // passwd home of the current uid (HOME is not consulted).
  std::string user_init;
  if (access(".spiceinit", F_OK) == 0) {
    user_init = "./.spiceinit";
  } else if (ngspice_passwd::current_user_has_entry()) {
    const struct passwd* pw = getpwuid(getuid());
    if (pw && pw->pw_dir) {
      std::string path = std::string(pw->pw_dir) + "/.spiceinit";
      if (access(path.c_str(), F_OK) == 0) user_init = path;
    }
  }

  reset_run_state();
  int rc = 0;
  bool stand_in_home = false;
  {
    SignalGuard signals;
    ngspice_passwd::PasswdFallback fallback;
    rc = ngspice_->ngSpice_Init(&Engine::on_char, nullptr, &Engine::on_exit, &Engine::on_data,
                                &Engine::on_init_data, &Engine::on_bg_thread, this);
    stand_in_home = fallback.used();
  }
  info_.init_messages = log_texts();
  if (stand_in_home)
    info_.init_messages.push_back("[lcspice: uid " + std::to_string(getuid()) +
                                  " has no passwd entry; ngspice's init was given the home "
                                  "/nonexistent, so no user .spiceinit was read]");
  if (rc != 0 || exit_requested()) {
    unusable_ = "ngSpice_Init failed";
    throw NgspiceError(Kind::Unavailable,
                       with_evidence("ngspice could not be initialised", info_.init_messages),
                       info_.init_messages);
  }
  initialised_ = true;
  info_.user_init_file = user_init;
  for (const std::string& line : info_.init_messages) {
    size_t at = line.find("ngspice-");
    if (at != std::string::npos && line.find("shared library") != std::string::npos) {
      size_t end = line.find(' ', at);
      info_.version = line.substr(at, end == std::string::npos ? std::string::npos : end - at);
    }
  }
  // Never wait for a person: with `interactive` set (a .spiceinit may set it) numparam errors ask
  // "Run Spice anyway? y/n" on standard input, and `askquit` asks before quitting.
  command("unset interactive");
  command("unset askquit");
  if (exit_requested()) fail_aborted("initialisation", log_since(0));
}

void Engine::command(const std::string& cmd) {
  std::string buffer = cmd;  // ngSpice_Command takes a char*
  SignalGuard signals;
  ngspice_->ngSpice_Command(buffer.data());
}

// Leaves no circuit and no plot but `const`. `remcirc` removes the current circuit and warns
// "there is no circuit loaded" when there is none left.
void Engine::clear_circuits_and_plots() {
  if (!unusable_.empty() || !initialised_) return;
  command("destroy all");
  for (int i = 0; i < 64; ++i) {
    const size_t mark = log_size();
    command("remcirc");
    bool none_left = false;
    for (const Line& line : log_since(mark))
      if (lower(line.text).find("no circuit loaded") != std::string::npos) none_left = true;
    if (none_left) break;
  }
}

bool Engine::wait_for_count(const long& counter, long before, Clock::time_point deadline) {
  std::unique_lock<std::mutex> lock(state_mutex_);
  while (true) {
    if (counter > before) return true;
    const auto now = Clock::now();
    if (now >= deadline) return false;
    state_cv_.wait_for(lock, std::min<Clock::duration>(deadline - now, kPollInterval));
  }
}

std::optional<std::string> Engine::tran_plot() {
  const char* current = ngspice_->ngSpice_CurPlot();
  if (current && starts_with_ci(current, "tran")) return std::string(current);
  // e.g. a deck with .tran and a later .op: the tran plot is not the current one
  if (char** plots = ngspice_->ngSpice_AllPlots())
    for (size_t i = 0; plots[i]; ++i)
      if (starts_with_ci(plots[i], "tran")) return std::string(plots[i]);
  return std::nullopt;
}

double Engine::simulated_time_reached() {
  std::optional<std::string> plot = tran_plot();
  if (!plot) return std::numeric_limits<double>::quiet_NaN();
  std::string name = *plot + ".time";
  const pvector_info info = ngspice_->ngGet_Vec_Info(name.data());
  if (!info || !info->v_realdata || info->v_length <= 0) return std::numeric_limits<double>::quiet_NaN();
  return info->v_realdata[info->v_length - 1];
}

void Engine::read_plot(const std::string& plot, NgspiceResult& result) {
  std::string plot_name = plot;
  std::vector<std::string> names;
  if (char** vecs = ngspice_->ngSpice_AllVecs(plot_name.data()))  // array reused by the next call: copy
    for (size_t i = 0; vecs[i]; ++i) names.emplace_back(vecs[i]);

  std::map<std::string, std::vector<double>> vectors;
  std::optional<std::vector<double>> time;
  for (const std::string& name : names) {
    std::string qualified = plot + "." + name;
    pvector_info info = ngspice_->ngGet_Vec_Info(qualified.data());
    if (!info) {
      std::string bare = name;
      info = ngspice_->ngGet_Vec_Info(bare.data());
    }
    if (!info || info->v_length < 0 || (info->v_length > 0 && !info->v_realdata && !info->v_compdata))
      fail(Kind::NoData, "ngspice listed the vector \"" + name + "\" of plot " + plot +
                             " but ngGet_Vec_Info could not read it");
    // ngGet_Vec_Info returns one static struct, overwritten by the next call: copy now.
    std::vector<double> data(static_cast<size_t>(info->v_length));
    for (size_t k = 0; k < data.size(); ++k)
      data[k] = info->v_realdata ? info->v_realdata[k] : info->v_compdata[k].cx_real;
    std::string key = lower(name);
    // ngspice names a node's vector by the node ("out"), but a numeric node's as "V(3)": a bare
    // number would read as a constant. The deck translation asks for nodes by name.
    if (key.size() > 3 && key.compare(0, 2, "v(") == 0 && key.back() == ')' &&
        key.find(',') == std::string::npos)
      key = key.substr(2, key.size() - 3);
    if (key == "time")
      time = std::move(data);
    else
      vectors[key] = std::move(data);
  }
  if (!time || time->empty())
    fail(Kind::NoData, "ngspice's plot " + plot + " has no time points");
  for (const auto& [name, data] : vectors)
    if (data.size() != time->size())
      fail(Kind::NoData, "ngspice's vector \"" + name + "\" has " + std::to_string(data.size()) +
                             " points but time has " + std::to_string(time->size()));
  result.time = std::move(*time);
  result.vectors = std::move(vectors);
}

void Engine::fail_aborted(const char* phase, const std::vector<Line>& lines) {
  int status;
  bool quit;
  {
    std::lock_guard<std::mutex> lock(state_mutex_);
    status = exit_status_;
    quit = exit_on_quit_;
  }
  std::vector<std::string> evidence;
  for (const Line& line : lines)
    if (line.stream == ngspice_messages::Stream::Err && evidence.size() < 6)
      evidence.push_back(line.text);
  unusable_ = std::string("ngspice asked to be unloaded during ") + phase +
              " (ControlledExit, status " + std::to_string(status) +
              (quit ? ", after `quit`" : "") + "); restart the process to use it again";
  std::string what = with_evidence(
      std::string("ngspice aborted during ") + phase + (quit ? " (it executed `quit`)" :
      " (it hit an error it cannot recover from and asked to be unloaded)"), evidence);
  fail(Kind::Aborted, what, /*clean_up=*/false);
}

NgspiceResult Engine::run(const NgspiceRun& run) {
  if (!std::isfinite(run.timeout_seconds) || run.timeout_seconds <= 0)
    throw std::invalid_argument("NgspiceRun::timeout_seconds must be finite and > 0, got " +
                                std::to_string(run.timeout_seconds));
  std::lock_guard<std::mutex> lock(run_mutex_);
  ensure_initialised();

  ngspice_deck::PreparedDeck deck = ngspice_deck::prepare(run.deck);
  if (!deck.error.empty())
    throw NgspiceError(Kind::Load, "ngspice deck rejected: " + deck.error, {});

  clear_circuits_and_plots();  // whatever an earlier failure left; its output is not this run's
  reset_run_state();

  // Load: ngspice parses the deck synchronously inside ngSpice_Circ.
  std::vector<char*> lines;
  for (std::string& line : deck.lines) lines.push_back(line.data());
  lines.push_back(nullptr);
  int rc;
  {
    SignalGuard signals;
    rc = ngspice_->ngSpice_Circ(lines.data());
  }
  if (rc != 0 || exit_requested()) fail_aborted("loading the deck", log_since(0));
  {
    std::vector<std::string> evidence;
    if (ngspice_messages::load_failed(log_since(0), evidence))
      fail(Kind::Load, with_evidence("ngspice could not load the deck", evidence));
  }

  // Run: the deck's analyses in ngspice's background thread, under the wall-clock limit.
  const size_t run_mark = log_size();
  long starts_before, ends_before;
  {
    std::lock_guard<std::mutex> state(state_mutex_);
    starts_before = bg_starts_;
    ends_before = bg_ends_;
  }
  const double cpu_start = process_cpu_seconds();
  const Clock::time_point start = Clock::now();
  const Clock::time_point deadline =
      start + std::chrono::duration_cast<Clock::duration>(
                  std::chrono::duration<double>(std::min(run.timeout_seconds, 1e9)));
  command("bg_run");

  bool finished = false;
  double reported = 0;
  while (true) {
    if (run.progress && simulated_time_.load(std::memory_order_relaxed) > reported)
      run.progress(reported = simulated_time_.load(std::memory_order_relaxed));
    if (wait_for_thread_end(ends_before, std::min(deadline, Clock::now() + kPollInterval))) {
      finished = true;
      break;
    }
    bool started;
    {
      std::lock_guard<std::mutex> state(state_mutex_);
      started = bg_starts_ > starts_before;
    }
    const auto now = Clock::now();
    // ngSpice_running() is true from the thread's start callback until it ends; a thread that
    // started and no longer runs has ended even if its end callback is still on its way.
    if (started && !ngspice_->ngSpice_running()) {
      wait_for_thread_end(ends_before, now + kHaltLimit);
      finished = true;
      break;
    }
    if (!started && now - start > kThreadStartLimit && !ngspice_->ngSpice_running())
      fail(Kind::Unavailable, with_evidence("ngspice did not start the analysis (bg_run)",
                                            texts_since(run_mark)));
    if (now >= deadline) break;
  }
  const double cpu_seconds = process_cpu_seconds() - cpu_start;

  if (!finished) {
    // A bg_halt that arrives before the thread has begun is lost: ngspice's _thread_stop reads
    // the exit flag the thread has not yet cleared, skips the interrupt, joins a detached thread
    // and reports it stopped, while the analysis runs on unhalted; destroying the circuit under
    // it crashed the process (a 1 ms time limit on a loaded machine: SIGSEGV in libngspice about
    // one run in ten). So the halt waits for the thread's start callback.
    const bool started = wait_for_thread_start(starts_before, Clock::now() + kThreadStartLimit);
    command("bg_halt");  // sets ngspice's interrupt flag and waits up to 1 s for the thread
    // Stopped: its end callback came. Not ngspice's running flag: a lost halt clears it with
    // the thread still running; and a thread that has not started within the limit may still
    // start, so nothing is cleared under it (the session is given up below).
    const bool stopped = started && wait_for_thread_end(ends_before, Clock::now() + kHaltLimit);
    std::string what = "ngspice exceeded the time limit of " + format_seconds(run.timeout_seconds);
    if (!stopped) {
      unusable_ = "an analysis that exceeded its time limit could not be stopped";
      fail(Kind::Timeout, what + " and could not be stopped; ngspice is unusable in this process",
           /*clean_up=*/false);
    }
    if (controlled_exit_after(run_mark)) fail_aborted("the analysis", log_since(run_mark));
    const double reached = simulated_time_reached();
    if (std::isfinite(reached))
      what += " (halted at simulated time " + format_seconds(reached) + ")";
    fail(Kind::Timeout, what);
  }
  if (controlled_exit_after(run_mark)) fail_aborted("the analysis", log_since(run_mark));

  std::vector<std::string> evidence;
  switch (ngspice_messages::classify_run(log_since(run_mark), evidence)) {
    case ngspice_messages::RunVerdict::NotLoaded:
      fail(Kind::Load, with_evidence("ngspice could not load the deck", evidence));
    case ngspice_messages::RunVerdict::Convergence:
      fail(Kind::Convergence, with_evidence("ngspice failed to converge", evidence));
    case ngspice_messages::RunVerdict::Interrupted:
      fail(Kind::Aborted, with_evidence("ngspice's analysis was interrupted", evidence));
    case ngspice_messages::RunVerdict::Completed:
      break;
  }

  std::optional<std::string> plot = tran_plot();
  if (!plot) {
    std::vector<std::string> said;
    for (const Line& line : log_since(run_mark))
      if (line.stream == ngspice_messages::Stream::Err) said.push_back(line.text);
    fail(Kind::NoData,
         with_evidence("ngspice produced no transient plot (does the deck have a .tran card?)",
                       said));
  }
  NgspiceResult result;
  read_plot(*plot, result);
  result.analysis_cpu_seconds = cpu_seconds;
  result.messages = log_texts();
  clear_circuits_and_plots();
  return result;
}

}  // namespace

NgspiceResult run_ngspice_transient(const NgspiceRun& run) { return Engine::instance().run(run); }

NgspiceInfo ngspice_info() { return Engine::instance().info(); }

void require_ngspice_library() { loaded_library(); }

}  // namespace lcs
