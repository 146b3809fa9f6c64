// `lcspice analyze`: the normal tree, fundamental loops, the pair type and C/R/L class of every
// diode (5.4.4), the components of H and the quotient G/H (5.4.6), the LCS dimensions and index.
#include <algorithm>
#include <optional>
#include <cstdio>
#include <sstream>

#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "cli/deck_transient.h"
#include "cli/load_circuit.h"
#include "cli/source_sampling.h"
#include "cli/uniqueness_report.h"
#include "graph/components.h"
#include "graph/diode_classes.h"
#include "solver/devices/device.h"
#include "solver/integrators/diode_refit.h"
#include "solver/integrators/fit_sensitivity.h"
#include "solver/model/netlist_options.h"
#include "solver/model/lcs_index.h"
#include "cli/ccp_report.h"

namespace lcs {

namespace {

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

// The range a fitted pair's line was fitted over and its worst error there (junction_fit.h).
std::string fit_text(const PairInfo& p) {
  char buf[200];
  std::snprintf(buf, sizeof buf, " over %.3g A to %.3g A (%s), worst error %.3g mV = %.3g %% of its voltage",
                p.fit_i1, p.fit_i2, p.circuit_fit ? "the currents it carries here" : ".options ifit",
                1e3 * p.fit_error, 100 * p.fit_error_fraction);
  return buf;
}

// A loop of more than kLoopTermsShown branches is shown by its ends (the text report of a
// 2500-stage multiplier, whose loops run down its capacitor chains, was 83 MB in full; --json
// keeps every term).
constexpr size_t kLoopTermsShown = 24;

std::string loop_text(const CircuitGraph& g, const std::vector<LoopTerm>& loop) {
  std::string s;
  const size_t end = kLoopTermsShown / 2;
  for (size_t k = 0; k < loop.size(); ++k) {
    if (loop.size() > kLoopTermsShown && k == end) {
      s += " ... (" + std::to_string(loop.size()) + " branches in all) ...";
      k = loop.size() - end;
    }
    const LoopTerm& t = loop[k];
    s += (s.empty() ? "" : " ") + std::string(t.sign > 0 ? "+" : "-") + g.branches[t.branch].name;
  }
  return s;
}

struct Report {
  const CircuitModel& model;
  NodePartition h;
  std::vector<DiodeClass> classes;
  LcsIndex index;
  std::vector<std::string> warnings;
  std::vector<UniquenessEntry> uniqueness;
  std::optional<CcpReport> ccp;  // circuits with lines
  std::vector<std::string> controlled;  // controlled sources and switches, one line each
  std::string refit;             // how the diodes were fitted to the circuit's currents, if they were
  std::optional<FitSensitivity> sensitivity;  // whether the answer depends on the curves below them
};

// E, F, G, H and S, W: what they are listed as (not warnings).
bool controlled_element(const Element& e) {
  switch (e.kind) {
    case ElementKind::Vcvs:
    case ElementKind::Vccs:
    case ElementKind::Cccs:
    case ElementKind::Ccvs:
    case ElementKind::VSwitch:
    case ElementKind::CSwitch: return true;
    default: return false;
  }
}

std::string verdict_text(const PMatrixReport& p) {
  switch (p.verdict) {
    case PMatrixReport::Verdict::P: return "a P-matrix";
    case PMatrixReport::Verdict::NotP: return "not a P-matrix";
    case PMatrixReport::Verdict::Unchecked: return "not checked (too many pairs)";
  }
  return "";
}

void print_ccp(const CircuitModel& m, const CcpReport& c) {
  std::printf("\nconvolution complementarity problem (lines, Stewart 4.6, 5.3):\n");
  std::printf("  w(t) = M0 z(t) + (m * z)(t) + q(t); the lines' paths enter m at their delays:");
  for (double d : c.delays) std::printf(" %s s", number(d).c_str());
  std::printf("\n");
  for (const std::shared_ptr<Device>& d : m.devices())
    if (d->has_history())
      for (const std::string& note : d->notes()) std::printf("  %s\n", note.c_str());
  if (m.pairs().empty()) {
    std::printf("  no complementarity pairs: a linear delay system\n");
    return;
  }
  std::ostringstream a, b;
  a << c.m0.format(Eigen::IOFormat(6, 0, " ", "\n", "    [", "]"));
  b << c.m1.format(Eigen::IOFormat(6, 0, " ", "\n", "    [", "]"));
  std::printf("  M0 = D (%s):\n%s\n", verdict_text(c.m0_report).c_str(), a.str().c_str());
  std::printf("  m(0+) = CB (%s):\n%s\n", verdict_text(c.m1_report).c_str(), b.str().c_str());
  if (c.index == 0)
    std::printf("  index 0: M0 is a P-matrix, a unique solution exists (4.6.1)\n");
  else if (c.index == 1)
    std::printf("  index 1: M0 vanishes on the pairs and m(0+) is a P-matrix (Theorem 5.6)\n");
  else if (c.index > 1)
    std::printf("  index %d: pairs of mixed index (see the LCS index above)\n", c.index);
  else
    std::printf("  index: undefined\n");
}

std::string class_of(const Report& r, int branch) {
  for (const DiodeClass& c : r.classes)
    if (c.branch == branch) return std::string(1, c.cls);
  return "?";
}

bool joins(const Report& r, int branch) {
  for (const DiodeClass& c : r.classes)
    if (c.branch == branch) return c.joins_h_components;
  return false;
}

void print_text(const Report& r) {
  const CircuitModel& m = r.model;
  const CircuitGraph& g = m.graph();
  const SpanningTree& t = m.tree();
  std::printf("circuit: %s\n", m.netlist().title.c_str());
  std::printf("nodes: %zu (ground 0), branches: %zu\n\n", g.nodes.size(), g.branches.size());
  std::printf("normal tree (Kruskal, V < C < R < D < L < I), %zu branches:\n", t.tree.size());
  for (int b : t.tree)
    std::printf("  %-10s %s  %s -> %s\n", g.branches[b].name.c_str(), branch_class_name(g.branches[b].cls),
                g.nodes[g.branches[b].from].c_str(), g.nodes[g.branches[b].to].c_str());
  std::printf("\nlinks and their fundamental loops (5.34), %zu:\n", t.links.size());
  for (size_t j = 0; j < t.links.size(); ++j)
    std::printf("  %-10s %s  loop: %s\n", g.branches[t.links[j]].name.c_str(),
                branch_class_name(g.branches[t.links[j]].cls), loop_text(g, fundamental_loop(g, t, t.links[j])).c_str());

  std::printf("\nH (circuit without diodes and current sources): %d component%s\n", r.h.count,
              r.h.count == 1 ? "" : "s");
  for (int c = 0; c < r.h.count && r.h.count > 1; ++c) {
    std::string nodes;
    for (size_t n = 0; n < g.nodes.size(); ++n)
      if (r.h.component[n] == c) nodes += (nodes.empty() ? "" : ", ") + g.nodes[n];
    std::printf("  H%d: {%s}\n", c + 1, nodes.c_str());
  }
  if (r.h.count > 1) {
    std::string tree_diodes;
    for (int b : t.tree)
      if (g.branches[b].cls == BranchClass::Diode && joins(r, b)) tree_diodes += (tree_diodes.empty() ? "" : ", ") + g.branches[b].name;
    std::printf("  quotient G/H: %d nodes; tree diodes spanning it (5.4.6): %s\n", r.h.count,
                tree_diodes.c_str());
  }

  std::printf("\ndiodes (%zu):\n", m.pairs().size());
  std::printf("  %-10s %-8s %-5s %-14s %s\n", "name", "pair", "class", "index (Gk_ii)", "law");
  std::printf("  (index: first k with a nonzero diagonal entry of the Markov parameter G_k; '-': none,\n"
              "   the pair's own z never moves its w: it is tied to the others by KCL or KVL)\n");
  for (size_t k = 0; k < m.pairs().size(); ++k) {
    const PairInfo& p = m.pairs()[k];
    std::string law = "VON=" + number(p.law.von) + " V RON=" + number(p.law.ron) + " ohm";
    const bool breakdown = p.name.size() > 3 && p.name.compare(p.name.size() - 3, 3, ":bv") == 0;
    if (p.fitted) law += std::string(breakdown ? " (fitted to breakdown BV/IBV/N/RS" : " (fitted to Shockley IS/N/RS") + fit_text(p) + ")";
    const int pk = r.index.pair_index[k];
    std::printf("  %-10s %-8s %-5s %-14s %s%s\n", g.branches[p.branch].name.c_str(),
                p.voltage_type ? "voltage" : "current", class_of(r, p.branch).c_str(),
                pk >= 0 ? std::to_string(pk).c_str() : "-", law.c_str(),
                joins(r, p.branch) ? "  [joins H components]" : "");
  }

  if (!r.refit.empty())
    std::printf("  fitted over the currents each diode carries in the .tran run: %s\n", r.refit.c_str());
  if (r.sensitivity)
    std::printf("  the lines %s this circuit: %s\n", r.sensitivity->exceeds({}) ? "do not serve" : "serve",
                r.sensitivity->Describe({}).c_str());

  std::printf("\nLCS: dx/dt = A x + B z + E u,  w = C x + D z + F u,  0 <= w _|_ z >= 0\n");
  std::printf("  states n = %d:", m.state_count());
  for (const StateInfo& st : m.states()) std::printf(" %s", st.label.c_str());
  std::printf("\n  pairs m = %d, inputs = %d (u0 = 1 carries VON)", m.pair_count(), m.input_count());
  for (int k = 1; k < m.inputs().size(); ++k) std::printf(", %s", m.inputs()[k].label.c_str());
  std::printf("\n");
  if (m.gamma().size() > 0 && m.gamma().cwiseAbs().maxCoeff() > 0)
    std::printf("  state shift: x = x_phys - Gamma u (capacitor/source loops or inductor/source cutsets)\n");
  if (r.index.markov.empty() && m.pair_count() > kPrintedMarkovPairs)
    std::printf("  Markov parameters D, CB, CAB: not printed above %d pairs\n", kPrintedMarkovPairs);
  const char* names[] = {"D", "CB", "CAB"};
  for (size_t k = 0; k < r.index.markov.size(); ++k) {
    std::ostringstream os;
    os << r.index.markov[k].format(Eigen::IOFormat(6, 0, " ", "\n", "    [", "]"));
    std::printf("  Markov parameter %s:\n%s\n", names[k], os.str().c_str());
  }
  if (!r.index.not_computed.empty()) std::printf("  index: not computed (%s)\n", r.index.not_computed.c_str());
  else if (r.index.index >= 0) std::printf("  index: %d\n", r.index.index);
  else std::printf("  index: undefined (G(s) singular for large s)\n");
  std::printf("\nuniqueness (LCP(q, M) has one solution for every q iff M is a P-matrix, 2.2):\n");
  for (const UniquenessEntry& e : r.uniqueness)
    std::printf("  %s, m = %d: %s\n", e.what.c_str(), e.size, e.verdict().c_str());
  if (r.ccp) print_ccp(m, *r.ccp);
  if (!r.controlled.empty()) {
    std::printf("\ncontrolled sources and switches (switches: the configuration at t = 0):\n");
    for (const std::string& c : r.controlled) std::printf("  %s\n", c.c_str());
  }
  for (const std::string& w : r.warnings) std::printf("warning: %s\n", w.c_str());
}

void print_json(const Report& r) {
  const CircuitModel& m = r.model;
  const CircuitGraph& g = m.graph();
  const SpanningTree& t = m.tree();
  std::ostringstream o;
  o << "{\n  \"title\": " << json_string(m.netlist().title) << ",\n  \"nodes\": [";
  for (size_t n = 0; n < g.nodes.size(); ++n) o << (n ? ", " : "") << json_string(g.nodes[n]);
  o << "],\n  \"tree\": [";
  for (size_t k = 0; k < t.tree.size(); ++k) o << (k ? ", " : "") << json_string(g.branches[t.tree[k]].name);
  o << "],\n  \"links\": [";
  for (size_t j = 0; j < t.links.size(); ++j) {
    o << (j ? ",\n" : "\n") << "    {\"name\": " << json_string(g.branches[t.links[j]].name) << ", \"loop\": [";
    const std::vector<LoopTerm> loop = fundamental_loop(g, t, t.links[j]);
    for (size_t k = 0; k < loop.size(); ++k)
      o << (k ? ", " : "") << "{\"branch\": " << json_string(g.branches[loop[k].branch].name)
        << ", \"sign\": " << loop[k].sign << "}";
    o << "]}";
  }
  o << "\n  ],\n  \"h_components\": " << r.h.count << ",\n  \"diodes\": [";
  for (size_t k = 0; k < m.pairs().size(); ++k) {
    const PairInfo& p = m.pairs()[k];
    o << (k ? ",\n" : "\n") << "    {\"name\": " << json_string(g.branches[p.branch].name)
      << ", \"pair\": " << json_string(p.voltage_type ? "voltage" : "current")
      << ", \"class\": " << json_string(class_of(r, p.branch)) << ", \"index\": " << r.index.pair_index[k]
      << ", \"von\": " << number(p.law.von) << ", \"ron\": " << number(p.law.ron)
      << ", \"fitted\": " << (p.fitted ? "true" : "false")
      << ", \"fit_range\": [" << number(p.fit_i1) << ", " << number(p.fit_i2) << "]"
      << ", \"fit_error_mv\": " << number(1e3 * p.fit_error)
      << ", \"fit_error_fraction\": " << number(p.fit_error_fraction)
      << ", \"circuit_fit\": " << (p.circuit_fit ? "true" : "false")
      << ", \"joins_h_components\": " << (joins(r, p.branch) ? "true" : "false") << "}";
  }
  o << "\n  ],\n  \"lcs\": {\"states\": " << m.state_count() << ", \"pairs\": " << m.pair_count()
    << ", \"inputs\": " << m.input_count() << ", \"index\": " << r.index.index << ", \"state_labels\": [";
  for (size_t k = 0; k < m.states().size(); ++k) o << (k ? ", " : "") << json_string(m.states()[k].label);
  o << "]";
  if (!r.index.not_computed.empty()) o << ", \"index_not_computed\": " << json_string(r.index.not_computed);
  o << "},\n  \"uniqueness\": [";
  for (size_t k = 0; k < r.uniqueness.size(); ++k) {
    const UniquenessEntry& e = r.uniqueness[k];
    o << (k ? ",\n" : "\n") << "    {\"matrix\": " << json_string(e.what) << ", \"verdict\": "
      << json_string(e.json_verdict()) << ", \"failing_pairs\": [";
    for (size_t j = 0; j < e.failing_pairs.size(); ++j) o << (j ? ", " : "") << json_string(e.failing_pairs[j]);
    o << "]}";
  }
  o << "\n  ],\n";
  if (r.ccp) {
    o << "  \"ccp\": {\"delays\": [";
    for (size_t k = 0; k < r.ccp->delays.size(); ++k) o << (k ? ", " : "") << number(r.ccp->delays[k]);
    o << "], \"m0_p_matrix\": " << (r.ccp->m0_report.verdict == PMatrixReport::Verdict::P ? "true" : "false")
      << ", \"m1_p_matrix\": " << (r.ccp->m1_report.verdict == PMatrixReport::Verdict::P ? "true" : "false")
      << ", \"index\": " << r.ccp->index << "},\n";
  }
  if (r.sensitivity) {
    const FitSensitivity& s = *r.sensitivity;
    o << "  \"fit_sensitivity\": {\"probe\": " << json_string(s.probe) << ", \"moved\": " << number(s.moved)
      << ", \"bound\": " << number(FitSensitivityOptions{}.bound) << ", \"decades\": "
      << number(FitSensitivityOptions{}.decades) << ", \"failure\": " << json_string(s.failure)
      << ", \"lines_serve\": " << (s.exceeds({}) ? "false" : "true") << "},\n";
  }
  o << "  \"controlled\": [";
  for (size_t k = 0; k < r.controlled.size(); ++k) o << (k ? ", " : "") << json_string(r.controlled[k]);
  o << "],\n";
  o << "  \"warnings\": [";
  for (size_t k = 0; k < r.warnings.size(); ++k) o << (k ? ", " : "") << json_string(r.warnings[k]);
  o << "]\n}\n";
  std::fputs(o.str().c_str(), stdout);
}

}  // namespace

int analyze_command(const AnalyzeArgs& args) {
  Netlist netlist = load_netlist(args.netlist);
  const double t1 = netlist.tran ? netlist.tran->tstop : 0.0;
  CircuitModel model = build_model(netlist, 0.0, t1);
  std::optional<DiodeRefitResult> refit;
  DiodeRefitOptions refit_options;
  const std::optional<TransientOptions> tran = deck_transient(netlist, model, refit_options);
  if (tran) {
    ModelOptions mo;
    mo.t1 = t1;
    refit = refit_diodes(netlist, mo, *tran, refit_options);
    if (refit->passes > 0) model = build_model(netlist, 0.0, t1, refit->ranges);
  }
  Report r{model, h_components(model.graph()), classify_diodes(model.graph()), lcs_index(model), {}, {}, {}, {}, {}, {}};
  for (const std::string& w : floating_potential_warnings(model)) r.warnings.push_back(w);
  if (!(netlist.tran && netlist.tran->uic))
    for (const std::string& w : dc_floating_start_warnings(model, netlist)) r.warnings.push_back(w);
  if (refit && refit->passes > 0) {
    r.refit = std::to_string(refit->passes) + " transient pass" + (refit->passes == 1 ? "" : "es") + ", " +
              (refit->converged ? "converged" : "not converged") +
              (refit->failure.empty() ? "" : " (" + refit->failure + ")");
    const std::string poor = poor_fit_message(model);
    if (!poor.empty()) r.warnings.push_back(poor);
    ModelOptions mo;
    mo.t1 = t1;
    mo.diode_ranges = refit->ranges;
    FitSensitivity s = fit_sensitivity(netlist, mo, *tran, probes_for(netlist, model, ""));
    if (!s.failure.empty() && refit_options.fallback)  // as run's check falls back
      s = fit_sensitivity(netlist, mo, *refit_options.fallback, probes_for(netlist, model, ""));
    if (s.measured) {
      r.sensitivity = s;
      if (s.exceeds({}))
        r.warnings.push_back("the ideal answer depends on the junctions' curves below the currents they carry (" +
                             s.Describe({}) + "): use --diode auto (the Shockley junctions), --diode shockley, "
                             "or give VON/RON on the cards");
    }
  }
  for (const std::shared_ptr<Device>& d : model.devices())
    if (!d->has_history())  // a line's notes are its part of the CCP section
      for (const std::string& note : d->notes())
        (controlled_element(d->element()) ? r.controlled : r.warnings).push_back(note);
  if (model.has_history()) {
    r.ccp = ccp_report(model);
    for (const std::string& w : r.ccp->warnings) r.warnings.push_back(w);
  }
  r.uniqueness = uniqueness_report(model, netlist.tran ? netlist.tran->tstep : 0.0);
  if (args.json) print_json(r);
  else print_text(r);
  return kExitOk;
}

}  // namespace lcs
