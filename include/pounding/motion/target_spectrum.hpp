#pragma once
// The target of a record selection as the user states it -- the code and its parameters -- and what
// `pounding records select` and a study's [target_spectrum] share around select_records (selection.hpp):
// building the DesignSpectrum (MCER x 1.5, EC8 at the selection's damping), the default scaling rule of each
// code, the default period range, and the printed summary of a Selection.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "pounding/core/enum_names.hpp"
#include "pounding/motion/asce7_site.hpp"
#include "pounding/motion/design_spectrum.hpp"
#include "pounding/motion/selection.hpp"

namespace pounding {

enum class TargetCode : std::uint8_t { asce7_16, ec8, iran2800, csv };
inline constexpr EnumName<TargetCode> target_code_names[] = {{TargetCode::asce7_16, "ASCE 7-16"},
                                                             {TargetCode::ec8, "EC8"},
                                                             {TargetCode::iran2800, "Standard 2800"},
                                                             {TargetCode::csv, "csv"}};
constexpr const auto& enum_names(TargetCode) { return target_code_names; }  // to_string(TargetCode)

struct TargetSpectrumSpec {
  TargetCode code = TargetCode::asce7_16;
  Asce7Spectrum asce7;      // the design spectrum's SDS, SD1 (g), TL (s)
  bool from_maps = false;   // ASCE: asce7 was computed from `maps` (asce7_from_maps, asce7_site.hpp)
  Asce7MapValues maps;      // ASCE from the maps: Ss, S1, site class, TL
  bool mcer = false;        // ASCE: the MCER spectrum, 1.5 x the design spectrum (ASCE 7-16 16.2 scales to it)
  Ec8Spectrum ec8;          // its damping_percent is replaced by the selection's damping
  Iran2800Spectrum iran2800;
  TabulatedSpectrum table;  // csv: the points, already read (read_tabulated_spectrum)
};

// The spectrum the records are scaled to; `damping` is the damping ratio of the record spectra (EC8's eta).
// Throws the InputError of the parameters' validate() (design_spectrum.hpp), naming the parameter.
DesignSpectrum make_target_spectrum(const TargetSpectrumSpec& spec, double damping);
// describe() of the target, with "MCER, 1.5 x the design spectrum (...): " in front for mcer.
std::string describe_target(const TargetSpectrumSpec& spec, const DesignSpectrum& target);
// EC8 for an EC8 target, ASCE 7-16 for the others.
ScalingRule default_scaling_rule(TargetCode code);
// The default period range as multiples {lo, hi} of the period(s): {0.2, 1.5} for ASCE 7-10 (16.1.3.1),
// {0.2, 2.0} otherwise (ASCE 7-16 16.2.3, EC8 3.2.3.1.2). The range is [lo min(T), hi max(T)].
std::array<double, 2> default_range_multiples(ScalingRule rule);

// The summary `records select` prints and a study's run log says, one string per line: target, rule, periods,
// candidates, one row per chosen record (rank, id, f_i, MSE, scale, event (year), station, component, source),
// the rules and every record passed over ("  refused <id>: <why>"), suite factor, the smallest mean/target ratio,
// whether the condition holds, then " WARNING: ..." lines. ids/sources: per candidate.
std::vector<std::string> selection_summary(const Selection& s, std::span<const std::string> ids,
                                           std::span<const std::string> sources, const std::string& target_text,
                                           const SelectionOptions& options);

}  // namespace pounding
