// T p1+ p1- p2+ p2- Z0= TD=  (lossless)   and   O p1+ p1- p2+ p2- model  (LTRA, lossy)
//
// The method of characteristics (Stewart 1.3.3): with the port currents i_k flowing into the
// line at p_k+, a lossless line is, at each port, its characteristic impedance Z0 in series with
// a history source carrying the wave that left the other port TD earlier:
//   v1(t) - Z0 i1(t) = (v2 + Z0 i2)(t - TD),   v2(t) - Z0 i2(t) = (v1 + Z0 i1)(t - TD).
// Each port is one resistive branch; the two history sources are delayed inputs of the LCS.
//
// A lossy (Heaviside RLCG) line has, from (1.13), I1 = Yc V1 - H (Yc V2 + I2) with the
// characteristic admittance Yc(s) and the propagation function H(s) = e^{-s tau} (...). Both
// are fitted by sums of exponentials (line_kernel.h):
//   Yc(s) = 1/Z0 + sum_i a_i / (s - p_i),   H(s) e^{s tau} = d + sum_j c_j / (s - q_j),
// so every convolution is an ODE (4.6: the CCP's kernel m(t) = M0 delta + sums of exponentials):
//   port k:  v_k - Z0 i_k + Z0 sum_i a_i xi_ki - u_k = 0,            xi_ki' = p_i xi_ki + v_k
//   u_1(t) = [d (v2 + Z0 i2 + Z0 sum a xi_2) + sum_j c_j zeta_2j](t - tau),
//   zeta_2j' = q_j zeta_2j + (v2 + Z0 i2 + Z0 sum a xi_2)             (and 1 <-> 2).
// The xi and zeta are states of the LCS, each a unit capacitor at an internal node driven by a
// controlled current branch (the line as a circuit of primitives, like the transistor); only the
// pure delay tau is history. A pole pair p, conj(p) is one real 2x2 block of two such states.
#pragma once

#include <memory>

#include "solver/devices/device.h"
#include "solver/devices/line_kernel.h"

namespace lcs {

class TransmissionLine : public Device {
 public:
  TransmissionLine(const Element& element, const Netlist& netlist, const DeviceOptions& options);
  std::vector<BranchDecl> branches() const override;
  void stamp(const StampContext& context, Stamps& stamps) const override;
  std::vector<std::pair<int, double>> terminal_current(char terminal) const override;
  bool has_history() const override { return true; }
  double max_step() const override { return delay_; }
  NgspiceCards ngspice(const NgspiceDeckContext& context) const override;
  std::vector<std::string> notes() const override;

  double z0() const { return z0_; }
  double delay() const { return delay_; }
  bool lossy() const { return kernel_ != nullptr; }
  const LineKernel* kernel() const { return kernel_.get(); }

 private:
  // One real mode of a fitted rational function: a real pole (a state) or a conjugate pair
  // (two states, the real and imaginary parts of one complex one).
  struct Mode {
    double re = 0, im = 0;          // the pole
    double res_re = 0, res_im = 0;  // its residue
    bool pair = false;
  };
  static std::vector<Mode> modes_of(const RationalFit& fit);
  void check_delay(const DeviceOptions& options) const;
  std::string internal_node(const std::string& what, int k) const;

  double z0_ = 0, delay_ = 0;
  std::string model_;  // O: the LTRA card's name
  std::vector<std::string> ignored_;  // its parameters lcspice does not use
  std::shared_ptr<LineKernel> kernel_;  // O lines only
  std::vector<Mode> admittance_, propagation_;
};

}  // namespace lcs
