// The target of a record selection and the summary of a Selection (target_spectrum.hpp).
#include "pounding/motion/target_spectrum.hpp"

#include <fmt/format.h>

namespace pounding {

DesignSpectrum make_target_spectrum(const TargetSpectrumSpec& spec, double damping) {
  switch (spec.code) {
    case TargetCode::asce7_16: {
      const double k = spec.mcer ? 1.5 : 1.0;  // MCER = 1.5 x the design spectrum (research note 3.1)
      return DesignSpectrum(Asce7Spectrum{k * spec.asce7.sds, k * spec.asce7.sd1, spec.asce7.tl});
    }
    case TargetCode::ec8: {
      Ec8Spectrum s = spec.ec8;
      s.damping_percent = 100 * damping;  // the target at the damping of the record spectra
      return DesignSpectrum(s);
    }
    case TargetCode::iran2800: return DesignSpectrum(spec.iran2800);
    case TargetCode::csv: return DesignSpectrum(spec.table);
  }
  return DesignSpectrum(spec.table);
}

std::string describe_target(const TargetSpectrumSpec& spec, const DesignSpectrum& target) {
  const bool asce = spec.code == TargetCode::asce7_16;
  return (asce && spec.mcer ? "MCER, 1.5 x the design spectrum (SDS and SD1 below include the 1.5): " : "") +
         target.describe() + (asce && spec.from_maps ? " (from " + describe(spec.maps) + ")" : "");
}

ScalingRule default_scaling_rule(TargetCode code) {
  return code == TargetCode::ec8 ? ScalingRule::ec8 : ScalingRule::asce7_16;
}

std::array<double, 2> default_range_multiples(ScalingRule rule) {
  return rule == ScalingRule::asce7_10 ? std::array<double, 2>{0.2, 1.5} : std::array<double, 2>{0.2, 2.0};
}

std::vector<std::string> selection_summary(const Selection& s, std::span<const std::string> ids,
                                           std::span<const std::string> sources, const std::string& target_text,
                                           const SelectionOptions& so) {
  std::vector<std::string> out;
  out.push_back("target: " + target_text);
  out.push_back("rule: " + s.rule_text);
  out.push_back(fmt::format("periods: {} log-spaced over {:.3f}-{:.3f} s, damping {:g} %", so.points, so.t_lo,
                            so.t_hi, 100 * so.damping));
  out.push_back(fmt::format("candidates: {}, eligible (factor within [{:g}, {:g}]): {}, chosen: {}", ids.size(),
                            so.min_scale, so.max_scale, s.eligible, s.chosen.size()));
  out.push_back(fmt::format("{:>4} {:<44} {:>9} {:>9} {:>9}  {:<30} {:<32} {:<5} {}", "rank", "record", "f_i", "MSE",
                            "scale", "event", "station", "comp", "file"));
  for (std::size_t k = 0; k < s.chosen.size(); ++k) {
    const RecordIdentity& id = s.identity[k];
    out.push_back(fmt::format("{:>4} {:<44} {:>9.4f} {:>9.5f} {:>9.4f}  {:<30} {:<32} {:<5} {}", k + 1, ids[s.chosen[k]],
                              s.individual_scale[k], s.mse[k], s.scale[k], id.known() ? id.event_text() : "-",
                              id.known() ? id.station : "-", id.known() && !id.component.empty() ? id.component : "-",
                              sources[s.chosen[k]]));
  }
  out.push_back(fmt::format("rules: at most {} per event, components = {}; {} record{} passed over{}",
                            so.max_per_event == 0 ? std::string("any number") : std::to_string(so.max_per_event),
                            to_string(so.components), s.refused.size(), s.refused.size() == 1 ? "" : "s",
                            s.refused.empty() ? "" : ":"));
  for (const auto& r : s.refused) out.push_back(fmt::format("  refused {}: {}", ids[r.candidate], r.reason));
  if (s.unidentified > 0)
    out.push_back(fmt::format("  {} of {} candidates have no recorded event/station (synthetic, or a file without a "
                              "MANIFEST.tsv row or PEER header line): not checked for duplicates",
                              s.unidentified, ids.size()));
  out.push_back(fmt::format("suite factor F = {:.6f}", s.suite_factor));
  out.push_back(fmt::format("min mean/target over the range = {:.6f}{}", s.min_ratio,
                            so.rule == ScalingRule::ec8 ? fmt::format(" (mean PGA / ag S = {:.6f})", s.pga_ratio)
                                                        : std::string()));
  out.push_back(so.rule == ScalingRule::none ? std::string("condition: none (rule \"none\")")
                                             : fmt::format("condition holds: {}", s.meets ? "yes" : "no"));
  for (const auto& w : s.warnings) out.push_back(" WARNING: " + w);
  return out;
}

}  // namespace pounding
