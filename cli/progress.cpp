#include "cli/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace lcs {

ProgressLine::ProgressLine(std::string label)
    : label_(std::move(label)), enabled_(isatty(STDERR_FILENO) == 1) {}

ProgressLine::~ProgressLine() {
  if (enabled_ && drawn_) std::fprintf(stderr, "\r\033[K");
}

void ProgressLine::update(double fraction, const std::string& detail) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_ < std::chrono::milliseconds(200)) return;
  last_ = now;
  drawn_ = true;
  const int percent = static_cast<int>(100 * std::clamp(fraction, 0.0, 1.0));
  std::fprintf(stderr, "\r\033[Klcspice: %s %3d%%%s%s", label_.c_str(), percent,
               detail.empty() ? "" : "  ", detail.c_str());
  std::fflush(stderr);
}

}  // namespace lcs
