// libngspice, opened with dlopen when the bridge first needs it, and the entry points of its
// shared-library interface (sharedspice.h) that the bridge calls.
//
// Nothing links libngspice: `run`, `op`, `analyze` and `plot` never load it (nor the libgomp it
// pulls in), and `validate`/`bench` on a machine without it fail with a message naming the
// library and the loader's reason instead of not starting at all.
#pragma once

#include <ngspice/sharedspice.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace lcs {

class NgspiceLibraryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class NgspiceLibrary {
 public:
  // Opens the first of `candidates` (file names or paths, as dlopen takes them) that loads with
  // every entry point below. Throws NgspiceLibraryError listing each candidate tried and why it
  // failed (dlerror(): not found, a dependency missing, a symbol missing).
  explicit NgspiceLibrary(const std::vector<std::string>& candidates);
  // dlclose. If this was the last handle, libngspice is unmapped and LeakSanitizer can no longer
  // attribute its allocations to it (scripts/lsan.supp suppresses them by module name).
  ~NgspiceLibrary();
  NgspiceLibrary(const NgspiceLibrary&) = delete;
  NgspiceLibrary& operator=(const NgspiceLibrary&) = delete;

  const std::string& loaded_from() const { return loaded_from_; }  // the candidate that loaded

  decltype(&::ngSpice_Init) ngSpice_Init = nullptr;
  decltype(&::ngSpice_Command) ngSpice_Command = nullptr;
  decltype(&::ngSpice_Circ) ngSpice_Circ = nullptr;
  decltype(&::ngSpice_CurPlot) ngSpice_CurPlot = nullptr;
  decltype(&::ngSpice_AllPlots) ngSpice_AllPlots = nullptr;
  decltype(&::ngSpice_AllVecs) ngSpice_AllVecs = nullptr;
  decltype(&::ngGet_Vec_Info) ngGet_Vec_Info = nullptr;
  decltype(&::ngSpice_running) ngSpice_running = nullptr;

 private:
  void* handle_ = nullptr;
  std::string loaded_from_;
};

// Where libngspice is looked for: only $LCSPICE_NGSPICE_LIB when it is set and not empty;
// otherwise the file pkg-config pointed to at configure time (if there was one), then the
// SONAME "libngspice.so.0" and "libngspice.so" through the loader's search path.
std::vector<std::string> ngspice_library_candidates();

// The process's libngspice, loaded from ngspice_library_candidates() at the first successful
// call and never unloaded. Thread-safe. Throws NgspiceLibraryError (a later call tries again).
const NgspiceLibrary& ngspice_library();

}  // namespace lcs
