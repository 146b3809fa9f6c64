// D anode cathode model: one complementarity pair (Stewart 5.4). The card's parameters are
// resolved here, once, for every use: the ideal law of the LCS, the smooth junction of the
// smooth method (8.2) and the ngspice deck of `validate`.
#pragma once

#include "solver/devices/device.h"

namespace lcs {

struct ResolvedDiodeLaw {
  IdealDiodeLaw law;
  bool fitted = false;  // VON/RON came from the Shockley fit, not from the card
  bool circuit_fit = false;  // ... over the currents this circuit carried (diode_refit.h)
  double fit_i1 = 0, fit_i2 = 0;
  double fit_error = 0, fit_error_fraction = 0;  // the line's worst error over [fit_i1, fit_i2]
};

// A card with VON and/or RON uses them (a missing one is 0). A card with neither gets a line
// through its Shockley curve v(i) = N*Vt*ln(1 + i/IS) + RS*i (junction_fit.h):
//  - with no circuit range, the chord between i1 = ifit/10 and i2 = 10*ifit (ifit from
//    `.options ifit=`, default 10 mA), where a power circuit operates;
//  - over `range`, the currents the diode carried in this circuit, the least-max-error line.
ResolvedDiodeLaw resolve_diode_law(const DiodeModel& model, double ifit, const CurrentRange& range = {});

// The breakdown pair's law (the card has BV), the reverse pair at -BV (SPEC §2):
//  - a card with VON, RON or Rrev (an ideal or LTspice card): VON = BV, RON = Rrev, else RON
//    (LTspice's Rrev defaults to Ron);
//  - else a line through ngspice's breakdown curve v(i) = BV + N Vt ln(i/IBV) + RS i (the reverse
//    voltage at reverse current i), fitted as the forward curve is, over the same default
//    decade pair or over the reverse currents carried.
ResolvedDiodeLaw resolve_breakdown_law(const DiodeModel& model, double ifit, const CurrentRange& range = {});

// The pair of a junction with law `law` (its fit carried along for `analyze` and the warnings).
PairLaw junction_pair_law(const std::string& name, int element, const ResolvedDiodeLaw& law, SmoothJunction smooth);

// The range a junction's current was given (DeviceOptions::diode_ranges), or none.
CurrentRange junction_range(const DeviceOptions& options, const std::string& key, bool breakdown);

double shockley_voltage(const DiodeModel& model, double current);

// The smooth diode that stands in for an ideal one (ngspice decks in `validate`, and the smooth
// method): a source VON in series with a Shockley diode of emission coefficient `emission`,
// saturation current `saturation_current` and RS = RON. As the emission coefficient goes to 0 it
// tends to the ideal law; at current i it needs about N Vt ln(i/IS) more voltage. A card that
// gives its own IS, N or RS keeps them (and no series source): the user's smooth diode, against
// which lcspice's ideal law is compared.
// With BV the smooth diode has ngspice's breakdown branch, I = -IBV exp(-(V + BV) / (N Vt)) with
// V the whole branch's voltage (an ideal card's: IBV = the saturation current times BV / Vt,
// which ngspice would raise it to, so the witness breaks down as sharply as it conducts).
struct SmoothDiodeLaw {
  double series_von = 0;  // V, the threshold source in series
  double is = 1e-14, n = 1, rs = 0;
  std::optional<double> bv;
  double ibv = 1e-3;
  std::optional<double> nbv;  // the breakdown's emission coefficient (none: n)
};
SmoothDiodeLaw smooth_equivalent(const DiodeModel& card, const ResolvedDiodeLaw& law,
                                 double emission, double saturation_current);

// The ngspice cards of one ideal junction named `tag`:
//   anode --[meter: + VON -]-- mid --|>|-- cathode   (the Shockley diode of `smooth`)
// The threshold source doubles as the junction's ammeter; returns its name. `context.open` puts
// a 1e15 ohm resistor where the diode would be (a test hook of `validate`).
std::string ngspice_junction(const std::string& tag, const std::string& anode, const std::string& cathode,
                             const SmoothDiodeLaw& smooth, const NgspiceDeckContext& context,
                             NgspiceCards& cards);

class Diode : public Device {
 public:
  // Throws NetlistError (at the card) when its model is not defined.
  Diode(const Element& element, const Netlist& netlist, const DeviceOptions& options);
  std::vector<BranchDecl> branches() const override;
  void stamp(const StampContext& context, Stamps& stamps) const override;
  bool current_probed_by_default() const override { return true; }
  NgspiceCards ngspice(const NgspiceDeckContext& context) const override;
  std::vector<std::string> notes() const override;
  std::vector<FittedJunction> fitted_junctions() const override;

  std::vector<std::pair<int, double>> element_current() const override;

  const DiodeModel& card() const { return card_; }
  const ResolvedDiodeLaw& law() const { return law_; }
  // The breakdown pair's law, when the card has BV: a second branch cathode -> anode ("d1:bv").
  const std::optional<ResolvedDiodeLaw>& breakdown() const { return breakdown_; }
  // CJO times the area under `.options diodecap`: a capacitor branch across the junction
  // ("d1:cj") when positive.
  double capacitance() const { return capacitance_; }

 private:
  DiodeModel card_;
  ResolvedDiodeLaw law_;
  std::optional<ResolvedDiodeLaw> breakdown_;
  double capacitance_ = 0;
};

}  // namespace lcs
