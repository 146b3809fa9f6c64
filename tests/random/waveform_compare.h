// Discrepancy between two runs of one circuit, probe by probe, at every row of the reference run
// (the other run interpolated linearly between its rows), relative to a scale per probe.
#pragma once

#include <string>
#include <vector>

#include "tests/random/method_run.h"

namespace lcs::random_circuit {

struct ProbeDiscrepancy {
  std::string probe;
  // The probe's range in the reference run, but at least 1e-3 of the widest range and 1e-5 of
  // the largest magnitude among the reference's probes of its kind (voltages v(...), currents
  // i(...)), and 1 nV or 1 pA: a diode that never conducts has a zero range (a time-stepping
  // LCP's 1e-15 A there is no error), and a circuit that does not move has only rounding.
  double scale = 0;
  double mean = 0;  // mean of |other - reference| / scale over the reference's rows
  double max = 0;   // the largest |other - reference| / scale, and where it is:
  double worst_time = 0, reference_value = 0, other_value = 0;
};

struct CompareOptions {
  // The other run's value is also read at t - shift and t + shift, and the nearest of the three
  // counts. A time-stepping method places a switching instant or a source jump within a step of
  // where it is (a jump at a grid time lands on either side of k h by rounding); read without
  // that slack, one sample at such an edge costs the probe's full range however small h is.
  double shift = 0;
  // Read the other run as the mean of its values half a step (MethodRun::step) before and after
  // t: the trapezoidal rule's ringing, z alternating about the solution with factor -1 per step
  // after a switch (docs/stability.md), cancels in it, while a smooth signal moves by O(h^2).
  bool average_neighbours = false;
};

std::vector<ProbeDiscrepancy> discrepancies(const MethodRun& reference, const MethodRun& other,
                                            const CompareOptions& options = {});

}  // namespace lcs::random_circuit
