// Several solutions of a step's LCP (transistor feedback, Stewart 5.4.7): the warm-started
// solver keeps the one continuous with the previous state -- the hysteresis a real flip-flop or
// multivibrator shows, the charge in its bases holding the mode -- and this says so once; where
// the previous mode has ended and several others remain, the state is not determined and the run
// stops (exit 3) naming the transistors (issue 10).
#pragma once

#include <string>
#include <vector>

#include "solver/lcp/lcp.h"
#include "solver/model/lcs_problem.h"

namespace lcs {

class MultistabilityNotes {
 public:
  // After lcp.solve(q) for the step ending at t. The solver's unknowns are `blocks` copies of
  // the pairs (Radau IIA's stages). Throws NumericalFailure when the status is NotUnique.
  void check(const LcpWarmSolver& lcp, const LcsProblem& model, double t, int blocks = 1);
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  bool said_ = false;
  std::vector<std::string> notes_;
};

// "transistors q1 and q2" for the owners of the given pairs ("q1:be" belongs to q1).
std::string pair_owners(const LcsProblem& model, const std::vector<int>& pairs);

}  // namespace lcs
