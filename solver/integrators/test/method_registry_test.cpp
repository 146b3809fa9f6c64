// The method registry: its shape and the traits the commands read instead of comparing names.
#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include "solver/integrators/method_registry.h"
#include "solver/integrators/transient.h"
#include "solver/model/dense_budget.h"
#include "solver/model/sparse_lcs.h"

namespace lcs {
namespace {

TEST(MethodRegistry, SortedUniqueAndOneFactoryEach) {
  const std::vector<MethodEntry>& table = method_registry();
  ASSERT_EQ(table.size(), 6u);
  std::set<std::string> names;
  for (size_t k = 0; k < table.size(); ++k) {
    const MethodEntry& e = table[k];
    if (k > 0) {
      EXPECT_LT(table[k - 1].name, e.name) << "sorted by name";
    }
    EXPECT_TRUE(names.insert(e.name).second) << e.name << " twice";
    EXPECT_NE(static_cast<bool>(e.make_stepper), static_cast<bool>(e.make_continuous))
        << e.name << ": exactly one of make_stepper and make_continuous";
    EXPECT_NE(e.adaptive(), e.fixed_step()) << e.name;
    EXPECT_FALSE(e.description.empty()) << e.name;
    // A fixed-step method is swept over steps; an adaptive one over tolerances.
    EXPECT_EQ(e.bench_sweep == BenchSweep::Tolerance, e.adaptive()) << e.name;
  }
  EXPECT_EQ(method_names(), "euler, event, radau3, radau5, smooth, theta");
}

TEST(MethodRegistry, TraitsOfEachMethod) {
  struct Expected {
    std::string name;
    bool adaptive, smooth_model, uses_theta, exact_reference, smooth_reference, is_default;
  };
  const std::vector<Expected> expected = {
      {"euler", false, false, false, false, false, false},
      {"event", true, false, false, true, false, true},
      {"radau3", false, false, false, false, false, false},
      {"radau5", false, false, false, false, false, false},
      {"smooth", true, true, false, false, true, false},
      {"theta", false, false, true, false, false, false},
  };
  for (const Expected& x : expected) {
    const MethodEntry* e = find_method(x.name);
    ASSERT_NE(e, nullptr) << x.name;
    EXPECT_EQ(e->name, x.name);
    EXPECT_EQ(e->adaptive(), x.adaptive) << x.name;
    EXPECT_EQ(e->fixed_step(), !x.adaptive) << x.name;
    EXPECT_EQ(e->smooth_model, x.smooth_model) << x.name;
    EXPECT_EQ(e->uses_theta, x.uses_theta) << x.name;
    EXPECT_EQ(e->exact_reference, x.exact_reference) << x.name;
    EXPECT_EQ(e->smooth_reference, x.smooth_reference) << x.name;
    EXPECT_EQ(e->is_default, x.is_default) << x.name;
    EXPECT_EQ(e->large_circuit_steps, x.name == "euler" || x.name == "theta") << x.name;
    EXPECT_EQ(e->bench_sweep, x.adaptive ? BenchSweep::Tolerance : BenchSweep::StepSize) << x.name;
  }
}

TEST(MethodRegistry, ReferencesAndDefault) {
  EXPECT_EQ(exact_reference_method().name, "event");
  ASSERT_NE(smooth_reference_method(), nullptr);
  EXPECT_EQ(smooth_reference_method()->name, "smooth");
  EXPECT_EQ(default_method().name, "event");
  EXPECT_EQ(fixed_step_default_method().name, "euler");
  EXPECT_EQ(TransientOptions().method, "euler");
  EXPECT_EQ(&exact_reference_method(), find_method("event"));
}

// SPEC §1: event is the default wherever it applies; a circuit with more pairs than its dense
// exponentials serve gets the fixed-step default, with the reason.
TEST(MethodRegistry, DefaultForACircuitFallsBackOnlyAboveThePairLimit) {
  struct Sized : LcsProblem {
    explicit Sized(int pairs) {
      lcs_.D = Eigen::MatrixXd::Zero(pairs, pairs);
    }
  };
  std::string why;
  EXPECT_EQ(default_method_for(Sized(128), &why).name, "event");
  EXPECT_TRUE(why.empty()) << why;
  EXPECT_EQ(default_method_for(Sized(129), &why).name, "euler");
  EXPECT_EQ(why, "129 complementarity pairs, more than the 128 up to which the event method's dense "
                 "exponentials stay cheap");
  // The exponentials are of the states too: an RC line of 3000 sections with one clamp.
  struct WithStates : LcsProblem {
    WithStates(int states, int pairs) {
      lcs_.A = Eigen::MatrixXd::Zero(states, states);
      lcs_.D = Eigen::MatrixXd::Zero(pairs, pairs);
    }
  };
  why.clear();
  EXPECT_EQ(default_method_for(WithStates(156, 100), &why).name, "event");
  EXPECT_TRUE(why.empty()) << why;
  EXPECT_EQ(default_method_for(WithStates(300, 1), &why).name, "euler");
  EXPECT_EQ(why, "300 states and 1 pairs, more than the 256 up to which the event method's dense "
                 "exponentials stay cheap");
}

// dense_budget.h: a circuit whose dense LCS (n + m)^2 doubles would exceed the budget is never
// formed dense. 6000 states and 6000 pairs: 1.07 GB a matrix, over the 1 GB budget itself; 4000
// and 4000: 488 MB, within it for one matrix but not for event's three or Radau's five.
TEST(MethodRegistry, DenseMethodsRefuseACircuitOverTheDenseBudget) {
  struct Deferred : LcsProblem {
    Deferred(int n, int m, bool stepping_sparse) {
      auto s = std::make_shared<SparseLcs>();
      s->A.resize(n, n);
      s->B.resize(n, m);
      s->C.resize(m, n);
      s->D.resize(m, m);
      s->E = Eigen::MatrixXd::Zero(n, 1);
      s->F = Eigen::MatrixXd::Zero(m, 1);
      if (stepping_sparse) sparse_lcs_ = s;
      defer_dense(s);
    }
  };
  const Deferred huge(6000, 6000, false);
  EXPECT_EQ(huge.state_count(), 6000);
  try {
    (void)huge.lcs();
    ADD_FAILURE() << "formed a 1.07 GB dense LCS";
  } catch (const DenseBudgetExceeded& e) {
    EXPECT_STREQ(e.what(), "the dense LCS of 6000 states and 6000 pairs (1.1 GB a matrix) is over the 1.0 GB "
                           "budget for dense matrices");
  }
  const Deferred large(4000, 4000, false), large_sparse(4000, 4000, true);
  std::string why;
  EXPECT_FALSE(find_method("event")->applies(large, &why));
  EXPECT_EQ(why, "the dense LCS of 4000 states and 4000 pairs (488 MB a matrix, 3 of them: 1.4 GB) is over the "
                 "1.0 GB budget for dense matrices; methods euler and theta step on the sparse circuit");
  EXPECT_FALSE(find_method("radau3")->applies(large, nullptr));
  EXPECT_FALSE(find_method("smooth")->applies(large, nullptr));
  EXPECT_FALSE(find_method("euler")->applies(large, &why));  // no sparse form: its dense step
  EXPECT_EQ(why, "the dense LCS of 4000 states and 4000 pairs (488 MB a matrix, 4 of them: 1.9 GB) is over the "
                 "1.0 GB budget for dense matrices");
  EXPECT_TRUE(find_method("euler")->applies(large_sparse, nullptr));
  EXPECT_TRUE(find_method("theta")->applies(large_sparse, nullptr));
  EXPECT_FALSE(find_method("event")->applies(large_sparse, nullptr));
  EXPECT_TRUE(find_method("smooth")->applies(large_sparse, nullptr));  // IDA with KLU on the sparse LCS
  EXPECT_EQ(default_method_for(large_sparse, &why).name, "euler");
  const Deferred within(1000, 1000, false);
  for (const MethodEntry& e : method_registry()) EXPECT_TRUE(e.applies(within, nullptr)) << e.name;
}

TEST(MethodRegistry, UnknownNames) {
  EXPECT_EQ(find_method("rk4"), nullptr);
  EXPECT_EQ(find_method(""), nullptr);
  EXPECT_EQ(find_method("Euler"), nullptr);  // names are exact
  EXPECT_EQ(find_method("trap"), nullptr);   // an ngspice name, only for `.options method=`
}

TEST(MethodRegistry, SpiceMethodNames) {
  const SpiceMethod euler = find_spice_method("euler");
  EXPECT_EQ(euler.entry, find_method("euler"));
  EXPECT_FALSE(euler.theta);
  EXPECT_FALSE(euler.gear);
  for (const std::string trap : {"trap", "trapezoidal"}) {
    const SpiceMethod m = find_spice_method(trap);
    EXPECT_EQ(m.entry, find_method("theta")) << trap;
    ASSERT_TRUE(m.theta) << trap;
    EXPECT_EQ(*m.theta, 0.5) << trap;
    EXPECT_FALSE(m.gear) << trap;
  }
  const SpiceMethod gear = find_spice_method("gear");
  EXPECT_EQ(gear.entry, nullptr);
  EXPECT_TRUE(gear.gear);
  const SpiceMethod unknown = find_spice_method("rk4");
  EXPECT_EQ(unknown.entry, nullptr);
  EXPECT_FALSE(unknown.gear);
  EXPECT_EQ(spice_method_names(), "euler, event, radau3, radau5, smooth, theta, trap");
}

}  // namespace
}  // namespace lcs
