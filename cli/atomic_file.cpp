#include "cli/atomic_file.h"

#include <cstdio>

#include "cli/exit_codes.h"

#include <climits>
#include <csignal>
#include <cstring>
#include <cstdlib>
#include <sys/stat.h>
#include <unistd.h>

namespace lcs {

namespace {

// Temporary files in flight, removed if SIGINT/SIGTERM/SIGHUP ends the program first. Plain
// arrays: the handler may only use async-signal-safe calls.
constexpr int kSlots = 8;
char g_temps[kSlots][PATH_MAX];
volatile sig_atomic_t g_used[kSlots];

void remove_temps_and_die(int sig) {
  for (int k = 0; k < kSlots; ++k)
    if (g_used[k]) unlink(g_temps[k]);
  signal(sig, SIG_DFL);
  raise(sig);
}

void track(const std::string& temp) {
  static const bool installed = [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) signal(sig, remove_temps_and_die);
    return true;
  }();
  (void)installed;
  if (temp.size() >= PATH_MAX) return;
  for (int k = 0; k < kSlots; ++k)
    if (!g_used[k]) {
      std::memcpy(g_temps[k], temp.c_str(), temp.size() + 1);
      g_used[k] = 1;
      return;
    }
}

}  // namespace

void release_temp(const std::string& temp) {
  for (int k = 0; k < kSlots; ++k)
    if (g_used[k] && temp == g_temps[k]) g_used[k] = 0;
}

AtomicTarget atomic_target(const std::string& path) {
  struct stat st {};
  if (stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) return {false, path};
  if (lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode)) {
    char resolved[PATH_MAX];
    if (realpath(path.c_str(), resolved)) return {true, resolved};
    // A dangling link: create the file it points to (relative to the link's folder).
    char target[PATH_MAX];
    const ssize_t len = readlink(path.c_str(), target, sizeof target - 1);
    if (len > 0) {
      target[len] = '\0';
      std::string t(target);
      if (t[0] != '/') {
        const size_t slash = path.rfind('/');
        t = (slash == std::string::npos ? std::string() : path.substr(0, slash + 1)) + t;
      }
      return {true, t};
    }
  }
  return {true, path};
}

int create_temp_beside(const AtomicTarget& target, std::string* temp) {
  *temp = target.path + ".tmp-XXXXXX";
  const int fd = mkstemp(temp->data());
  if (fd < 0) return -1;
  struct stat st {};
  mode_t mode;
  if (stat(target.path.c_str(), &st) == 0) {
    mode = st.st_mode & 07777;
  } else {
    const mode_t mask = umask(0);
    umask(mask);
    mode = 0666 & ~mask;
  }
  fchmod(fd, mode);
  track(*temp);
  return fd;
}

AtomicFile::AtomicFile(const std::string& path) : path_(path), target_(atomic_target(path)) {
  temp_ = target_.path;
  if (target_.replace) {
    const int fd = create_temp_beside(target_, &temp_);
    if (fd < 0) throw CliError(kExitUsage, "error: cannot write '" + path + "'");
    close(fd);
  }
}

AtomicFile::~AtomicFile() {
  if (!committed_ && target_.replace) {
    std::remove(temp_.c_str());
    release_temp(temp_);
  }
}

void AtomicFile::commit() {
  committed_ = true;
  if (!target_.replace) return;
  const bool ok = std::rename(temp_.c_str(), target_.path.c_str()) == 0;
  release_temp(temp_);
  if (!ok) {
    std::remove(temp_.c_str());
    throw CliError(kExitUsage, "error: cannot write '" + path_ + "'");
  }
}

void write_text_file(const std::string& path, const std::string& text) {
  AtomicFile file(path);
  std::FILE* out = std::fopen(file.temp().c_str(), "w");
  const bool written = out && std::fwrite(text.data(), 1, text.size(), out) == text.size();
  if (!out || std::fclose(out) != 0 || !written)
    throw CliError(kExitUsage, "error: cannot write " + path + ": " + std::strerror(errno));
  file.commit();
}

}  // namespace lcs
