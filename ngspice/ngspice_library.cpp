#include "ngspice/ngspice_library.h"

#include <dlfcn.h>

#include <cstdlib>
#include <mutex>

namespace lcs {

namespace {

std::string last_dlerror(const std::string& fallback) {
  const char* e = dlerror();
  return e ? e : fallback;
}

// Resolves `name` into `fn`; returns false (and says why in `why`) if the library lacks it.
template <class Fn>
bool resolve(void* handle, const char* name, Fn& fn, std::string& why) {
  dlerror();  // clear: a symbol's value could legitimately be null
  void* address = dlsym(handle, name);
  if (!address) {
    why = last_dlerror(std::string("no symbol ") + name);
    return false;
  }
  fn = reinterpret_cast<Fn>(address);
  return true;
}

}  // namespace

NgspiceLibrary::NgspiceLibrary(const std::vector<std::string>& candidates) {
  std::string failures;
  for (const std::string& candidate : candidates) {
    // RTLD_NOW: a missing dependency fails here, not at the first call. RTLD_LOCAL: its symbols
    // stay out of the global scope. The executable's own getpwuid still comes first for its
    // calls (passwd_fallback.h).
    void* handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    std::string why;
    if (!handle) {
      why = last_dlerror("dlopen failed");
    } else if (resolve(handle, "ngSpice_Init", ngSpice_Init, why) &&
               resolve(handle, "ngSpice_Command", ngSpice_Command, why) &&
               resolve(handle, "ngSpice_Circ", ngSpice_Circ, why) &&
               resolve(handle, "ngSpice_CurPlot", ngSpice_CurPlot, why) &&
               resolve(handle, "ngSpice_AllPlots", ngSpice_AllPlots, why) &&
               resolve(handle, "ngSpice_AllVecs", ngSpice_AllVecs, why) &&
               resolve(handle, "ngGet_Vec_Info", ngGet_Vec_Info, why) &&
               resolve(handle, "ngSpice_running", ngSpice_running, why)) {
      handle_ = handle;
      loaded_from_ = candidate;
      return;
    } else {
      dlclose(handle);
    }
    failures += (failures.empty() ? "" : "; ") + why;
  }
  if (candidates.empty()) failures = "no candidate file names";
  throw NgspiceLibraryError("cannot load libngspice, the ngspice shared library (Debian: "
                            "libngspice0; LCSPICE_NGSPICE_LIB names another file): " + failures);
}

NgspiceLibrary::~NgspiceLibrary() {
  if (handle_) dlclose(handle_);
}

std::vector<std::string> ngspice_library_candidates() {
  const char* chosen = std::getenv("LCSPICE_NGSPICE_LIB");
  if (chosen && *chosen) return {chosen};
  std::vector<std::string> out;
#ifdef LCSPICE_NGSPICE_CONFIGURED_LIBRARY
  out.push_back(LCSPICE_NGSPICE_CONFIGURED_LIBRARY);
#endif
  out.push_back("libngspice.so.0");
  out.push_back("libngspice.so");
  return out;
}

const NgspiceLibrary& ngspice_library() {
  static std::mutex mutex;
  static const NgspiceLibrary* library = nullptr;  // never destroyed: ngspice may own a thread
  std::lock_guard<std::mutex> lock(mutex);
  if (!library) library = new NgspiceLibrary(ngspice_library_candidates());
  return *library;
}

}  // namespace lcs
