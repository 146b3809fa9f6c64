// Writing an output file so that readers never see it torn: a temporary file beside the target,
// renamed into place. Devices and FIFOs (/dev/null, a pipe) are written in place instead, and a
// symbolic link has its target replaced, not the link.
#pragma once

#include <string>

namespace lcs {

struct AtomicTarget {
  bool replace = true;  // false: a device or FIFO, write in place
  std::string path;     // the file to rename onto (a symbolic link's target)
};
AtomicTarget atomic_target(const std::string& path);

// Creates the temporary file for `target` (its path in *temp) with the mode the final file
// should have: the replaced file's, or 0666 less the umask for a new one. Returns the open
// descriptor, or -1 with errno set.
// The temporary file is removed if SIGINT, SIGTERM or SIGHUP ends the program before
// release_temp() (called once it has been renamed into place or removed).
int create_temp_beside(const AtomicTarget& target, std::string* temp);
void release_temp(const std::string& temp);

// A file written under a temporary name and renamed into place by commit(); destroyed without
// commit(), the temporary file is removed. For devices and FIFOs temp() is the path itself.
class AtomicFile {
 public:
  explicit AtomicFile(const std::string& path);  // throws CliError (exit 1)
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  const std::string& temp() const { return temp_; }
  void commit();                                  // throws CliError (exit 1)

 private:
  std::string path_, temp_;
  AtomicTarget target_;
  bool committed_ = false;
};

// Writes `text` to `path` through an AtomicFile; throws CliError (exit 1) on failure.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace lcs
