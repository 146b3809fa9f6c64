// Opening libngspice with dlopen: where it is looked for, what a file that is not it or is not
// there gives, and what the bridge reports when the library cannot be loaded. Tests that need a
// process where libngspice was never loaded run in a child through EXPECT_EXIT.
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "ngspice/ngspice_library.h"
#include "ngspice/ngspice_session.h"

namespace lcs {
namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::string load_error(const std::vector<std::string>& candidates) {
  try {
    NgspiceLibrary library(candidates);
  } catch (const NgspiceLibraryError& e) {
    return e.what();
  }
  return "";
}

// Sets (or, with nullptr, unsets) an environment variable for one scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value)
      setenv(name, value, 1);
    else
      unsetenv(name);
  }
  ~ScopedEnv() {
    if (old_)
      setenv(name_, old_->c_str(), 1);
    else
      unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(NgspiceLibrary, CandidatesAreTheSonameThenTheDevelopmentName) {
  ScopedEnv env("LCSPICE_NGSPICE_LIB", nullptr);
  const std::vector<std::string> c = ngspice_library_candidates();
  ASSERT_GE(c.size(), 2u);
  EXPECT_EQ(c[c.size() - 2], "libngspice.so.0");
  EXPECT_EQ(c.back(), "libngspice.so");
}

TEST(NgspiceLibrary, TheEnvironmentVariableIsTheOnlyCandidate) {
  ScopedEnv env("LCSPICE_NGSPICE_LIB", "/opt/ngspice/lib/libngspice.so.0");
  EXPECT_EQ(ngspice_library_candidates(), std::vector<std::string>{"/opt/ngspice/lib/libngspice.so.0"});
}

TEST(NgspiceLibrary, LoadsTheInstalledLibraryPastAMissingCandidate) {
  // The process-wide library first, so this second handle's dlclose leaves libngspice mapped:
  // LeakSanitizer matches lsan.supp's "libngspice.so" against the module of an allocation's
  // frames, and libngspice's allocations at load time would lose their module if it were unloaded.
  ngspice_library();
  std::vector<std::string> candidates = {"/nonexistent/libngspice.so.0"};
  for (const std::string& c : ngspice_library_candidates()) candidates.push_back(c);
  NgspiceLibrary library(candidates);
  EXPECT_NE(library.loaded_from(), "/nonexistent/libngspice.so.0");
  EXPECT_NE(library.ngSpice_Init, nullptr);
  EXPECT_NE(library.ngSpice_running, nullptr);
}

TEST(NgspiceLibrary, AMissingFileIsNamedWithTheLoadersReason) {
  const std::string what = load_error({"/nonexistent/libngspice.so.0"});
  EXPECT_TRUE(contains(what, "cannot load libngspice")) << what;
  EXPECT_TRUE(contains(what, "/nonexistent/libngspice.so.0: cannot open shared object file")) << what;
}

TEST(NgspiceLibrary, ALibraryWithoutTheEntryPointsIsRefused) {
  const std::string what = load_error({"libm.so.6"});
  EXPECT_TRUE(contains(what, "undefined symbol: ngSpice_Init")) << what;
}

TEST(NgspiceLibrary, EveryCandidateTriedIsReported) {
  const std::string what = load_error({"/nonexistent/a.so", "/nonexistent/b.so"});
  EXPECT_TRUE(contains(what, "/nonexistent/a.so: ")) << what;
  EXPECT_TRUE(contains(what, "; /nonexistent/b.so: ")) << what;
}

// In a fresh process: every bridge call is NoLibrary, not a crash, and names what was tried.
TEST(NgspiceLibraryDeathTest, WithoutTheLibraryTheBridgeSaysNoLibrary) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        setenv("LCSPICE_NGSPICE_LIB", "/nonexistent/libngspice.so.0", 1);
        int status = 0;
        try {
          require_ngspice_library();
          status = 1;
        } catch (const NgspiceError& e) {
          if (e.kind() != NgspiceError::Kind::NoLibrary) status = 2;
          if (!contains(e.what(), "/nonexistent/libngspice.so.0: cannot open")) status = 3;
        }
        try {
          run_ngspice_transient({{"t", "r1 a 0 1", ".tran 1m 1m", ".end"}, 10, nullptr});
          status = 4;
        } catch (const NgspiceError& e) {
          if (e.kind() != NgspiceError::Kind::NoLibrary) status = 5;
        }
        try {
          ngspice_info();
          status = 6;
        } catch (const NgspiceError& e) {
          if (e.kind() != NgspiceError::Kind::NoLibrary) status = 7;
        }
        std::_Exit(status);
      },
      ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace lcs
