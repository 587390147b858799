#pragma once
// One adjacent pair of an inventory written as a pair study (`pounding inventory pair`): the two designed buildings
// as shear buildings with lognormal uncertainty on period, strength and damping, records selected and scaled to the
// site's ASCE 7-16 design spectrum, the gap axis in metres with the measured gap marked. The same numbers a study
// over the whole inventory will use for this pair (issue 48).
//
// Per building (docs/inventory.md "A pair as a study"): model "shear", storeys and storey_height as inventoried,
// mass = the ELF's total mass, period lognormal about T (Cu Ta or measured) with dispersion beta_period,
// yield_coefficient lognormal about Vy,1 / W with beta_strength, zeta lognormal about 0.05 with beta_damping,
// stiffness_profile "shear" (k proportional to the inverted-triangle storey shears: the study's profile, which
// differs from the ELF's 12.8.3 profile only for T > 0.5 s, where k > 1), alpha of the system, ASCE 7-16 R, Cd, Ie.
// Dispersions are lognormal standard deviations beta; the study takes CoV = sqrt(exp(beta^2) - 1).
#include <string>

#include "pounding/inventory/inventory.hpp"

namespace pounding::inventory {

struct PairStudyOptions {
  double ss = 1.5, s1 = 0.6, tl = 8;  // the site's mapped MCER values (g) and TL (s)
  double beta_period = 0.25, beta_strength = 0.35, beta_damping = 0.4;  // FEMA P-58-style modelling dispersions
  int samples = 20;                  // structure samples per record
  int records = 11;                  // records selected to the spectrum (ASCE 7-16 16.2.2: at least 11)
  std::uint64_t seed = 1;
  bool mce = true;                   // records scaled to the MCER spectrum (1.5 x design, 16.2), else to the design one
  std::string output;                // the results file the study names; empty: "<a>--<b>.h5"
};

// The study text. The site class of the pair's spectrum is the softer of the two buildings' (the larger design
// values), said in a comment; InputError naming the building for a site the ELF refuses.
std::string pair_study_text(const Inventory& inv, const Adjacency& pair, const PairStudyOptions& options);

}  // namespace pounding::inventory
