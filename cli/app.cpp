#include "cli/app.h"

#include <iostream>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "netlist/number.h"
#include "solver/model/dense_budget.h"
#include "solver/integrators/method_registry.h"

namespace lcs {

namespace {

// A numeric option that reads SPICE numbers (20u, 1.5meg, 1e-6).
CLI::Option* add_number(CLI::App* cmd, const std::string& name, std::optional<double>& target,
                        const std::string& help) {
  return cmd->add_option_function<std::string>(
      name,
      [&target, name](const std::string& text) {
        const std::optional<double> v = parse::parse_number(text);
        if (!v) throw CLI::ValidationError(name, "'" + text + "' is not a finite number");
        target = *v;
      },
      help);
}

// The same for an option with a default value.
CLI::Option* add_number(CLI::App* cmd, const std::string& name, double& target, const std::string& help) {
  return cmd->add_option_function<std::string>(
      name,
      [&target, name](const std::string& text) {
        const std::optional<double> v = parse::parse_number(text);
        if (!v) throw CLI::ValidationError(name, "'" + text + "' is not a finite number");
        target = *v;
      },
      help);
}

}  // namespace

int run_cli(int argc, char** argv) {
  CLI::App app{"lcspice: circuits of ideal diodes as linear complementarity systems"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "lcspice 0.1.0");

  RunArgs run;
  CLI::App* run_cmd = app.add_subcommand("run", "transient simulation; writes waveform CSV");
  run_cmd->add_option("netlist", run.netlist, "netlist file")->required();
  run_cmd->add_option("-o", run.output, "CSV path ('-' or absent: standard output)");
  run_cmd->add_option("--method", run.method, "integration method: " + method_names());
  add_number(run_cmd, "--theta", run.theta, "theta of --method theta (default 0.5)");
  add_number(run_cmd, "--step", run.step, "fixed step (default: the .tran TSTEP)");
  add_number(run_cmd, "--tstop", run.tstop, "overrides the .tran TSTOP");
  run_cmd->add_option("--probe", run.probes, "comma-separated probes, overrides .print/.save");
  add_number(run_cmd, "--rtol", run.rtol, "relative tolerance of event (event times) and smooth");
  add_number(run_cmd, "--atol", run.atol, "absolute tolerance of smooth (SUNDIALS weighted norm)");
  add_number(run_cmd, "--emission", run.emission,
             "smooth: emission coefficient N of the diodes standing in for ideal ones (default 0.05)");
  run_cmd->add_option("--diode", run.diode,
                      "diode model: ideal (complementarity with VON/RON; every method but smooth), "
                      "shockley (smooth diodes, --method smooth), auto (ideal where the fit to the circuit's "
                      "currents serves it, else the smooth method with Shockley diodes)");
  run_cmd->add_flag("--stats", run.stats, "print a run summary to standard error");
  run_cmd->add_flag("--euler-at-switching", run.euler_at_switching,
                    "theta: check each stiff step whose mode changes against implicit Euler's and take Euler's "
                    "where it ends in another mode or the two diverge (cures overshoots a diode holds; README)");

  OpArgs op;
  CLI::App* op_cmd = app.add_subcommand("op", "DC operating point at t = 0");
  op_cmd->add_option("netlist", op.netlist, "netlist file")->required();
  op_cmd->add_flag("--all", op.all, "every solution of the static complementarity problem");

  AnalyzeArgs analyze;
  CLI::App* analyze_cmd =
      app.add_subcommand("analyze", "spanning tree, loops, diode classes, LCS dimensions and index");
  analyze_cmd->add_option("netlist", analyze.netlist, "netlist file")->required();
  analyze_cmd->add_flag("--json", analyze.json, "machine-readable report");

  ValidateArgs validate;
  CLI::App* validate_cmd = app.add_subcommand(
      "validate", "run the circuit in ngspice (Shockley diodes) too and compare every probe");
  validate_cmd->add_option("netlist", validate.netlist, "netlist file")->required();
  add_number(validate_cmd, "--tol", validate.tol, "tolerance on max|error|/range per probe (default 0.02)");
  validate_cmd->add_option("--report", validate.report,
                           "write the table as CSV here, and per-probe PNG overlays beside it");
  validate_cmd->add_flag("--print-deck", validate.print_deck, "print the ngspice deck and stop");
  validate_cmd->add_flag("--converge", validate.converge,
                         "run ngspice again at N/2, N/4, N/8 and report the rate the disagreement shrinks");
  add_number(validate_cmd, "--emission", validate.emission,
                           "emission coefficient N of the Shockley diodes (default 0.05)");
  add_number(validate_cmd, "--max-step", validate.max_step,
                           "ngspice's maximum step (default: the output interval, at most TSTEP)");
  validate_cmd->add_option("--method", validate.method, "lcspice method: " + method_names());
  add_number(validate_cmd, "--step", validate.step, "lcspice step (default TSTEP/10)");
  validate_cmd->add_option("--probe", validate.probes, "comma-separated probes, overrides .print/.save");
  add_number(validate_cmd, "--timeout", validate.timeout, "seconds of wall time for ngspice (default 600)");
  validate_cmd->add_option("--ngspice-option", validate.ngspice_options,
                           "an .options word for the ngspice deck (repeatable), e.g. rshunt=1e9");

  BenchArgs bench;
  CLI::App* bench_cmd = app.add_subcommand(
      "bench", "work-precision study: every method and ngspice at several steps/tolerances; CSV + PNG per circuit");
  bench_cmd->add_option("netlists", bench.netlists, "netlists (default: the suite in circuits/bench_suite.tsv)");
  bench_cmd->add_option("-o", bench.output_dir, "output directory (default bench-results)");
  bench_cmd->add_flag("--quick", bench.quick, "two settings per method, one ngspice run: seconds, for tests");
  bench_cmd->add_flag("--no-ngspice", bench.no_ngspice, "leave ngspice out");
  bench_cmd->add_flag("--no-smooth-reference", bench.no_smooth_reference,
                      "no smooth (Shockley) reference: ngspice against the event reference only, smooth not run "
                      "(the reference's rtol 1e-10 run can take longer than the rest)");
  bench_cmd->add_option("--reference", bench.reference,
                        "the ideal circuit's reference: event (default; rtol 1e-13, checked at 1e-14 with TSTEP/2) "
                        "or euler (implicit Euler at TSTEP/64, checked at TSTEP/128, read linearly between its "
                        "rows at ngspice's times: for circuits whose event reference takes too long)");
  bench_cmd->add_option("--method,--methods", bench.methods,
                        "comma-separated methods (default: all; --scaling and --scale: euler)");
  bench_cmd->add_option("--probe", bench.probes, "comma-separated probes for the netlists given");
  bench_cmd->add_option("--ngspice-option", bench.ngspice_options, "extra ngspice .options word (repeatable)");
  add_number(bench_cmd, "--ngspice-timeout", bench.ngspice_timeout, "seconds of wall time per ngspice run (default 300)");
  bench_cmd->add_flag("--scaling", bench.scaling,
                      "cost scaling instead: a fixed-step method (default euler) and ngspice at step h over "
                      "TSTOP, 2 TSTOP, 4 TSTOP, ...; CPU against steps, log-log slopes; <circuit>_scaling.csv/.png");
  add_number(bench_cmd, "--tstop", bench.tstop, "--scaling: the first run's TSTOP (default: the netlist's); "
             "--scale: every run's TSTOP (default: five source periods)");
  bench_cmd->add_option("--scaling-max", bench.scaling_max,
                        "--scaling: longest run / first run, a power of two (default: up to 64, at most ~4e4 steps)");
  bench_cmd->add_option("--scale", bench.scale,
                        "circuit-size study instead: generated circuits of one family (cw, ladder, rectifiers) at "
                        "growing N, CPU per simulated second and peak memory against diodes for the methods and "
                        "ngspice, each run in its own process; growth exponents; scale_<family>.csv/.png");
  bench_cmd->add_option("--sizes", bench.sizes,
                        "--scale: comma-separated, increasing N: stages (cw, 2N diodes), sections (ladder) or "
                        "rectifiers (default: 10 to 1000 diodes)");
  add_number(bench_cmd, "--run-timeout", bench.run_timeout,
             "--scale: wall-clock seconds per run; a run killed at the limit ends its series (default 120)");
  bench_cmd->add_option("--fit-from", bench.fit_from,
                        "--scale: fit the growth exponents over runs with at least this many diodes (default 100)");

  PlotArgs plot;
  CLI::App* plot_cmd = app.add_subcommand("plot", "plot a waveform CSV against time (PNG, gnuplot)");
  plot_cmd->add_option("csv", plot.csv, "waveform CSV")->required();
  plot_cmd->add_option("-o", plot.output, "PNG path (default: the CSV path with .png)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitUsage;
  }

  try {
    if (run_cmd->parsed()) return run_command(run);
    if (op_cmd->parsed()) return op_command(op);
    if (analyze_cmd->parsed()) return analyze_command(analyze);
    if (plot_cmd->parsed()) return plot_command(plot);
    if (bench_cmd->parsed()) return bench_command(bench);
    if (validate_cmd->parsed()) return validate_command(validate);
  } catch (const CliError& e) {
    std::cerr << e.what() << "\n";
    return e.code();
  } catch (const DenseBudgetExceeded& e) {
    std::cerr << "lcspice: error: " << e.what() << " (methods euler and theta step on the sparse circuit)\n";
    return kExitNumerical;
  } catch (const std::exception& e) {
    std::cerr << "lcspice: internal error: " << e.what() << "\n";
    return kExitNumerical;
  }
  return kExitUsage;
}

}  // namespace lcs
