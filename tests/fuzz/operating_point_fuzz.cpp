// libFuzzer target: netlist text -> parse -> model formation -> operating point (SPEC `op`).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "solver/model/circuit_model.h"
#include "solver/model/operating_point.h"
#include "tests/fuzz/fuzz_outcome.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > lcs::fuzz::kMaxInputBytes) return 0;
  const std::string text(reinterpret_cast<const char*>(data), size);
  lcs::fuzz::run_expecting_documented_errors([&] {
    // The name puts relative .include files in a directory that does not exist.
    const lcs::Netlist netlist = lcs::parse_netlist_string(text, "/nonexistent-fuzz-dir/deck.cir");
    if (netlist.elements.size() > lcs::fuzz::kMaxElements) return;
    lcs::ModelOptions options;
    options.t1 = netlist.tran ? netlist.tran->tstop : 0.0;
    const lcs::CircuitModel model = lcs::CircuitModel::build(netlist, options);
    const lcs::OperatingPoint op = lcs::solve_operating_point(model, 0.0);
    if (!op.x.allFinite() || !op.z.allFinite()) {
      std::fprintf(stderr, "fuzz finding: operating point is not finite\n");
      std::abort();
    }
  });
  return 0;
}
