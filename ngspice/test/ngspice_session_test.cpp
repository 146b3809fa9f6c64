// The bridge against the real libngspice: answers checked against closed forms, repeated and
// concurrent runs, every failure kind, and the process conditions of CI (no passwd entry, no
// HOME, closed standard input). Tests that need a fresh ngspice (it is one per process, and some
// failures leave it unusable) run in a child process through EXPECT_EXIT.
#include "tests/support/sanitizers.h"
#include <gtest/gtest.h>
#include <grp.h>
#include <pwd.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <future>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "ngspice/ngspice_session.h"

namespace lcs {
namespace {

using Kind = NgspiceError::Kind;

const std::vector<std::string> kRcDeck = {
    "RC step response",
    "V1 in 0 PULSE(0 1 0 1n 1n 1 2)",
    "R1 in out 1k",
    "C1 out 0 1u",
    ".tran 1u 5m 0 1u",
    ".end",
};

// A resistive divider loaded by a Shockley diode, driven by a ramp: every time point is a static
// solve of (vin - v)/R1 = v/R2 + IS (exp(v/(N Vt)) - 1) + GMIN v.
const std::vector<std::string> kDiodeDeck = {
    "Diode divider",
    "V1 in 0 PWL(0 0 1m 5)",
    "R1 in a 1k",
    "R2 a 0 10k",
    "D1 a 0 d1",
    ".model d1 D(IS=1e-14 N=1)",
    ".tran 10u 1m 0 10u",
    ".end",
};

// A 10 V step straight across a junction with N = 0.001: ngspice cannot follow it.
const std::vector<std::string> kTimestepTooSmallDeck = {
    "step across a sharp diode",
    "V1 in 0 PULSE(0 10 1u 1p 1p 1 2)",
    "D1 in 0 dd",
    ".model dd D(IS=1e-14 N=0.001)",
    ".tran 1u 10u",
    ".end",
};

// Ten seconds of a 1 kHz sine at a 1 ns maximum step: minutes of work.
const std::vector<std::string> kLongDeck = {
    "long transient",
    "V1 in 0 SIN(0 1 1k)",
    "R1 in out 1k",
    "C1 out 0 1u",
    ".tran 1n 10 0 1n",
    ".end",
};

// An undefined parameter makes ngspice's numparam stage call controlled_exit.
const std::vector<std::string> kControlledExitDeck = {
    "undefined parameter",
    "V1 in 0 DC 1",
    "R1 in 0 1k",
    ".model d1 D(IS=abc N=1)",
    "D1 in 0 d1",
    ".tran 1u 1m",
    ".end",
};

NgspiceRun run_of(std::vector<std::string> deck, double timeout = 60) {
  NgspiceRun run;
  run.deck = std::move(deck);
  run.timeout_seconds = timeout;
  return run;
}

// Runs `deck`, expects an NgspiceError of `kind`, returns it.
NgspiceError expect_failure(const std::vector<std::string>& deck, Kind kind, double timeout = 60) {
  try {
    NgspiceResult r = run_ngspice_transient(run_of(deck, timeout));
    ADD_FAILURE() << "expected a " << to_string(kind) << " error, got " << r.time.size()
                  << " time points";
  } catch (const NgspiceError& e) {
    EXPECT_EQ(e.kind(), kind) << to_string(e.kind()) << ": " << e.what();
    return e;
  }
  return NgspiceError(Kind::Unavailable, "no error", {});
}

bool any_message_contains(const std::vector<std::string>& messages, const std::string& text) {
  for (const std::string& m : messages)
    if (m.find(text) != std::string::npos) return true;
  return false;
}

double max_rc_error(const NgspiceResult& r) {
  const std::vector<double>& out = r.vectors.at("out");
  double worst = 0;
  for (size_t k = 0; k < r.time.size(); ++k)
    worst = std::max(worst, std::abs(out[k] - (1 - std::exp(-r.time[k] / 1e-3))));
  return worst;
}

// The diode equation solved by bisection (f decreases in v).
double divider_voltage(double vin) {
  const double kBoltzmann = 1.38064852e-23, kCharge = 1.6021766208e-19, kT = 300.15;
  const double vt = kBoltzmann * kT / kCharge, is = 1e-14, gmin = 1e-12;
  auto f = [&](double v) {
    return (vin - v) / 1e3 - v / 10e3 - is * std::expm1(v / vt) - gmin * v;
  };
  double lo = std::min(0.0, vin), hi = std::max(0.0, vin);
  for (int i = 0; i < 200; ++i) {
    double mid = 0.5 * (lo + hi);
    (f(mid) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(NgspiceSession, RcStepResponseMatchesClosedForm) {
  const auto wall_start = std::chrono::steady_clock::now();
  NgspiceResult r = run_ngspice_transient(run_of(kRcDeck));
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  ASSERT_GT(r.time.size(), 1000u);  // TMAX = 1 us over 5 ms
  EXPECT_EQ(r.time.front(), 0.0);
  EXPECT_NEAR(r.time.back(), 5e-3, 1e-12);
  for (size_t k = 1; k < r.time.size(); ++k) ASSERT_GT(r.time[k], r.time[k - 1]);
  ASSERT_EQ(r.vectors.count("out"), 1u);
  ASSERT_EQ(r.vectors.count("in"), 1u);
  ASSERT_EQ(r.vectors.count("v1#branch"), 1u);
  EXPECT_EQ(r.vectors.count("time"), 0u);  // the scale is r.time
  for (const auto& [name, data] : r.vectors) EXPECT_EQ(data.size(), r.time.size()) << name;

  const std::vector<double>& out = r.vectors.at("out");
  for (size_t k = 0; k < r.time.size(); ++k)
    ASSERT_NEAR(out[k], 1 - std::exp(-r.time[k] / 1e-3), 1e-3) << "t = " << r.time[k];
  // The source current is the capacitor's charging current, -(1 - v)/R.
  const std::vector<double>& i = r.vectors.at("v1#branch");
  for (size_t k = 0; k < r.time.size(); ++k)
    if (r.time[k] > 1e-8) {
      ASSERT_NEAR(i[k], -(1 - out[k]) / 1e3, 1e-9) << "t = " << r.time[k];
    }

  std::cout << "[ timing ] RC 1k/1u, .tran 1u 5m TMAX 1u: " << r.time.size() << " points, "
            << r.analysis_cpu_seconds << " s CPU, " << wall << " s wall (whole call), max error "
            << max_rc_error(r) << "\n";
}

// Compares every point with the diode equation; returns the worst |error|. `tolerance(v)` is the
// allowed error at the exact voltage v.
template <typename Tolerance>
double check_divider(const NgspiceResult& r, Tolerance tolerance) {
  EXPECT_GT(r.time.size(), 50u);
  const std::vector<double>& a = r.vectors.at("a");
  const std::vector<double>& i = r.vectors.at("v1#branch");
  double worst = 0;
  int conducting = 0;
  for (size_t k = 0; k < r.time.size(); ++k) {
    const double vin = 5 * r.time[k] / 1e-3;
    const double expected = divider_voltage(vin);
    worst = std::max(worst, std::abs(a[k] - expected));
    EXPECT_NEAR(a[k], expected, tolerance(expected)) << "t = " << r.time[k] << ", vin = " << vin;
    EXPECT_NEAR(i[k], -(vin - a[k]) / 1e3, 1e-12 + 1e-9 * std::abs(i[k])) << "t = " << r.time[k];
    if (expected > 0.55) ++conducting;
  }
  EXPECT_GT(conducting, 10);  // the comparison covers the exponential part, not just the linear one
  // A few operating points by name: the returned points nearest 0.2, 0.5 and 1 ms (vin = 1, 2.5,
  // 5 V), where the diode carries about 0.2, 1.8 and 4.2 mA.
  for (double t : {0.2e-3, 0.5e-3, 1e-3}) {
    size_t k = 0;
    for (size_t j = 1; j < r.time.size(); ++j)
      if (std::abs(r.time[j] - t) < std::abs(r.time[k] - t)) k = j;
    EXPECT_NEAR(r.time[k], t, 20e-6);
    const double expected = divider_voltage(5 * r.time[k] / 1e-3);
    EXPECT_GT(expected, 0.6);
    EXPECT_NEAR(a[k], expected, tolerance(expected)) << "t = " << r.time[k];
  }
  return worst;
}

TEST(NgspiceSession, DiodeDividerMatchesDiodeEquation) {
  // Default options: ngspice stops Newton when the update is below RELTOL |v| + VNTOL.
  NgspiceResult r = run_ngspice_transient(run_of(kDiodeDeck));
  const double worst_default =
      check_divider(r, [](double v) { return 1e-3 * std::abs(v) + 1e-6; });

  // Tight options: the answer must follow the equation much more closely.
  std::vector<std::string> tight = kDiodeDeck;
  tight.insert(tight.end() - 2, ".options reltol=1e-6 vntol=1e-9 abstol=1e-15");
  NgspiceResult t = run_ngspice_transient(run_of(tight));
  const double worst_tight = check_divider(t, [](double) { return 1e-6; });
  EXPECT_LT(worst_tight, worst_default);
  std::cout << "[ detail ] diode divider: " << r.time.size() << " points, max |error| "
            << worst_default << " V (default options), " << worst_tight << " V (reltol=1e-6)\n";
}

TEST(NgspiceSession, SubcircuitNodesAndSavedDeviceVectorsAreRead) {
  NgspiceResult r = run_ngspice_transient(run_of({
      "subcircuit divider",
      "V1 in 0 PWL(0 0 1m 5)",
      "X1 in a div",
      "D1 a 0 d1",
      ".model d1 D(IS=1e-14 N=1)",
      ".subckt div p q",
      "R1 p n1 500",
      "R2 n1 q 500",
      ".ends",
      ".options reltol=1e-6 vntol=1e-9 abstol=1e-15",
      ".save all @d1[id]",
      ".tran 10u 1m",
      ".end",
  }));
  ASSERT_EQ(r.vectors.count("x1.n1"), 1u);
  ASSERT_EQ(r.vectors.count("@d1[id]"), 1u);
  const auto& in = r.vectors.at("in");
  const auto& a = r.vectors.at("a");
  const auto& n1 = r.vectors.at("x1.n1");
  const auto& id = r.vectors.at("@d1[id]");
  for (size_t k = 0; k < r.time.size(); ++k) {
    EXPECT_NEAR(n1[k], 0.5 * (in[k] + a[k]), 1e-9);
    // KCL at a; @d1[id] is evaluated at the last Newton iterate, so it agrees to the tolerances.
    EXPECT_NEAR(id[k], (in[k] - a[k]) / 1e3, 1e-12 + 1e-4 * std::abs(id[k]));
  }
}

TEST(NgspiceSession, RepeatedRunsGiveTheSameAnswers) {
  const NgspiceResult rc = run_ngspice_transient(run_of(kRcDeck));
  const NgspiceResult diode = run_ngspice_transient(run_of(kDiodeDeck));
  for (int i = 0; i < 20; ++i) {
    const bool odd = i % 2;
    const NgspiceResult again = run_ngspice_transient(run_of(odd ? kDiodeDeck : kRcDeck));
    const NgspiceResult& single = odd ? diode : rc;
    ASSERT_EQ(again.time, single.time) << "run " << i;
    ASSERT_EQ(again.vectors, single.vectors) << "run " << i;  // no mixing, bit for bit
  }
}

long resident_kib() {
  long pages_total = 0, pages_resident = 0;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld %ld", &pages_total, &pages_resident) != 2) pages_resident = 0;
    std::fclose(f);
  }
  return pages_resident * (sysconf(_SC_PAGESIZE) / 1024);
}

// Each RC run makes a plot of 4 x 5022 doubles (160 kB) and a circuit; without `destroy all`
// and `remcirc` between runs, 100 runs keep 18 MB (no `remcirc`: 2 MB; neither: 0.1-0.3 MB here).
TEST(NgspiceSession, RepeatedRunsDoNotAccumulatePlotsOrCircuits) {
#if LCS_UNDER_ASAN
  GTEST_SKIP() << "AddressSanitizer's quarantine keeps freed memory resident";
#endif
  for (int i = 0; i < 10; ++i) run_ngspice_transient(run_of(kRcDeck));
  const long before = resident_kib();
  for (int i = 0; i < 100; ++i) run_ngspice_transient(run_of(kRcDeck));
  const long grown = resident_kib() - before;
  std::cout << "[ detail ] resident memory grew " << grown << " KiB over 100 runs\n";
  EXPECT_LT(grown, 1024);
}

TEST(NgspiceSession, ConcurrentCallersAreSerialised) {
  const NgspiceResult reference = run_ngspice_transient(run_of(kRcDeck));
  std::vector<std::future<NgspiceResult>> runs;
  for (int i = 0; i < 4; ++i)
    runs.push_back(std::async(std::launch::async, [] { return run_ngspice_transient(run_of(kRcDeck)); }));
  for (auto& f : runs) {
    NgspiceResult r = f.get();
    EXPECT_EQ(r.time, reference.time);
    EXPECT_EQ(r.vectors, reference.vectors);
  }
}

TEST(NgspiceSession, DeckShapesThatNgspiceWouldMisreadAreNormalised) {
  const NgspiceResult reference = run_ngspice_transient(run_of(kRcDeck));
  std::vector<std::string> no_end(kRcDeck.begin(), kRcDeck.end() - 1);
  std::vector<std::string> trailing = kRcDeck;
  trailing.push_back("R9 in 0 1");  // after .end: must not leak into this or the next run
  std::vector<std::string> blank_title = kRcDeck;
  blank_title[0] = "";
  std::string one_string;
  for (const std::string& line : kRcDeck) one_string += line + "\r\n";
  for (const auto& deck : {no_end, trailing, blank_title, std::vector<std::string>{one_string}}) {
    NgspiceResult r = run_ngspice_transient(run_of(deck));
    EXPECT_EQ(r.time, reference.time);
    EXPECT_EQ(r.vectors, reference.vectors);
  }
}

TEST(NgspiceSession, NormalRunReportsCpuTimeAndMessages) {
  NgspiceResult r = run_ngspice_transient(run_of(kRcDeck));
  EXPECT_GT(r.analysis_cpu_seconds, 0.0);
  EXPECT_LT(r.analysis_cpu_seconds, 30.0);
  ASSERT_FALSE(r.messages.empty());
  EXPECT_TRUE(any_message_contains(r.messages, "Circuit: rc step response"));
  EXPECT_TRUE(any_message_contains(r.messages, "No. of Data Rows"));
  for (const std::string& m : r.messages) {
    EXPECT_NE(m.rfind("stdout ", 0), 0u) << m;
    EXPECT_NE(m.rfind("stderr ", 0), 0u) << m;
  }
}

TEST(NgspiceSession, InfoReportsTheLibrary) {
  NgspiceInfo info = ngspice_info();
  EXPECT_EQ(info.version.rfind("ngspice-", 0), 0u) << info.version;
  EXPECT_TRUE(any_message_contains(info.init_messages, "shared library"));
}

TEST(NgspiceErrors, UnknownModelIsALoadError) {
  NgspiceError e = expect_failure({"unknown model", "V1 in 0 DC 1", "R1 in out 1k",
                                   "D1 out 0 nomodel", ".tran 1u 1m", ".end"},
                                  Kind::Load);
  EXPECT_TRUE(any_message_contains(e.messages(), "could not find a valid modelname"));
  EXPECT_NE(std::string(e.what()).find("could not find a valid modelname"), std::string::npos)
      << e.what();
}

TEST(NgspiceErrors, SyntaxErrorsAreLoadErrors) {
  NgspiceError e = expect_failure(
      {"syntax", "V1 in 0 DC 1", "foo bar baz", ".tran 1u 1m", ".end"}, Kind::Load);
  EXPECT_TRUE(any_message_contains(e.messages(), "Error: not enough parameters in line"));
  e = expect_failure({"bad value", "V1 in 0 DC 1", "R1 in 0 abc", ".tran 1u 1m", ".end"},
                     Kind::Load);
  EXPECT_TRUE(any_message_contains(e.messages(), "unknown parameter (abc)"));
  e = expect_failure({"bad tran", "V1 in 0 DC 1", "R1 in 0 1k", ".tran 0 1m", ".end"},
                     Kind::Load);
  EXPECT_TRUE(any_message_contains(e.messages(), "TSTEP is invalid, must be greater than zero."));
  e = expect_failure({"missing include", ".include /nonexistent/lcspice-missing.lib",
                      "V1 in 0 DC 1", "R1 in 0 1k", ".tran 1u 1m", ".end"},
                     Kind::Load);
  EXPECT_TRUE(any_message_contains(e.messages(),
                                   "Could not find include file /nonexistent/lcspice-missing.lib"));
}

TEST(NgspiceErrors, DecksTheBridgeRefusesAreLoadErrors) {
  NgspiceError e = expect_failure(
      {"controls", "V1 in 0 DC 1", "R1 in 0 1k", ".tran 1u 1m", ".control", "quit", ".endc", ".end"},
      Kind::Load);
  EXPECT_NE(std::string(e.what()).find(".control"), std::string::npos) << e.what();
  expect_failure({}, Kind::Load);
  EXPECT_THROW(run_ngspice_transient(run_of(kRcDeck, 0)), std::invalid_argument);
  EXPECT_THROW(run_ngspice_transient(run_of(kRcDeck, NAN)), std::invalid_argument);
  // None of that disturbed ngspice.
  EXPECT_LT(max_rc_error(run_ngspice_transient(run_of(kRcDeck))), 1e-3);
}

TEST(NgspiceErrors, TimestepTooSmallIsAConvergenceError) {
  NgspiceError e = expect_failure(kTimestepTooSmallDeck, Kind::Convergence);
  EXPECT_TRUE(any_message_contains(
      e.messages(), "doAnalyses: TRAN:  Timestep too small; time = 1e-06, timestep = 2.5e-19: "
                    "trouble with dd-instance d1"));
  EXPECT_TRUE(any_message_contains(e.messages(), "run simulation(s) aborted"));
  EXPECT_NE(std::string(e.what()).find("Timestep too small"), std::string::npos) << e.what();
}

TEST(NgspiceErrors, FailedOperatingPointIsAConvergenceError) {
  NgspiceError e = expect_failure({"op fails", "V1 in 0 DC 10", "D1 in 0 dd",
                                   ".model dd D(IS=1e-14 N=0.001)", ".tran 1u 10u", ".end"},
                                  Kind::Convergence);
  EXPECT_TRUE(any_message_contains(e.messages(), "Error: Transient op failed, timestep too small"));
  EXPECT_TRUE(any_message_contains(e.messages(), "Timestep too small; initial timepoint"));
}

TEST(NgspiceErrors, TimeoutHaltsTheRunAndNgspiceStaysUsable) {
  const auto start = std::chrono::steady_clock::now();
  NgspiceError e = expect_failure(kLongDeck, Kind::Timeout, 0.3);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(elapsed, 0.3);
  EXPECT_LT(elapsed, 3.0);
  EXPECT_NE(std::string(e.what()).find("time limit of 0.3 s"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("halted at simulated time"), std::string::npos) << e.what();
  EXPECT_TRUE(any_message_contains(e.messages(), "run simulation interrupted"));
  std::cout << "[ detail ] timeout: " << e.what() << ", call took " << elapsed << " s\n";

  NgspiceResult r = run_ngspice_transient(run_of(kRcDeck));
  EXPECT_LT(max_rc_error(r), 1e-3);
  EXPECT_NEAR(r.time.back(), 5e-3, 1e-12);
}

TEST(NgspiceSession, ProgressIsReportedOnTheCallersThreadAsItGrows) {
  std::vector<double> times;
  const std::thread::id caller = std::this_thread::get_id();
  bool other_thread = false;
  NgspiceRun run = run_of(kLongDeck, 1.0);
  run.progress = [&](double t) {
    times.push_back(t);
    other_thread |= std::this_thread::get_id() != caller;
  };
  double halted_at = 0;
  try {
    run_ngspice_transient(run);
    ADD_FAILURE() << "the 10 s transient at 1 ns steps finished within 1 s";
  } catch (const NgspiceError& e) {
    EXPECT_EQ(e.kind(), Kind::Timeout) << e.what();
    const std::string what = e.what();
    const size_t at = what.find("halted at simulated time ");
    if (at != std::string::npos) halted_at = std::atof(what.c_str() + at + 25);
  }
  EXPECT_FALSE(other_thread);
  ASSERT_GE(times.size(), 10u);  // polled every 5 ms for 1 s while ngspice moves on at 1 ns
  EXPECT_GT(times.front(), 0.0);
  for (size_t k = 1; k < times.size(); ++k) ASSERT_GT(times[k], times[k - 1]);
  EXPECT_LE(times.back(), halted_at);  // ngspice's accepted points reach no further than the plot
  std::cout << "[ detail ] progress: " << times.size() << " reports, last " << times.back()
            << " s of 10 s; halted at " << halted_at << " s\n";

  // The next run starts from 0 again (not from where the halted one stopped) and a run that
  // completes reports no point beyond its TSTOP: 20 us at 1 ns steps, well short of the halt.
  ASSERT_GT(halted_at, 2e-5);
  times.clear();
  NgspiceRun shorter = run_of({"short transient", "V1 in 0 SIN(0 1 1k)", "R1 in out 1k", "C1 out 0 1u",
                               ".tran 1n 20u 0 1n", ".end"});
  shorter.progress = [&](double t) { times.push_back(t); };
  NgspiceResult r = run_ngspice_transient(shorter);
  EXPECT_NEAR(r.time.back(), 2e-5, 1e-15);
  for (double t : times) EXPECT_LE(t, 2e-5);
}

TEST(NgspiceErrors, DeckWithoutTranIsNoData) {
  NgspiceError e =
      expect_failure({"no analysis", "V1 in 0 DC 1", "R1 in 0 1k", ".end"}, Kind::NoData);
  EXPECT_TRUE(any_message_contains(e.messages(), "Warning: No job (tran, ac, op etc.) defined:"));
  expect_failure({"only op", "V1 in 0 DC 1", "R1 in 0 1k", ".op", ".end"}, Kind::NoData);
  EXPECT_LT(max_rc_error(run_ngspice_transient(run_of(kRcDeck))), 1e-3);
}

// In a child process: the controlled exit leaves ngspice unusable for the rest of that process.
TEST(NgspiceErrorsDeathTest, ControlledExitIsAbortedAndLeavesNgspiceUnavailable) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        int failures = 0;
        try {
          run_ngspice_transient(run_of(kControlledExitDeck));
          std::cerr << "no error\n";
          ++failures;
        } catch (const NgspiceError& e) {
          if (e.kind() != Kind::Aborted) ++failures;
          if (!any_message_contains(e.messages(), "Undefined parameter [abc]")) ++failures;
          if (!any_message_contains(e.messages(), "ngspice.dll cannot recover")) ++failures;
          std::cerr << to_string(e.kind()) << ": " << e.what() << "\n";
        }
        try {
          run_ngspice_transient(run_of(kRcDeck));
          std::cerr << "ran after the controlled exit\n";
          ++failures;
        } catch (const NgspiceError& e) {
          if (e.kind() != Kind::Unavailable) ++failures;
          std::cerr << to_string(e.kind()) << ": " << e.what() << "\n";
        }
        std::_Exit(failures);
      },
      ::testing::ExitedWithCode(0), "");
}

// Run the RC deck in a fresh process after `prepare` changed its conditions; exit 0 if right.
void expect_rc_in_child(const std::function<void()>& prepare) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        prepare();
        int status = 1;
        try {
          NgspiceResult r = run_ngspice_transient(run_of(kRcDeck));
          status = max_rc_error(r) < 1e-3 && r.time.size() > 1000 ? 0 : 2;
          NgspiceError t = expect_failure(kLongDeck, Kind::Timeout, 0.2);
          if (t.kind() != Kind::Timeout) status = 3;
          if (max_rc_error(run_ngspice_transient(run_of(kRcDeck))) >= 1e-3) status = 4;
        } catch (const std::exception& e) {
          std::cerr << e.what() << "\n";
        }
        std::_Exit(status);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(NgspiceProcessDeathTest, WorksWithoutHomeAndWithStdinClosed) {
  expect_rc_in_child([] {
    unsetenv("HOME");
    close(STDIN_FILENO);
  });
}

TEST(NgspiceProcessDeathTest, WorksWithUnwritableHome) {
  expect_rc_in_child([] {
    setenv("HOME", "/proc", 1);
    close(STDIN_FILENO);
  });
}

// ngspice 39's init dereferences getpwuid(getuid()) unchecked (passwd_fallback.h).
TEST(NgspiceProcessDeathTest, WorksForAUidWithoutPasswdEntry) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to switch to a uid without a passwd entry";
  constexpr uid_t uid = 4242;  // constexpr: the lambda below reads it without a capture
  if (getpwuid(uid) != nullptr) GTEST_SKIP() << "uid 4242 has a passwd entry here";
  expect_rc_in_child([] {
    if (setgroups(0, nullptr) != 0 || setresgid(uid, uid, uid) != 0 || setresuid(uid, uid, uid) != 0)
      std::_Exit(10);
    unsetenv("HOME");
  });
}

// glibc adds SA_RESTORER (not in the headers) to every disposition it installs.
bool same_disposition(const struct sigaction& a, const struct sigaction& b) {
  constexpr int kRestorer = 0x04000000;
  return (a.sa_flags & ~kRestorer) == (b.sa_flags & ~kRestorer) &&
         ((a.sa_flags & SA_SIGINFO) ? a.sa_sigaction == b.sa_sigaction : a.sa_handler == b.sa_handler);
}

void on_signal_info(int, siginfo_t*, void*) {}

// In a fresh process (so init happens here): install a SA_SIGINFO handler, run, check that every
// disposition is as it was. Exits 0 if so.
[[noreturn]] void check_signal_dispositions() {
  const int signals[] = {SIGINT, SIGSEGV, SIGILL, SIGFPE, SIGTERM};
  constexpr int kCount = sizeof(signals) / sizeof(signals[0]);
  struct sigaction mine {};
  mine.sa_sigaction = on_signal_info;
  mine.sa_flags = SA_SIGINFO | SA_ONSTACK;
  sigemptyset(&mine.sa_mask);
  sigaction(SIGSEGV, &mine, nullptr);
  struct sigaction before[kCount], after[kCount];
  for (int i = 0; i < kCount; ++i) sigaction(signals[i], nullptr, &before[i]);
  int status = 0;
  try {
    run_ngspice_transient(run_of(kRcDeck));
    expect_failure(kLongDeck, Kind::Timeout, 0.2);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    status = 1;
  }
  for (int i = 0; i < kCount; ++i) {
    sigaction(signals[i], nullptr, &after[i]);
    if (!same_disposition(before[i], after[i])) {
      std::cerr << "signal " << signals[i] << " changed\n";
      status = 2;
    }
  }
  std::_Exit(status);
}

// ngSpice_Init swaps SIGSEGV with signal() (losing SA_SIGINFO) and toggles SIGILL; the bridge
// restores the caller's dispositions.
TEST(NgspiceProcessDeathTest, SignalDispositionsSurviveInitAndRuns) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(check_signal_dispositions(), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace lcs
