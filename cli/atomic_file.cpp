#include "cli/atomic_file.h"

#include <climits>
#include <cstdlib>
#include <sys/stat.h>
#include <unistd.h>

namespace lcs {

AtomicTarget atomic_target(const std::string& path) {
  struct stat st {};
  if (stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) return {false, path};
  char resolved[PATH_MAX];
  if (lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode) && realpath(path.c_str(), resolved))
    return {true, resolved};
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
  return fd;
}

}  // namespace lcs
