// See passwd_fallback.h for why this file defines a C library function.
#include "ngspice/passwd_fallback.h"

#include <dlfcn.h>
#include <pwd.h>
#include <unistd.h>

#include <atomic>

namespace {

std::atomic<bool> g_fallback_active{false};
std::atomic<bool> g_fallback_used{false};

using GetpwuidFn = struct passwd* (*)(uid_t);

GetpwuidFn real_getpwuid() {
  // The next definition after this executable's: the C library's.
  static const GetpwuidFn fn = reinterpret_cast<GetpwuidFn>(dlsym(RTLD_NEXT, "getpwuid"));
  return fn;
}

}  // namespace

extern "C" struct passwd* getpwuid(uid_t uid) {
  GetpwuidFn real = real_getpwuid();
  struct passwd* entry = real ? real(uid) : nullptr;
  if (entry || !g_fallback_active.load() || uid != getuid()) return entry;
  static char name[] = "lcspice";
  static char password[] = "x";
  static char gecos[] = "";
  static char home[] = "/nonexistent";
  static char shell[] = "/bin/false";
  static struct passwd stand_in;
  stand_in.pw_name = name;
  stand_in.pw_passwd = password;
  stand_in.pw_uid = uid;
  stand_in.pw_gid = getgid();
  stand_in.pw_gecos = gecos;
  stand_in.pw_dir = home;
  stand_in.pw_shell = shell;
  g_fallback_used = true;
  return &stand_in;
}

namespace lcs::ngspice_passwd {

PasswdFallback::PasswdFallback() {
  g_fallback_used = false;
  g_fallback_active = true;
}

PasswdFallback::~PasswdFallback() { g_fallback_active = false; }

bool PasswdFallback::used() const { return g_fallback_used.load(); }

bool current_user_has_entry() {
  GetpwuidFn real = real_getpwuid();
  return real && real(getuid()) != nullptr;
}

}  // namespace lcs::ngspice_passwd
