#pragma once
// Modes of a shear stick, Rayleigh damping and stiffness profiles (issue 25 §2; docs/architecture.md §2.2.3
// "Bodies and damping", "Modes", "Stiffness and strength profiles"; formulas in
// ../shared/research/systems-and-bridges.md §1).
//
// A shear stick of n floors, bottom first: floor i has mass m[i] (kg), storey i (between floor i and the
// floor below it, floor -1 being the ground) has stiffness k[i] (N/m). M = diag(m), K tridiagonal with
// K_ii = k_i + k_{i+1} (k_n = 0), K_{i,i+1} = -k_{i+1}. The generalised problem K φ = ω² M φ becomes the
// symmetric tridiagonal A = M^{-1/2} K M^{-1/2}, solved by implicit QL with Wilkinson shifts (tqli); its
// unit eigenvectors z give the mass-normalised shapes φ = M^{-1/2} z.
//
// Symbols (systems-and-bridges.md §1): M_j = φ_jᵀMφ_j, L_j = φ_jᵀM1, Γ_j = L_j/M_j, M*_j = L_j²/M_j,
// Σ_j M*_j = Σ_i m_i.
//
// The model layer takes no user input: callers validate (the command line, the study), and these functions
// refuse what they were not meant to get with std::invalid_argument (a programming error);
// stick_defect() says beforehand what is wrong, without throwing.
#include <span>
#include <string>
#include <vector>

#include "pounding/core/enum_names.hpp"

namespace pounding::model {

struct Modes {
  std::vector<double> omega;   // ω_j, rad/s, ascending
  std::vector<double> period;  // T_j = 2π/ω_j, s
  // phi[j][i]: mode j at floor i (bottom first), MASS-NORMALISED (φ_jᵀ M φ_j = 1, units kg^-1/2), signed so
  // that the roof value is positive (it is never zero in exact arithmetic: the end components of an
  // eigenvector of an unreduced tridiagonal matrix are non-zero); for a mode confined below the roof (see
  // phi_roof) the largest value is positive instead.
  std::vector<std::vector<double>> phi;
  // The same shapes scaled to a roof value of 1, for printing: roof_normalised[j]. A mode confined below the
  // roof (roof value < 1e-6 of its largest, as high modes of irregular sticks are: disorder localises them)
  // is scaled to a largest |value| of 1 instead (roof_normalised[j] false), so no printed value is huge.
  std::vector<std::vector<double>> phi_roof;
  std::vector<bool> roof_normalised;
  std::vector<double> gamma;       // Γ_j of the mass-normalised φ_j (= L_j, kg^1/2)
  std::vector<double> gamma_roof;  // Γ_j of phi_roof[j]: with roof = 1, the roof-displacement participation
  std::vector<double> meff;        // M*_j = L_j²/M_j, kg (independent of the normalisation)
  std::vector<double> meff_ratio;  // M*_j / Σ m
};

// "" when (m, k) is a stick these functions take, else the first reason it is not: empty, sizes differ, a
// value not finite or not > 0, or a stiffness/mass spread beyond 1e12 (the eigenvalues would lose their
// digits). Names the floor or storey from 1 ("floor 3", "storey 2").
std::string stick_defect(std::span<const double> m, std::span<const double> k);

// All n modes of the stick, ascending ω. Throws std::invalid_argument when stick_defect() is not empty.
Modes shear_stick_modes(std::span<const double> m, std::span<const double> k);

// Rayleigh damping C = a0 M + a1 K0 with ratio zeta_i at omega_i and zeta_j at omega_j (Chopra,
// "Classical damping matrices"): a0 = 2ω_iω_j(ζ_iω_j − ζ_jω_i)/(ω_j² − ω_i²), a1 = 2(ζ_jω_j − ζ_iω_i)/(ω_j² − ω_i²).
// Throws std::invalid_argument unless 0 < ω_i < ω_j (finite) and the ratios are finite.
struct Rayleigh {
  double a0, a1;  // 1/s, s
};
Rayleigh rayleigh(double omega_i, double zeta_i, double omega_j, double zeta_j);
// The ratio every mode gets: ζ(ω) = a0/(2ω) + a1 ω/2.
double rayleigh_ratio(const Rayleigh& r, double omega);

// The two modes Rayleigh damping takes in a stick of n storeys when modes i < j were asked for (a study's
// rayleigh_modes, where the storey count varies from sample to sample): j' = min(j, n), i' = min(i, j' - 1) -- the
// modes asked for when the building has them, else the highest two it has (n >= 2; e.g. [1, 3] gives 1 and 2 in a
// two-storey building, [3, 5] gives 3 and 4 in four storeys). n = 1: {1, 1} -- one mode, damped by c = 2 zeta
// sqrt(k m), the SDOF's. Throws std::invalid_argument unless 1 <= i < j and n >= 1.
struct ModePair {
  int i, j;
};
ModePair rayleigh_modes_for(int i, int j, int n);

// Classical (modal) damping C = M Φ diag(2 ζ_j ω_j / M_j) Φᵀ M over all n modes (systems-and-bridges.md §1;
// DampingForm::dense of model/system.hpp): row-major n x n, N s/m. zeta: per mode from mode 1, the last value
// repeating for the higher modes (the study's `damping = {modal = {zeta = [...]}}`). Throws
// std::invalid_argument for an empty or non-finite zeta, or modes not of these masses.
std::vector<double> modal_damping_matrix(std::span<const double> m, const Modes& modes, std::span<const double> zeta);
// The ratio of mode j (0-based) under that rule.
double modal_ratio(std::span<const double> zeta, std::size_t j);

// Storey-stiffness shapes (architecture.md §2.2.3): `uniform` k_i = const; `shear` k_i ∝ V_i = Σ_{j>=i} m_j z_j,
// the storey shear of the inverted-triangle equivalent lateral forces F_j ∝ m_j z_j (EN 1998-1 §4.3.3.2.3),
// z_j the height of floor j above the ground.
enum class StiffnessProfile { uniform, shear };
inline constexpr EnumName<StiffnessProfile> stiffness_profile_names[] = {{StiffnessProfile::uniform, "uniform"},
                                                                         {StiffnessProfile::shear, "shear"}};
constexpr const auto& enum_names(StiffnessProfile) { return stiffness_profile_names; }

// The profile's shape, k_1 = 1 (the bottom storey). storey_heights: one per storey (bottom first) or one value
// for all (m); ignored by `uniform`. Throws std::invalid_argument for masses or heights not finite and > 0.
std::vector<double> stiffness_shape(std::span<const double> m, std::span<const double> storey_heights,
                                    StiffnessProfile profile);
// Storey stiffnesses (N/m) of `profile` scaled so that the first period is T1 (s): k <- k (ω_target/ω_1)²,
// exact because K is linear in the scale and ω² with it.
std::vector<double> stiffness_for_period(std::span<const double> m, std::span<const double> storey_heights,
                                         StiffnessProfile profile, double T1);

}  // namespace pounding::model
