// Works around a crash of ngspice 39's ngSpice_Init when the current user has no passwd entry.
//
// ngSpice_Init looks for the user init file: `./.spiceinit` if it exists, else
// `getpwuid(getuid())->pw_dir + "/.spiceinit"` -- without checking for NULL (fixed upstream later).
// In containers and CI runners started with an arbitrary uid (`docker run --user 12345`) there is
// no such entry and the process dies with SIGSEGV inside ngSpice_Init. HOME plays no part.
//
// The bridge defines getpwuid() itself (passwd_fallback.cpp). Every executable that links the
// bridge exports that definition (ngspice/CMakeLists.txt), and libngspice, opened with dlopen,
// finds the executable's symbols before the C library's, so its call binds to it. It forwards to the C library's
// getpwuid, and only while a PasswdFallback is alive (the bridge holds one around ngSpice_Init,
// under its mutex) does it answer a failed lookup of the current uid with a stand-in entry whose
// home is "/nonexistent" (so no user init file is read). At all other times, and for every other
// caller, it is exactly the C library's function.
#pragma once

namespace lcs::ngspice_passwd {

class PasswdFallback {
 public:
  PasswdFallback();
  ~PasswdFallback();
  PasswdFallback(const PasswdFallback&) = delete;
  PasswdFallback& operator=(const PasswdFallback&) = delete;
  // True if the stand-in entry was handed out during this object's lifetime.
  bool used() const;
};

// True if the C library knows the current uid (so ngspice reads ~/.spiceinit from its home).
bool current_user_has_entry();

}  // namespace lcs::ngspice_passwd
