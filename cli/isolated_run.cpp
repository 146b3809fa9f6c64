#include "cli/isolated_run.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>

namespace lcs {

namespace {

void write_all(int fd, const std::string& text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<size_t>(n);
  }
}

[[noreturn]] void child_main(int report_fd, const std::function<std::string()>& work) {
  const int null_fd = ::open("/dev/null", O_WRONLY);
  if (null_fd >= 0) {
    ::dup2(null_fd, STDOUT_FILENO);
    ::dup2(null_fd, STDERR_FILENO);
  }
  std::string report;
  try {
    report = work();
  } catch (const std::exception& e) {
    report = std::string("error: ") + e.what();
  } catch (...) {
    report = "error: unknown exception";
  }
  write_all(report_fd, report);
  ::close(report_fd);
  ::_exit(0);  // no atexit handlers, no flushing of the parent's copied stdio buffers
}

double seconds(const timeval& t) { return t.tv_sec + 1e-6 * t.tv_usec; }

}  // namespace

IsolatedRun run_isolated(const std::function<std::string()>& work, double timeout_seconds) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error(std::string("cannot make a pipe: ") + std::strerror(errno));
  std::fflush(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(std::string("cannot fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::close(fds[0]);
    child_main(fds[1], work);
  }
  ::close(fds[1]);

  IsolatedRun result;
  bool timed_out = false;
  char buf[4096];
  for (;;) {
    const double left =
        timeout_seconds - std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (left <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::ceil(std::min(left, 3600.0) * 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;  // the loop re-checks the time left
    const ssize_t n = ::read(fds[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of file: the child closed its end (reported, or died)
    result.report.append(buf, static_cast<size_t>(n));
  }
  ::close(fds[0]);
  if (timed_out) ::kill(pid, SIGKILL);

  int status = 0;
  rusage usage{};
  while (::wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.peak_rss_mb = usage.ru_maxrss / 1024.0;  // Linux: KiB
  result.child_cpu_seconds = seconds(usage.ru_utime) + seconds(usage.ru_stime);
  char why[96];
  if (timed_out) {
    result.outcome = IsolatedRun::Outcome::TimedOut;
    std::snprintf(why, sizeof why, "timed out after %.3g s (wall clock)", timeout_seconds);
    result.why = why;
    result.report.clear();
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    result.outcome = IsolatedRun::Outcome::Finished;
  } else {
    result.outcome = IsolatedRun::Outcome::Crashed;
    if (WIFSIGNALED(status))
      std::snprintf(why, sizeof why, "the child process died of signal %d (%s)", WTERMSIG(status),
                    strsignal(WTERMSIG(status)));
    else
      std::snprintf(why, sizeof why, "the child process exited with status %d", WEXITSTATUS(status));
    result.why = why;
  }
  return result;
}

}  // namespace lcs
