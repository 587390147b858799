// Every key of the study file (see study_keys.hpp). One entry per key, in its section; the order here is the
// order of docs/study-reference.md. After an edit: build/pounding study-reference -o docs/study-reference.md
#include "pounding/config/study_keys.hpp"

#include <cmath>

#include <fmt/format.h>

namespace pounding::config {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

constexpr StudySection sections[] = {
    {"", "Top level", "Keys before any [table]."},
    {"records", "[records]",
     "The ground motions: exactly one of `suite`, `directory` or `files` names them."},
    {"records.files", "[records] files entries",
     "An entry of `files` is a path string or an inline table `{path = \"b.AT2\", scale = 1.5}`."},
    {"structures", "[structures]",
     "The stochastic structure model (stochastic-pounding-monte-carlo.txt, sections 2.1-3.1): the defaults of both "
     "buildings and the settings they share."},
    {"structures.buildingN", "[structures.building1], [structures.building2] (and [structures.buildingK] of a row)",
     "One building's overrides of [structures] and its own period, height, mass, damping and strength. Every key is "
     "optional; an absent key takes the value of [structures]. Heights given to both buildings make a pair study "
     "(answers in metres). period, height, mass, zeta and yield_coefficient take a number or a distribution table "
     "(below)."},
    {"isolation", "[structures.buildingK] isolation = {...}",
     "Base isolation of a shear building (model = \"shear\"): a base mass on a bearing under the storeys "
     "(physics::IsolationSpec; docs/architecture.md §2.2.3). The superstructure keeps its fixed-base Rayleigh damping, "
     "its floor dashpots referencing the base. Peak displacements (peak_u1/2) include the base."},
    {"moat", "[structures.buildingK] moat = {...}",
     "Rigid moat walls either side of an isolated base (needs isolation): two contact elements in their own group, "
     "active in both scenes (they do not depend on the study gap), not counted in the pounding's impacts."},
    {"distribution", "Distribution tables",
     "`key = {lognormal = {median = .., cov = ..}}` or `key = {uniform = {min = .., max = ..}}` for period, height, "
     "mass, zeta or yield_coefficient of a building. Every draw is truncated exactly (inverse CDF) to the key's "
     "valid range (period (0, 100] s, height (0, 1000] m, mass (0, 1e10] kg, zeta [0, 1), Cy (0, 5]) and refused "
     "when that keeps less than 50 % of the probability."},
    {"distribution.lognormal", "lognormal = {median, cov}",
     "ln X ~ N(ln median, sigma^2), sigma^2 = ln(1 + cov^2)."},
    {"distribution.uniform", "uniform = {min, max}", "X uniform on [min, max], min <= max."},
    {"gaps", "[gaps]", "The gaps analysed, as ratios of the code separation d = code_gap_coefficient (h1 + h2)."},
    {"contact", "[contact]", "The contact element between the buildings."},
    {"contact.restitution", "[contact] restitution = {...}",
     "A velocity-dependent coefficient of restitution e(v0) (issue 26 §3; contact/restitution.hpp): each impact of "
     "the coupled runs takes e at its latched approach velocity v0, clamped to [0.01, 1], through the Hertzdamp "
     "damping law's xibar (the same curve as collide/simulate --restitution-*). SDOF pairs, shear buildings, rows and "
     "bridges (every joint; a joint's own restitution is then refused) with law = \"hertzdamp\", the central-difference "
     "stepper and the impacts scene; not with a moat; exclusive with [contact] e. Impacts whose v0 lies outside the "
     "valid range are counted per analysis, summed over a system's contact elements (impacts/restitution_outside), and "
     "reported. Give one of preset, "
     "polynomial, table; [contact] restitution = \"lindsay2011\" is short for {preset = \"lindsay2011\"}."},
    {"analysis", "[analysis]", "Time integration and the treatment of analyses that fail."},
    {"report", "[report]", "What the report derives from the results."},
    {"outputs", "[outputs]", "What the impacts scene must deliver (scene = \"auto\" reads it)."},
    {"intensity", "[intensity]",
     "A fragility study: the records are scaled to intensity-measure levels (stripes) and a fragility is fitted "
     "per gap."},
    {"intensity.periods", "[intensity] periods = {min, max, count}", "count log-spaced periods from min to max."},
    {"bridge", "[bridge]",
     "A bridge study (issue 26; docs/bridges.md): a chain of frames (SDOFs or short shear sticks) left to right, the expansion joints between "
     "them (contact elements of the [contact] law, the study's gap axis), cable restrainers and hinge bearings across "
     "the joints, abutments at the ends. The same keys as the bridge file of `pounding simulate --bridge`, whose top "
     "level is this table. The joints' gaps become the gap axis: d = the smallest joint gap is the reference the [gaps] "
     "ratios multiply, and joint j's gap at ratio x is x d + (gap_j - d). Not with [structures], [intensity] or "
     "[contact] levels / gap_offsets. Results: format 3, frames as the bodies (their levels as floors) and joints as the "
     "elements of /system."},
    {"bridge.frame", "[[bridge.frame]]", "One frame (pier and deck segment: an SDOF, or a short shear stick with storeys = n), left to right."},
    {"bridge.joint", "[[bridge.joint]]", "The expansion joint between frame j and frame j + 1 (one fewer than frames)."},
    {"bridge.restrainer", "[bridge.joint] restrainer = {...}",
     "Cable restrainers across the joint: tension-only bilinear with slack; the slack grows by the plastic elongation."},
    {"bridge.bearing", "[bridge.joint] bearing = {...}, [bridge.abutment.left|right] bearing = {...}",
     "An elastomeric bearing: bilinear kinematic hardening acting both ways (M&D: 6 kips/in, 2.4 kips, 33 %)."},
    {"bridge.abutments", "[bridge.abutment]", "The two abutments, as sub-tables left and right."},
    {"bridge.abutment", "[bridge.abutment.left], [bridge.abutment.right]",
     "An abutment: a wall with backfill in compression after its gap (elastic-perfectly-plastic, Caltrans SDC, or "
     "hyperbolic, Shamsabadi et al. 2007) and an optional bearing."},
    {"hazard", "[hazard]",
     "The site hazard of a fragility study: the annual rate of pounding and the risk-targeted separation."},
    {"target_spectrum", "[target_spectrum]",
     "The design spectrum the records of `[records] select = N` are chosen and amplitude-scaled to. Needs select; "
     "select needs it. Which keys a code takes is listed in each key's meaning."},
};

constexpr StudyKey keys[] = {
    // ---------------------------------------------------------------- top level
    {"", "title", "string", "the study file's stem", "", "any", "Shown in the log and the report."},
    {"", "seed", "integer", "required", "", "[0, 2^63 - 1]",
     "Master seed of every random stream (structures, synthetic records, bootstrap)."},
    {"", "scene", "string", "\"probability\"", "", "\"probability\" | \"impacts\" | \"auto\"",
     "probability: one uncoupled run per model answers every gap (whether a pair touches depends only on the "
     "motion before the first contact); impacts: coupled contact runs at every gap (forces, amplification); "
     "auto: impacts when [outputs] asks for forces or amplification, else probability."},
    {"", "output", "string", "<study stem>.h5", "", "a non-empty path",
     "The results file (HDF5), relative to the working directory."},
    {"", "records", "table", "required", "", "", "Section [records]."},
    {"", "structures", "table", "all defaults", "", "", "Section [structures]."},
    {"", "gaps", "table", "all defaults", "", "", "Section [gaps]."},
    {"", "contact", "table", "all defaults", "", "", "Section [contact]."},
    {"", "analysis", "table", "all defaults", "", "", "Section [analysis]."},
    {"", "report", "table", "all defaults", "", "", "Section [report]."},
    {"", "outputs", "table", "all defaults", "", "", "Section [outputs]."},
    {"", "intensity", "table", "absent", "", "", "Section [intensity]; present: a fragility study."},
    {"", "hazard", "table", "absent", "", "", "Section [hazard]; needs [intensity]."},
    {"", "target_spectrum", "table", "absent", "", "", "Section [target_spectrum]; needs [records] select."},
    {"", "bridge", "table", "absent", "", "", "Section [bridge]; present: a bridge study."},

    // ---------------------------------------------------------------- [records]
    {"records", "suite", "string", "none", "", "a suite file path, or \"builtin\"",
     "A records suite file (relative to the study file); \"builtin\" is the embedded 25-record synthetic suite."},
    {"records", "real_dir", "string", "none", "", "a directory",
     "Where the suite's real PEER records are (relative to the study file)."},
    {"records", "directory", "string", "none", "", "a directory",
     "Every record file in this directory (relative to the study file)."},
    {"records", "files", "array", "none", "", "paths or {path, scale} tables",
     "The record files, each a path (relative to the study file) or {path = .., scale = ..}."},
    {"records", "scale", "number", "1.0", "", "(0, 1000]", "Factor applied to every record.", 1e-6, 1e3},
    {"records", "units", "string", "\"g\"", "", "\"g\" | \"m/s2\" | \"cm/s2\"",
     "Units of the acceleration values in the record files."},
    {"records", "dt", "number", "0", "s", "[0, 1]",
     "Time step of one-column record files (files with a header give their own).", 0.0, 1.0},
    {"records", "limit", "integer", "0", "", "[0, 100000]",
     "Use only the first N records (0: all). Not together with select.", 0, 100000},
    {"records", "synthetic_only", "boolean", "false", "", "true | false",
     "Use only the suite's synthetic records."},
    {"records", "select", "integer", "none", "", "[1, 100000]",
     "Choose N records from the library named above and scale them to [target_spectrum] (ASCE 7-16 asks for at "
     "least 11). Needs [target_spectrum]; not with limit.", 1, 100000},
    {"records", "max_per_event", "integer", "2", "", "[0, 100000]",
     "With select: at most this many records of one earthquake (0: no limit). FEMA P-695's far-field set takes at "
     "most two per event, against event bias. Event from MANIFEST.tsv or the PEER header.", 0, 100000},
    {"records", "components", "string", "\"one\"", "", "\"one\" | \"both\"",
     "With select: one = one component per station (the better match); both = both may be chosen. A second copy of "
     "one recording (same event, station and axis) is never chosen."},
    {"records", "polarity", "string", "\"both\" in a pair study (both heights given), \"recorded\" in a grid study", "",
     "\"recorded\" | \"both\"",
     "\"both\" applies every record with both signs, as two analyses of the same record: pounding counts when "
     "building 1 moves towards building 2 (peak of u1 - u2), and a ground motion's sign is arbitrary. The bootstrap, "
     "jackknife and per-record tables keep a record's two signs together as one record. \"recorded\": the sign as "
     "recorded (the paper studies state it)."},

    {"records", "supports", "integer", "none (one record per analysis)", "", "[2, 100]",
     "A bridge on several supports (frames' support = K): the directory's files PREFIX_s01 .. PREFIX_sNN (pounding "
     "motions --out DIR writes rRRR_sJJ.AT2) are one realisation's N support motions, support K's record drives "
     "channel K. Only with directory; not with select.", 2, 100},
    {"records.files", "path", "string", "required", "", "a record file", "The record file (relative to the study)."},
    {"records.files", "scale", "number", "1.0", "", "(0, 1000]", "Factor applied to this record.", 1e-6, 1e3},

    // ---------------------------------------------------------------- [structures]
    {"structures", "periods", "array of numbers", "[1.00, 1.05, ..., 1.50]", "s", "[0.02, 20] (a real building), strictly increasing, 1 to 1000 values",
     "The period grid of both buildings: every pair (T1, T2) of the grid is a period pair. Not with "
     "period_min/period_max/period_step.", 0.02, 20.0},
    {"structures", "period_min", "number", "1.00", "s", "[0.02, 20] (a real building)", "First period of a grid period_min:period_step:period_max.",
     0.02, 20.0},
    {"structures", "period_max", "number", "1.50", "s", "[0.02, 20] (a real building)", "Last period of the grid.", 0.02, 20.0},
    {"structures", "period_step", "number", "0.05", "s", "> 0", "Step of the grid."},
    {"structures", "samples_per_pair", "integer", "256", "", "[1, 2^40] (and the results must fit in 64 GiB)",
     "Random structure pairs per period pair (the paper: 256 x 121 pairs = 30,976 models).", 1, 1099511627776.0},
    {"structures", "aspect_ratios", "array of numbers", "[1.0, 2.0, 3.0]", "", "(0, 100], 1 to 100 values",
     "Aspect ratios h/r of the foundation (equally likely); r = h / aspect.", 1e-300, 100.0},
    {"structures", "rho_mean", "number", "1800", "kg/m^3", "(0, 1e5]", "Mean of the lognormal soil density rho.",
     1e-300, 1e5},
    {"structures", "rho_cov", "number", "0.068", "", "[0, 2]", "CoV of the soil density.", 0.0, 2.0},
    {"structures", "mbar_mean", "number", "0.6", "", "(0, 100]",
     "Mean of the parent lognormal of the mass index mbar (m = mbar rho r^2 h).", 1e-300, 100.0},
    {"structures", "mbar_cov", "number", "0.20", "", "(0, 2]", "CoV of the mass index's parent lognormal.", 1e-300, 2.0},
    {"structures", "mbar_min", "number", "0.4", "", "(0, 100]", "Lower truncation of the mass index.", 1e-300, 100.0},
    {"structures", "mbar_max", "number", "0.8", "", "(mbar_min, 1000]", "Upper truncation of the mass index.",
     1e-300, 1000.0},
    {"structures", "zeta", "number", "0.05", "", "[0, 0.5] (a real building)", "Viscous damping ratio: c = 2 zeta sqrt(k m).", 0.0, 0.5},
    {"structures", "hysteresis", "string", "\"bilinear\"", "", "\"bilinear\" | \"elastic\"",
     "bilinear: kinematic hardening, fy from drift/ductility (or yield_coefficient) and alpha; elastic: linear."},
    {"structures", "drift", "number", "0.02", "", "(0, 1]", "Yield drift: u_y = drift h / ductility.", 1e-300, 1.0},
    {"structures", "ductility", "number", "6", "", "[1, 100]", "Ductility in u_y = drift h / ductility.", 1.0, 100.0},
    {"structures", "alpha", "number", "0.05", "", "[0, 1)", "Post-yield stiffness ratio.", 0.0, 0.999999},
    {"structures", "height_min", "number", "30", "m", "[2, 1000] (a real building)", "Lower height limit of the period-height rule.",
     2.0, 1000.0},
    {"structures", "height_max", "number", "50", "m", "[height_min, 1000]", "Upper height limit of the period-height rule.",
     2.0, 1000.0},
    {"structures", "ct_lower", "number", "0.05", "s/m^x", "(0, 10]",
     "Period-height rule ct_lower h^x <= T <= ct_upper h^x (eq. 6): the lower coefficient.", 1e-300, 10.0},
    {"structures", "ct_upper", "number", "0.08", "s/m^x", "(ct_lower, 10]", "The rule's upper coefficient.", 1e-300, 10.0},
    {"structures", "height_exponent", "number", "0.75", "", "(0, 2]", "The rule's exponent x.", 1e-300, 2.0},
    {"structures", "code_gap_coefficient", "number", "0.005", "", "(0, 1]",
     "Code separation d = coefficient (h1 + h2) (Standard 2800, eq. 5); gap ratios are multiples of d.", 1e-300, 1.0},
    {"structures", "contact_density", "number", "2400", "kg/m^3", "(0, 1e5]",
     "Density of the equivalent spheres of the Hertz contact stiffness.", 1e-300, 1e5},
    {"structures", "contact_youngs_modulus", "number", "24.86e9", "Pa", "(0, 1e13]",
     "Young's modulus of the equivalent spheres (57000 sqrt(4000) psi).", 1e-300, 1e13},
    {"structures", "contact_poisson", "number", "0.15", "", "[0, 0.5)", "Poisson's ratio of the equivalent spheres.",
     0.0, 0.499999},
    {"structures", "kh", "number", "0", "N/m^1.5", "[0, inf)",
     "The Hertz stiffness for every pair; 0: from equivalent spheres of the two buildings.", 0.0, inf},
    {"structures", "equal_heights", "boolean", "false", "", "true | false",
     "One height for both buildings, uniform on the intersection of their rule intervals (needs heights from the "
     "rule and grid or fixed periods)."},
    {"structures", "model", "string", "\"sdof\"", "", "\"sdof\" | \"shear\"",
     "The buildings' structural model (each building may override it): sdof = one DOF at the effective height "
     "(the paper's model); shear = a shear building of `storeys` floors, each storey storey_height high: floor "
     "masses from floor_mass or the building's mass split equally, storey stiffnesses from storey_stiffness or "
     "stiffness_profile scaled to the building's period T1, every storey yielding at the drift ratio drift / "
     "ductility (Vy_i = k_i storey_height drift / ductility; with yield_coefficient Cy: base shear Cy M g, upper "
     "storeys by the shear profile), Rayleigh damping zeta on modes 1 and 2 (rayleigh_modes); contact at the floors "
     "both buildings "
     "have at the same level (within 0.05 m). A shear building of one storey is the SDOF bit for bit. With "
     "[intensity] (fragility: stripes, IDA) every stripe runs the shear buildings on the scaled record, except that "
     "a lane whose every storey and bearing stays elastic is scaled from the lowest stripe (scale_elastic)."},
    {"structures", "storey_height", "number", "3.2", "m", "(0, 10] ([2, 10] for model = \"sdof\")",
     "The storey height of both buildings (each may override it): the code rules' storey count and the shear "
     "model's storeys (max(1, round(height / storey_height)) per sample) and floor levels.", 1e-300, 10.0},
    {"structures", "stiffness_profile", "string", "\"uniform\"", "", "\"uniform\" | \"shear\"",
     "Shear model, storey stiffnesses from T1: uniform = equal storeys; shear = proportional to the storey shear of "
     "an inverted-triangle load (model::stiffness_shape), both scaled so the fundamental period is T1."},
    {"structures", "damping", "string", "\"rayleigh\"", "", "\"rayleigh\" | \"modal\"",
     "Shear model: rayleigh = C = a0 M + a1 K0 with the building's zeta at modes 1 and 2 (the other modes get "
     "a0 / (2 omega) + a1 omega / 2); modal = classical modal damping C = M Phi diag(2 zeta_j omega_j / M_j) Phi' M, "
     "every mode exactly its ratio (modal_zeta, else zeta). The default of both buildings."},
    {"structures", "modal_zeta", "array of numbers", "every mode the building's zeta", "", "[0, 0.5] each",
     "With damping = \"modal\": the damping ratio per mode from mode 1, the last value repeating for the higher "
     "modes (a one-storey building takes the first). The default of both buildings.", 0.0, 0.5},
    {"structures", "rayleigh_modes", "array of numbers", "[1, 2]", "", "[1, 200], two different whole numbers",
     "With damping = \"rayleigh\" (shear model): the two modes i < j (either order) that get the building's zeta "
     "exactly; the others get a0 / (2 omega) + a1 omega / 2. A sampled building with fewer than j storeys takes "
     "modes min(i, j' - 1) and j' = min(j, n) -- the highest two it has (e.g. [1, 3] damps a two-storey building "
     "at modes 1 and 2) -- and one storey is the SDOF (c = 2 zeta sqrt(k m)); so in a row mixing SDOF and shear "
     "buildings it damps the shear buildings and the SDOFs keep their zeta (refused where every building is an "
     "SDOF). The run's model line states it; "
     "pounding modes --rayleigh-modes and simulate --rayleigh-modesK show each mode's ratio. The default of every "
     "building.", 1.0, 200.0},
    {"structures", "building1", "table", "the [structures] defaults", "", "", "Building 1 (the left one)."},
    {"structures", "building2", "table", "the [structures] defaults", "", "", "Building 2 (the right one of a pair)."},
    {"structures", "buildings", "integer", "2", "", "[2, 16]",
     "The number of buildings side by side, left to right (a row, docs/rows.md): each pounds its neighbours, every "
     "joint with the study gap ratio x d, d = code_gap_coefficient x the largest (h_j + h_j+1) of the row's joints; "
     "the probability scene counts an analysis as pounding when ANY joint touches. Buildings 3..n take one period "
     "each (a fixed period or a distribution in [structures.buildingK]: the period grid spans buildings 1 and 2); "
     "SDOF and shear buildings mix (a run of neighbouring SDOFs meets its shear neighbours at their floor nearest "
     "the lowest of its heights, at most the lower neighbour's roof; docs/rows.md); storey heights may differ; not "
     "with equal_heights. [intensity] (stripes, IDA) runs the whole row per stripe (docs/rows.md).",
     2.0, 16.0},
    {"structures", "buildingK", "table", "the [structures] defaults", "", "",
     "Building K of a row (K = 3..buildings, left to right after building 2); the same keys as building1."},

    // ---------------------------------------------------------------- [structures.building1], [structures.building2]
    {"structures.buildingN", "periods", "array of numbers", "[structures] periods", "s", "[0.02, 20] (a real building), strictly increasing",
     "This building's period grid. Not with period.", 0.02, 20.0},
    {"structures.buildingN", "period_min", "number", "1.00", "s", "[0.02, 20] (a real building)", "Grid form of periods, as in [structures].",
     0.02, 20.0},
    {"structures.buildingN", "period_max", "number", "1.50", "s", "[0.02, 20] (a real building)", "Grid form of periods.", 0.02, 20.0},
    {"structures.buildingN", "period_step", "number", "0.05", "s", "> 0", "Grid form of periods."},
    {"structures.buildingN", "period", "number or distribution", "none (the grid)", "s", "[0.02, 20] (a real building)",
     "A fixed period (a grid of one point) or a distribution drawn per sample (with the period-height rule: "
     "truncated to the periods the rule admits, refused when that keeps less than 50 %). Not with a grid.",
     0.02, 20.0},
    {"structures.buildingN", "height", "number or distribution", "the period-height rule", "m", "[2, 1000] (a real building)",
     "The building's height; default uniform on the rule interval for its period.", 2.0, 1000.0},
    {"structures.buildingN", "mass", "number or distribution", "the mass-index model", "kg", "[1e3, 1e10] (a real building)",
     "The mass; default m = mbar rho r^2 h.", 1e3, 1e10},
    {"structures.buildingN", "zeta", "number or distribution", "[structures] zeta", "", "[0, 0.5] (a real building)",
     "Viscous damping ratio.", 0.0, 0.5},
    {"structures.buildingN", "yield_coefficient", "number or distribution", "the drift/ductility rule", "", "[0.005, 5] (a real building)",
     "Cy = Vy / W: fy = Cy m g (g = 9.80665 m/s^2). Not with drift or ductility, nor for an elastic building.",
     0.005, 5.0},
    {"structures.buildingN", "alpha", "number", "[structures] alpha", "", "[0, 1)", "As in [structures].", 0.0, 0.999999},
    {"structures.buildingN", "hysteresis", "string", "[structures] hysteresis", "", "\"bilinear\" | \"elastic\"",
     "As in [structures]."},
    {"structures.buildingN", "aspect_ratios", "array of numbers", "[structures] aspect_ratios", "", "(0, 100]",
     "As in [structures].", 1e-300, 100.0},
    {"structures.buildingN", "rho_mean", "number", "[structures] rho_mean", "kg/m^3", "(0, 1e5]", "As in [structures].",
     1e-300, 1e5},
    {"structures.buildingN", "rho_cov", "number", "[structures] rho_cov", "", "[0, 2]", "As in [structures].", 0.0, 2.0},
    {"structures.buildingN", "mbar_mean", "number", "[structures] mbar_mean", "", "(0, 100]", "As in [structures].",
     1e-300, 100.0},
    {"structures.buildingN", "mbar_cov", "number", "[structures] mbar_cov", "", "(0, 2]", "As in [structures].",
     1e-300, 2.0},
    {"structures.buildingN", "mbar_min", "number", "[structures] mbar_min", "", "(0, 100]", "As in [structures].",
     1e-300, 100.0},
    {"structures.buildingN", "mbar_max", "number", "[structures] mbar_max", "", "(mbar_min, 1000]", "As in [structures].",
     1e-300, 1000.0},
    {"structures.buildingN", "drift", "number", "[structures] drift", "", "(0, 1]", "As in [structures].", 1e-300, 1.0},
    {"structures.buildingN", "ductility", "number", "[structures] ductility", "", "[1, 100]", "As in [structures].",
     1.0, 100.0},
    {"structures.buildingN", "height_min", "number", "[structures] height_min", "m", "[2, 1000] (a real building)", "As in [structures].",
     2.0, 1000.0},
    {"structures.buildingN", "height_max", "number", "[structures] height_max", "m", "[height_min, 1000]",
     "As in [structures].", 2.0, 1000.0},
    {"structures.buildingN", "ct_lower", "number", "[structures] ct_lower", "s/m^x", "(0, 10]",
     "As in [structures]; giving ct_lower, ct_upper or height_exponent checks a given height against the rule.",
     1e-300, 10.0},
    {"structures.buildingN", "ct_upper", "number", "[structures] ct_upper", "s/m^x", "(ct_lower, 10]",
     "As in [structures].", 1e-300, 10.0},
    {"structures.buildingN", "height_exponent", "number", "[structures] height_exponent", "", "(0, 2]",
     "As in [structures].", 1e-300, 2.0},
    // the building's code design factors (sampling/code_factors.hpp; issue 23 item 5): the report's code design
    // displacements from [target_spectrum] and the scope of Standard 2800's 0.005 h rule
    {"structures.buildingN", "asce7_r", "number", "none", "", "[1, 8]",
     "ASCE 7-16 Table 12.2-1 response modification coefficient R of the building's system (with asce7_cd): the "
     "report's ASCE 7-16 design displacement delta_M = Cd delta_e / Ie.", 1.0, 8.0},
    {"structures.buildingN", "asce7_cd", "number", "none", "", "[1, 6.5]",
     "ASCE 7-16 Table 12.2-1 deflection amplification factor Cd (with asce7_r).", 1.0, 6.5},
    {"structures.buildingN", "asce7_ie", "number", "1.0", "", "1.0 | 1.25 | 1.5",
     "ASCE 7-16 Table 1.5-2 seismic importance factor Ie.", 1.0, 1.5},
    {"structures.buildingN", "ec8_q", "number", "none", "", "[1, 8]",
     "EN 1998-1 behaviour factor q: the report's EC8 design displacement d_s = q d_e (q_d = q, 4.3.4).", 1.0, 8.0},
    {"structures.buildingN", "s2800_ru", "number", "none", "", "[1, 8]",
     "Standard 2800 (4th ed.) behaviour factor Ru of the building's system (with s2800_cd): the report's design "
     "drift Delta_M = Cd Delta_eu.", 1.0, 8.0},
    {"structures.buildingN", "s2800_cd", "number", "none", "", "[1, 6.5]",
     "Standard 2800 deflection amplification factor Cd (with s2800_ru).", 1.0, 6.5},
    {"structures.buildingN", "s2800_importance", "number", "[target_spectrum] importance (Standard 2800), else not known",
     "", "0.8 | 1.0 | 1.2 | 1.4",
     "Standard 2800 importance factor I; 1.2 and 1.4 (high, very high) put the building outside the 0.005 h rule.",
     0.8, 1.4},
    {"structures.buildingN", "storeys", "integer", "round(height / storey_height), at least 1", "", "[1, 200]",
     "Storeys above the base: Standard 2800's 0.005 h rule is for at most 8.", 1, 200},
    {"structures.buildingN", "storey_height", "number", "[structures] storey_height (3.2)", "m",
     "(0, 10] ([2, 10] for model = \"sdof\")",
     "The default of storeys (max(1, round(height / storey_height))) and, for model = \"shear\", every storey's "
     "height: floor k at k storey_height (a scale model's frames may be 0.1 m). Shear buildings of different storey "
     "heights pound floor to floor where levels agree within [contact] level_tolerance and floor to column elsewhere "
     "(docs/floor-contact.md).", 1e-300, 10.0},
    {"structures.buildingN", "model", "string", "[structures] model", "", "\"sdof\" | \"shear\"",
     "As in [structures]: an SDOF building may pair with a shear building (it meets the floor nearest its height, "
     "its roof if the other is lower)."},
    {"structures.buildingN", "floor_mass", "number", "the building's mass / storeys", "kg", "[1e-3, 1e9]",
     "Shear model: the mass of every floor. Absent: the building's mass (given or the mass-index model) split "
     "equally over its floors.", 1e-3, 1e9},
    {"structures.buildingN", "storey_stiffness", "number", "stiffness_profile scaled to the period", "N/m",
     "[1, 1e12]",
     "Shear model: the stiffness of every storey. Absent: stiffness_profile scaled so the fundamental period is the "
     "building's period (sampled or given); given, the building's T1 is this stiffness's and the period only "
     "selects the height.", 1.0, 1e12},
    {"structures.buildingN", "stiffness_profile", "string", "[structures] stiffness_profile", "",
     "\"uniform\" | \"shear\"", "As in [structures]."},
    {"structures.buildingN", "damping", "string", "[structures] damping", "", "\"rayleigh\" | \"modal\"",
     "As in [structures]; \"modal\" needs model = \"shear\" (an isolated building: its superstructure's fixed-base modes)."},
    {"structures.buildingN", "modal_zeta", "array of numbers", "[structures] modal_zeta", "", "[0, 0.5] each",
     "As in [structures].", 0.0, 0.5},
    {"structures.buildingN", "rayleigh_modes", "array of numbers", "[structures] rayleigh_modes", "",
     "[1, 200], two different whole numbers", "As in [structures] (model = \"shear\", damping = \"rayleigh\").",
     1.0, 200.0},
    {"structures.buildingN", "isolation", "table", "none (fixed base)", "", "{bearing, base_mass, ...}",
     "Shear model: base isolation (keys under \"[structures.buildingK] isolation\")."},
    {"structures.buildingN", "moat", "table", "none", "", "{gap, law, stiffness, e}",
     "Shear model with isolation: moat walls (keys under \"[structures.buildingK] moat\")."},

    // ---------------------------------------------------------------- isolation, moat
    {"isolation", "bearing", "string", "\"linear\"", "",
     "\"linear\" | \"lead-rubber\" | \"friction-pendulum\" | \"bouc-wen\"",
     "linear: a spring k_eff and a dashpot 2 zeta_eff sqrt(k_eff M_total) on the bearing's deformation; lead-rubber: "
     "bilinear kinematic hardening k1, k2 with characteristic strength qd (Fy = qd / (1 - k2 / k1)), no viscous "
     "damping of its own; friction-pendulum: a pendulum spring W / R (W = g M_total, the base and the storeys) plus "
     "friction mu(v) W through a smoothed stick-slip of yield displacement u_y (Constantinou et al. 1990); "
     "bouc-wen: F = k2 u + qd z with Bouc-Wen's z (|z| <= 1 for A = beta + gamma, u_y = qd / (k1 - k2)). The "
     "same laws and numbers as pounding simulate --isolationK."},
    {"isolation", "base_mass", "number", "one floor's mass", "kg", "[1e-3, 1e10]",
     "The base slab's mass above the bearings.", 1e-3, 1e10},
    {"isolation", "k_eff", "number", "required (linear)", "N/m", "[1, 1e12]", "Linear bearing: effective stiffness.",
     1.0, 1e12},
    {"isolation", "zeta_eff", "number", "0.1", "", "[0, 0.5]",
     "Linear bearing: effective damping ratio (the default is simulate's --bearing-zeta and Python's).", 0.0, 0.5},
    {"isolation", "k1", "number", "required (lead-rubber, bouc-wen)", "N/m", "[1, 1e12]",
     "Lead-rubber and Bouc-Wen bearings: elastic (pre-yield) stiffness.", 1.0, 1e12},
    {"isolation", "k2", "number", "required (lead-rubber, bouc-wen)", "N/m", "[0, 1e12], below k1",
     "Lead-rubber and Bouc-Wen bearings: post-yield stiffness.", 0.0, 1e12},
    {"isolation", "qd", "number", "required (lead-rubber, bouc-wen)", "N", "[1e-3, 1e10]",
     "Lead-rubber and Bouc-Wen bearings: characteristic strength (force at zero displacement on the hysteresis "
     "loop).", 1e-3, 1e10},
    {"isolation", "radius", "number", "required (friction-pendulum)", "m", "[0.1, 50]",
     "Friction pendulum: effective radius R of the sliding surface (T = 2 pi sqrt(R / g) for a rigid "
     "superstructure).", 0.1, 50.0},
    {"isolation", "mu_slow", "number", "required (friction-pendulum)", "", "[0.001, 0.5]",
     "Friction pendulum: friction coefficient at rest.", 1e-3, 0.5},
    {"isolation", "mu_fast", "number", "mu_slow", "", "[0.001, 0.5]",
     "Friction pendulum: friction coefficient at high speed, mu(v) = mu_fast - (mu_fast - mu_slow) exp(-rate |v|) "
     "(a value other than mu_slow needs rate > 0).", 1e-3, 0.5},
    {"isolation", "rate", "number", "0", "s/m", "[0, 1000]",
     "Friction pendulum: the rate a of mu(v) (0: constant friction mu_slow).", 0.0, 1e3},
    {"isolation", "u_y", "number", "0.00025", "m", "[1e-6, 0.02]",
     "Friction pendulum: yield displacement of the smoothed stick-slip (the sliding starts within it).", 1e-6, 0.02},
    {"isolation", "a", "number", "1", "", "[0.1, 10]", "Bouc-Wen bearing: A of dz/du = (A - |z|^eta (gamma + beta "
     "sgn(z du))) / u_y.", 0.1, 10.0},
    {"isolation", "beta", "number", "0.5", "", "[0.001, 10]", "Bouc-Wen bearing: beta, the |du| term.", 1e-3, 10.0},
    {"isolation", "gamma", "number", "0.5", "", "[-10, 10], |gamma| <= beta",
     "Bouc-Wen bearing: gamma, the du term (|gamma| <= beta: the stable, passive class).", -10.0, 10.0},
    {"isolation", "eta", "integer", "1", "", "[1, 8]", "Bouc-Wen bearing: the exponent eta (an integer).", 1.0, 8.0},
    {"moat", "gap", "number", "required", "m", "[1e-4, 10]", "Clearance from the base to each wall.", 1e-4, 10.0},
    {"moat", "law", "string", "[contact] law", "", "a contact law except \"none\"", "The walls' contact law."},
    {"moat", "stiffness", "number", "equivalent spheres of the base mass with itself", "law units", "[0, 1e13]",
     "Contact stiffness (N/m for linear and Kelvin, N/m^1.5 for Hertz laws); 0: the default.", 0.0, 1e13},
    {"moat", "e", "number", "[contact] e", "", "(0, 1]", "Coefficient of restitution at the walls.", 1e-6, 1.0},

    // ---------------------------------------------------------------- distributions
    {"distribution", "lognormal", "table", "", "", "{median, cov}", "A lognormal law (not with uniform)."},
    {"distribution", "uniform", "table", "", "", "{min, max}", "A uniform law (not with lognormal)."},
    {"distribution.lognormal", "median", "number", "required", "the key's", "the key's range", "The median."},
    {"distribution.lognormal", "cov", "number", "required", "", "[0, 2]", "CoV of X; 0 means fixed."},
    {"distribution.uniform", "min", "number", "required", "the key's", "the key's range", "Lower end."},
    {"distribution.uniform", "max", "number", "required", "the key's", ">= min", "Upper end."},

    // ---------------------------------------------------------------- [bridge]
    {"bridge", "frame", "array of tables", "required", "", "2 or more tables (a study), 1 or more (a bridge file)",
     "The frames, left to right ([[bridge.frame]])."},
    {"bridge", "joint", "array of tables", "required", "", "one fewer than frames", "The joints ([[bridge.joint]])."},
    {"bridge", "abutment", "table", "none", "", "{left, right}", "The abutments ([bridge.abutment.left|right])."},
    {"bridge", "samples", "integer", "1", "", "[1, 1000000]",
     "Bridges per record (models): 1 for a fixed bridge; more with period_cov or mass_cov.", 1, 1e6},
    {"bridge", "period_cov", "number", "0", "", "[0, 1]",
     "Lognormal CoV of each frame's period about its own (median; truncated to [0.02, 20] s), drawn per model and "
     "frame independently. 0: fixed.", 0.0, 1.0},
    {"bridge", "mass_cov", "number", "0", "", "[0, 1]",
     "Lognormal CoV of each frame's mass about its own (truncated to [1, 1e10] kg). 0: fixed.", 0.0, 1.0},
    {"bridge.frame", "label", "string", "\"frame K\"", "", "any", "The frame's name in reports."},
    {"bridge.frame", "mass", "number", "required", "kg", "[1, 1e10]", "The frame's mass (deck and tributary pier).",
     1.0, 1e10},
    {"bridge.frame", "period", "number", "required (or stiffness)", "s", "[0.02, 20]",
     "The frame's stand-alone period; k = m (2 pi / T)^2.", 0.02, 20.0},
    {"bridge.frame", "stiffness", "number", "required (or period)", "N/m", "[1, 1e13]", "The frame's lateral stiffness.",
     1.0, 1e13},
    {"bridge.frame", "zeta", "number", "0.05", "", "[0, 0.5]", "Damping ratio: a dashpot 2 zeta sqrt(k m) to its pier's ground.",
     0.0, 0.5},
    {"bridge.frame", "yield_force", "number", "none (linear)", "N", "[1, 1e16]", "The frame's yield force.", 1.0, 1e16},
    {"bridge.frame", "alpha", "number", "0", "", "[0, 0.999]", "Post-yield stiffness ratio.", 0.0, 0.999},
    {"bridge.frame", "hysteresis", "string", "\"bilinear\"", "", "\"bilinear\" | \"q-hyst\"",
     "bilinear: kinematic hardening; q-hyst: Saiidi & Sozen's stiffness-degrading law (needs yield_force)."},
    {"bridge.frame", "beta", "number", "0.5", "", "[0, 1]", "Q-Hyst's unloading exponent: k_u = k0 (d_y / d_m)^beta.",
     0.0, 1.0},
    {"bridge.frame", "height", "number", "10", "m", "[0.1, 1000]", "The pier height (labels and drift ratios).", 0.1, 1000.0},
    {"bridge.frame", "support", "integer", "1", "", "[1, 1000]",
     "The ground-motion channel of its pier (multi-support input; 1 for uniform input).", 1, 1000},
    {"bridge.frame", "storeys", "integer", "1", "", "[1, 50]",
     "Levels of the frame: 1 an SDOF (pier and deck); n > 1 a short shear stick of n levels (pier levels under the "
     "deck, the deck the top level; joints, restrainers, bearings and abutments act on the deck). A stick's mass, "
     "stiffness and yield_force are each level's / storey's, its period T1 (uniform stiffness), its zeta Rayleigh's at "
     "modes 1 and 2 (or damping = \"modal\"), its hysteresis every storey's.", 1, 50},
    {"bridge.frame", "storey_mass", "array of numbers", "mass on every level", "kg", "[1, 1e10]",
     "A stick's level masses, bottom first (one value or one per level; the deck's last). Instead of mass.", 1.0, 1e10},
    {"bridge.frame", "storey_stiffness", "array of numbers", "stiffness or period", "N/m", "[1, 1e13]",
     "A stick's storey stiffnesses, bottom first (one value or one per storey). Instead of stiffness/period.", 1.0, 1e13},
    {"bridge.frame", "storey_yield", "array of numbers", "yield_force in every storey", "N", "[1, 1e16]",
     "A stick's storey yield forces, bottom first (one value or one per storey). Instead of yield_force.", 1.0, 1e16},
    {"bridge.frame", "storey_height", "array of numbers", "height / storeys", "m", "[0.01, 1000]",
     "A stick's storey heights, bottom first (one value or one per storey; labels and drifts).", 0.01, 1000.0},
    {"bridge.frame", "damping", "string", "\"rayleigh\"", "", "\"rayleigh\" | \"modal\"",
     "A stick's damping: Rayleigh (zeta at modes 1 and 2; floor and storey dashpots) or classical modal damping "
     "(zeta, or modal_zeta per mode)."},
    {"bridge.frame", "modal_zeta", "array of numbers", "zeta for every mode", "", "[0, 0.5]",
     "Modal damping ratios from mode 1 (the last repeating); with damping = \"modal\".", 0.0, 0.5},
    {"bridge.joint", "gap", "number", "required", "m", "[0, 10] (a study: > 0)",
     "The joint's gap. In a study the smallest is the reference d of the [gaps] ratios.", 0.0, 10.0},
    {"bridge.joint", "contact_stiffness", "number", "[contact] stiffness (a study), --kh (a bridge file)", "law units",
     "[1, 1e16]", "The joint's contact stiffness: N/m^n for the Hertz family, N/m for linear and Kelvin.", 1.0, 1e16},
    {"bridge.joint", "restitution", "number", "[contact] e (a study), --e (a bridge file)", "", "[0.01, 1]",
     "The joint's coefficient of restitution.", 0.01, 1.0},
    {"bridge.joint", "restrainer", "table", "none", "", "{stiffness, yield_force, alpha, slack}", "Cable restrainers."},
    {"bridge.joint", "bearing", "table", "none", "", "{stiffness, yield_force, alpha}", "A hinge bearing."},
    {"bridge.restrainer", "stiffness", "number", "required", "N/m", "[1, 1e13]", "Elastic stiffness of the restrainers.",
     1.0, 1e13},
    {"bridge.restrainer", "yield_force", "number", "none (elastic)", "N", "[1, 1e16]", "Yield force.", 1.0, 1e16},
    {"bridge.restrainer", "alpha", "number", "0.05", "", "[0, 0.999]", "Post-yield stiffness ratio.", 0.0, 0.999},
    {"bridge.restrainer", "slack", "number", "the joint's gap (a bridge file); required in a study", "m", "[0, 10]",
     "Opening of the joint before the cables take tension.", 0.0, 10.0},
    {"bridge.bearing", "stiffness", "number", "required", "N/m", "[1, 1e13]", "Elastic stiffness.", 1.0, 1e13},
    {"bridge.bearing", "yield_force", "number", "none (linear)", "N", "[1, 1e16]", "Yield force.", 1.0, 1e16},
    {"bridge.bearing", "alpha", "number", "0", "", "[0, 0.999]", "Post-yield stiffness ratio.", 0.0, 0.999},
    {"bridge.abutments", "left", "table", "none", "", "[bridge.abutment.left]", "The left abutment (at frame 1)."},
    {"bridge.abutments", "right", "table", "none", "", "[bridge.abutment.right]", "The right abutment (at the last frame)."},
    {"bridge.abutment", "backfill", "string", "\"none\"", "", "\"none\" | \"epp\" | \"hyperbolic\"",
     "The backfill's law in compression after the gap."},
    {"bridge.abutment", "gap", "number", "0", "m", "[0, 10]", "The expansion gap between the deck and the back wall.",
     0.0, 10.0},
    {"bridge.abutment", "stiffness", "number", "required (epp without width and height)", "N/m", "[1, 1e13]",
     "EPP backfill: stiffness.", 1.0, 1e13},
    {"bridge.abutment", "capacity", "number", "required (epp without width and height)", "N", "[1, 1e16]",
     "EPP backfill: passive capacity.", 1.0, 1e16},
    {"bridge.abutment", "width", "number", "none", "m", "[0.1, 1000]",
     "EPP backfill: back-wall width for Caltrans SDC's K_abut and P_bw (with height).", 0.1, 1000.0},
    {"bridge.abutment", "height", "number", "none", "m", "[0.1, 100]", "EPP backfill: back-wall height (with width).",
     0.1, 100.0},
    {"bridge.abutment", "alpha", "number", "0", "", "[0, 0.999]", "EPP backfill: post-yield ratio.", 0.0, 0.999},
    {"bridge.abutment", "k_max", "number", "required (hyperbolic)", "N/m", "[1, 1e13]", "Hyperbolic backfill: initial stiffness.",
     1.0, 1e13},
    {"bridge.abutment", "k_ur", "number", "k_max", "N/m", "[1, 1e13], >= k_max", "Hyperbolic backfill: unloading/reloading stiffness.",
     1.0, 1e13},
    {"bridge.abutment", "rf", "number", "0.7", "", "[0.001, 1]", "Hyperbolic backfill: failure ratio.", 1e-3, 1.0},
    {"bridge.abutment", "f_ult", "number", "required (hyperbolic)", "N", "[1, 1e16]", "Hyperbolic backfill: ultimate force.",
     1.0, 1e16},
    {"bridge.abutment", "bearing", "table", "none", "", "{stiffness, yield_force, alpha}", "The abutment's bearing."},
    {"bridge.abutment", "support", "integer", "1", "", "[1, 1000]", "The ground-motion channel of the wall.", 1, 1000},

    // ---------------------------------------------------------------- [gaps]
    {"gaps", "ratios", "array of numbers", "[0.1, 0.2, 0.3, 0.5, 0.7, 1.0]", "", "(0, 100], strictly increasing",
     "The gaps analysed (impacts scene) as ratios of the code separation d.", 1e-9, 100.0},
    {"gaps", "curve_max", "number", "max(1.5, the largest ratio)", "", "[0.01, 100]",
     "Upper end of the probability-versus-gap curve.", 0.01, 100.0},
    {"gaps", "curve_step", "number", "0.005", "", "[1e-4, 1]", "Step of the probability-versus-gap curve.", 1e-4, 1.0},

    // ---------------------------------------------------------------- [contact]
    {"contact", "law", "string", "\"hertzdamp\"", "",
     "\"linear\" | \"kelvin\" | \"hertz\" | \"hertzdamp\" | \"jankowski\" | \"stereomechanical\"",
     "The contact law (\"none\" is refused: it cannot count impacts)."},
    {"contact", "damping_law", "string", "\"lankarani-nikravesh\"", "",
     "\"lankarani-nikravesh\" | \"hunt-crossley\" | \"flores\" | \"hu-guo\" | \"gonthier\" | \"calibrated\" | "
     "\"ye\" | \"three-spring\"",
     "How Hertzdamp's damping follows from e (calibrated: one free impact returns exactly e; ye and three-spring: the "
     "link-element paper's laws, three-spring acting on 1.5 x the contact stiffness)."},
    {"contact", "e", "number", "0.65", "", "(0, 1]", "Coefficient of restitution.", 1e-6, 1.0},
    {"contact", "levels", "string", "\"common\"", "", "\"common\" | \"top\"",
     "Shear buildings and rows: which facing floors pound -- common = every pair of floors at the same level (and "
     "every other floor against the neighbour's column, docs/floor-contact.md), top = only the lower roof of each pair "
     "of neighbours (against the other building's floor or column there)."},
    {"contact", "gap_offsets", "array of numbers", "none (0 at every level)", "m", "[0, 10]",
     "Shear buildings and rows: per contact level from level 1 (an element's level: the number of the floor that "
     "strikes, the left one floor to floor), added to the study gap at that level (a level beyond the list: 0). An analysis touches at gap g when some level's uncoupled closing minus its offset exceeds g "
     "(/uncoupled/peak_closing is the largest of those), so the probability scene stays exact.",
     0.0, 10.0},
    {"contact", "joint_gap_offsets", "array of numbers", "none (0 at every joint)", "m", "[0, 10]",
     "Rows: per joint left to right (buildings - 1 values), added to the study gap of every element of that joint "
     "(with gap_offsets: both). An analysis touches at gap g when some element's uncoupled closing minus its "
     "offset exceeds g (/uncoupled/peak_closing is the largest of those, /system/element_gap_offset each element's "
     "offset), so the probability scene stays exact. Not for a pair (its one joint's gap is the ratio x d) or a "
     "bridge (each [[bridge.joint]] has its own gap).",
     0.0, 10.0},
    {"contact", "level_tolerance", "number", "0.05", "m", "[0, 1]",
     "Shear buildings and rows, below half the smallest storey height (a floor meets at most one floor): floors of "
     "neighbouring buildings whose levels differ by at most this meet floor to "
     "floor; every other floor below the neighbour's roof meets the neighbour's column between two floors (linear "
     "shape functions, docs/floor-contact.md). 0.05 m: slabs whose levels differ by less overlap over most of their "
     "depth (a 0.15-0.25 m slab), i.e. the construction tolerance of one level, not a different level.",
     0.0, 1.0},
    {"contact", "shape_functions", "string", "\"linear\"", "", "\"linear\" | \"cubic\"",
     "Shear buildings: how a floor striking the neighbour's column between two floors shares the column's two floors "
     "(x = (1 - N2) u_below + N2 u_above, the force with the same weights): linear N2 = xi, or cubic N2 = 3 xi^2 - "
     "2 xi^3, the fixed-fixed column's deflected shape (its nodal forces are the column's fixed-end reactions). "
     "docs/floor-contact.md."},
    {"contact", "n", "number", "1.5", "", "[1, 3]", "Exponent of the Hertz-family force k delta^n.", 1.0, 3.0},
    {"contact", "v0_min", "number", "1e-3", "m/s", "(0, 1]",
     "Smallest approach velocity used to set the contact damping.", 1e-12, 1.0},
    {"contact", "stiffness", "number", "0 (Hertz family: equivalent spheres)", "N/m^n (N/m for linear, kelvin)",
     "(0, 1e20]", "Contact stiffness; required for linear and kelvin.", 0.0, 1e20},
    {"contact", "restitution", "string or table", "none (e for every impact)", "", "\"lindsay2011\" | {...}",
     "e(v0) instead of e: a preset's name, or the table under \"[contact] restitution\"."},
    {"contact.restitution", "preset", "string", "none", "", "\"lindsay2011\"",
     "The bridge paper's eq. 15 (lindsay-2011-bridge-expansion-joints.txt), model-scale m/s, valid 0.99-3.13 m/s; "
     "PROVISIONAL (a coefficient's digit and sign were lost in the text: seeds-models.md §1.7)."},
    {"contact.restitution", "polynomial", "array of numbers", "none", "", "1 to 8 coefficients in [-1e300, 1e300]",
     "e(v) = c0 + c1 v + c2 v^2 + ..., constant term first, v in `units`.", -1e300, 1e300},
    {"contact.restitution", "table", "array of [v, e] pairs", "none", "", "v ascending >= 0, e in (0, 1]",
     "e(v) linear between the points, the end values beyond; the valid range defaults to the table's."},
    {"contact.restitution", "units", "string", "\"m/s\"", "", "\"m/s\" | \"cm/s\" | \"mm/s\"",
     "Velocity units of the polynomial, the table and valid."},
    {"contact.restitution", "valid", "array of numbers", "the table's range; [0, inf) for a polynomial", "", "[vmin, vmax], 0 <= vmin < vmax",
     "The calibrated velocity range: impacts outside it are counted and reported.", 0.0, 1e300},

    // ---------------------------------------------------------------- [analysis]
    {"analysis", "stepper", "string", "\"central-difference\"", "",
     "\"central-difference\" | \"newmark\" | \"rk4\" | \"nigam-jennings\"",
     "The time integrator. SDOF pairs: all four. Shear buildings and rows: central-difference, newmark (average "
     "acceleration with Newton, unconditionally stable for the structure) or rk4 (h omega_max < 2.8); newmark and rk4 "
     "run bilinear storeys and linear or lead-rubber bearings (not friction-pendulum or Bouc-Wen). Bridges: "
     "central-difference."},
    {"analysis", "substeps", "integer", "1", "", "[1, 10000]", "Integration steps per record step.", 1, 10000},
    {"analysis", "max_dt", "number", "0.0025 in the impacts scene, 0 in the probability scene", "s", "[0, 1] (0: no cap)",
     "Largest integration step (docs/accuracy.md: 2.5 ms gives 1 % peak forces).", 0.0, 1.0},
    {"analysis", "batch", "integer", "256", "", "[1, 65536]",
     "Models integrated together (results do not depend on it).", 1, 65536},
    {"analysis", "threads", "integer", "0", "", "[0, 1024] (0: automatic)",
     "Worker threads per rank, each computing its own units. 0: the CPUs this process may run on (its affinity "
     "mask) when the job is one rank, 1 per rank under mpirun with several ranks (nothing oversubscribes); a "
     "value given applies to every rank. pounding run --threads and Study.run(threads=) override it. Results do "
     "not depend on it.", 0, 1024},
    {"analysis", "free_vibration", "number", "0", "s", "[0, 1000]", "Time analysed after the record ends.", 0.0, 1000.0},
    {"analysis", "displacement_limit", "number", "10", "m", "(0, 1e6]",
     "A model whose displacement exceeds this is marked diverged.", 1e-6, 1e6},
    {"analysis", "skip_untouched", "boolean", "true", "", "true | false",
     "Impacts scene: pairs whose uncoupled peak closing stays below a gap are not rerun with contact (their "
     "coupled run would be identical)."},
    {"analysis", "scale_elastic", "boolean", "true", "", "true | false",
     "Multiple stripes: a model that stays elastic takes the lowest stripe's peaks times the ratio of the scale "
     "factors instead of a run (an elastic response scales exactly with the record)."},
    {"analysis", "max_excluded_fraction", "number", "0.001", "", "[0, 1]",
     "Largest fraction of all analyses that may be excluded (diverged, non-finite, coarse) before the run ends "
     "with exit code 3.", 0.0, 1.0},
    {"analysis", "coarse", "string", "\"exclude\"", "", "\"exclude\" | \"keep\"",
     "A coupled analysis the resolution guard marks coarse (its peak force is off by more than 1 %): excluded "
     "from the statistics like a diverged one, or kept (still counted and reported)."},

    // ---------------------------------------------------------------- [report]
    {"report", "targets", "array of numbers", "[10, 5, 1]", "%", "(0, 100)",
     "Probabilities of pounding whose separations the report gives.", 1e-6, 99.999},
    {"report", "fit_min", "number", "0.1", "", "[0, 100]", "Lowest gap ratio of the cubic fit.", 0.0, 100.0},
    {"report", "fit_max", "number", "1.0", "", "[0, 100], > fit_min", "Highest gap ratio of the cubic fit.", 0.0, 100.0},
    {"report", "confidence", "number", "0.95", "", "[0.5, 0.999]", "Level of the bootstrap intervals.", 0.5, 0.999},
    {"report", "bootstrap", "integer", "2000", "", "[0, 100000]",
     "Replicates of the two-stage bootstrap (records, then models within records); 0: no interval.", 0, 100000},
    {"report", "compare_with", "string", "\"\"", "", "\"\" | \"stochastic-pounding\"",
     "Print the published study's Table 3 and eq. 10 beside ours (the paper studies set it)."},
    {"report", "html", "boolean", "false", "", "true | false",
     "Also write the HTML report (answer, figures, every table, provenance; one self-contained file) next to the "
     "results at the end of the run: the output path with .html for its extension."},
    {"report", "h1", "refused", "", "", "", "No longer a setting: heights come from [structures.building1] height."},
    {"report", "h2", "refused", "", "", "", "No longer a setting: heights come from [structures.building2] height."},

    // ---------------------------------------------------------------- [outputs]
    {"outputs", "forces", "boolean", "true", "", "true | false", "Peak impact forces (impacts scene)."},
    {"outputs", "amplification", "boolean", "true", "", "true | false",
     "Amplification of the peak displacement by pounding (impacts scene)."},
    {"outputs", "per_model", "boolean", "true", "", "true | false",
     "false: keep only the reductions (per record and gap ratio the hit counts, per period pair the maps, the gap "
     "curve, per record a histogram of peak closing / code gap on a log grid of 200 bins per decade) instead of every "
     "model's peaks, so memory does not grow with the models (docs/results-format.md /reductions). Probability scene "
     "of an SDOF pair or grid study only; the report's tables are exact, its separation advice is read from the "
     "histograms."},

    // ---------------------------------------------------------------- [intensity]
    {"intensity", "measure", "string", "\"Sa\"", "", "\"PGA\" | \"PGV\" | \"Sa\" | \"Sa_avg\"",
     "The intensity measure of the stripes."},
    {"intensity", "method", "string", "\"msa\"", "", "\"msa\" | \"ida\"",
     "Multiple stripes (Baker 2015 MLE) or incremental dynamic analysis."},
    {"intensity", "period", "number or \"pair\"", "required for Sa", "s", "[0.01, 20]",
     "Sa's period; \"pair\": the geometric mean of the buildings' median periods. Only for Sa.", 0.01, 20.0},
    {"intensity", "periods", "array of numbers or {min, max, count}", "required for Sa_avg", "s", "[0.01, 20], at least 2",
     "Sa_avg's periods (the geometric mean of Sa over them). Only for Sa_avg.", 0.01, 20.0},
    {"intensity", "damping", "number", "0.05", "", "[0, 0.5]", "Damping ratio of Sa and Sa_avg.", 0.0, 0.5},
    {"intensity", "levels", "array of numbers", "required", "g (PGV: m/s)", "(0, 10] g, (0, 20] m/s; increasing",
     "The stripes' IM levels (msa: at least 2)."},
    {"intensity", "max_scale", "number", "10", "", "[1, 1000]",
     "A record whose factor to a level exceeds this is dropped from that stripe.", 1.0, 1000.0},
    {"intensity", "tolerance", "number", "0.01", "", "[1e-6, 0.5]",
     "ida, yielding structures: bisection until the bracket of the IM at first contact is within this relative "
     "width. Only for method = \"ida\".", 1e-6, 0.5},

    {"intensity.periods", "min", "number", "required", "s", "[0.01, 20]", "First period.", 0.01, 20.0},
    {"intensity.periods", "max", "number", "required", "s", "[0.01, 20], > min", "Last period.", 0.01, 20.0},
    {"intensity.periods", "count", "integer", "10", "", "[2, 200]", "Number of log-spaced periods.", 2, 200},

    // ---------------------------------------------------------------- [hazard]
    {"hazard", "curve", "string", "none", "", "a CSV file",
     "The hazard curve: rows of IM, annual rate of exceedance (IM increasing, rate decreasing; relative to the "
     "study file). Not with k0, k."},
    {"hazard", "k0", "number", "none", "1/year", "[1e-12, 10]",
     "Power-law hazard lambda(IM) = k0 IM^-k. Not with curve.", 1e-12, 10.0},
    {"hazard", "k", "number", "none", "", "[0.1, 20]", "Slope of the power-law hazard.", 0.1, 20.0},
    {"hazard", "years", "number", "50", "years", "[1, 10000]", "Exposure time of the probability of pounding.", 1.0,
     10000.0},
    {"hazard", "target", "number", "2.0", "% in `years`", "[0.0001, 99]",
     "Target probability of pounding of the risk-targeted separation.", 1e-4, 99.0},
    {"hazard", "source", "string", "\"\"", "", "any", "Where the hazard comes from (cited in the report)."},

    // ---------------------------------------------------------------- [target_spectrum]
    {"target_spectrum", "code", "string", "required", "", "\"ASCE 7-16\" | \"EC8\" | \"Standard 2800\" | \"csv\"",
     "The design spectrum."},
    {"target_spectrum", "sds", "number", "required (ASCE 7-16), or ss, s1 and site_class", "g", "(0, 5]",
     "ASCE 7-16: design short-period Sa.", 1e-6, 5.0},
    {"target_spectrum", "sd1", "number", "required (ASCE 7-16), or ss, s1 and site_class", "g", "(0, 5]",
     "ASCE 7-16: design 1-s Sa.", 1e-6, 5.0},
    {"target_spectrum", "ss", "number", "none (instead of sds, sd1)", "g", "(0, 5]",
     "ASCE 7-16: mapped MCER Sa at 0.2 s (ch. 22); SDS = 2/3 Fa Ss, Fa from Table 11.4-1 (motion/asce7_site.hpp).",
     1e-6, 5.0},
    {"target_spectrum", "s1", "number", "none (instead of sds, sd1)", "g", "(0, 3]",
     "ASCE 7-16: mapped MCER Sa at 1 s; SD1 = 2/3 Fv S1, Fv from Table 11.4-2 (Supplement 1).", 1e-6, 3.0},
    {"target_spectrum", "site_class", "string", "required with ss and s1", "",
     "\"A\" | \"B\" | \"C\" | \"D\" | \"D-default\" | \"E\" | \"F\"",
     "ASCE 7-16 site class (D-default: 11.4.3's default, Fa >= 1.2). F and the 11.4.8 site-specific cases (E with "
     "Ss >= 1, D and E with S1 >= 0.2) are refused: give sds and sd1 from a site-specific analysis."},
    {"target_spectrum", "tl", "number", "8", "s", "[1, 20]", "ASCE 7-16: long-period transition period.", 1.0, 20.0},
    {"target_spectrum", "mcer", "boolean", "false", "", "true | false",
     "ASCE 7-16: true scales to the MCER spectrum, 1.5 x the design one (16.2)."},
    {"target_spectrum", "type", "integer", "1", "", "1 | 2", "EC8: spectrum type.", 1, 2},
    {"target_spectrum", "ground", "string", "required (EC8)", "", "\"A\" | \"B\" | \"C\" | \"D\" | \"E\"",
     "EC8: ground type."},
    {"target_spectrum", "agr", "number", "required (EC8)", "g", "(0, 2]", "EC8: reference peak ground acceleration on "
     "ground A.", 1e-6, 2.0},
    {"target_spectrum", "importance", "number", "1", "", "[0.8, 1.4]",
     "EC8 (gammaI) and Standard 2800 (I): importance factor.", 0.8, 1.4},
    {"target_spectrum", "a", "number", "required (Standard 2800)", "", "0.20 | 0.25 | 0.30 | 0.35",
     "Standard 2800: design base acceleration ratio A (zone value)."},
    {"target_spectrum", "soil", "string", "required (Standard 2800)", "", "\"I\" | \"II\" | \"III\" | \"IV\"",
     "Standard 2800: soil type."},
    {"target_spectrum", "file", "string", "required (csv)", "", "a CSV file",
     "csv: the spectrum as \"period,sa\" lines in s and g (relative to the study file)."},
    {"target_spectrum", "rule", "string", "\"ASCE 7-16\" (\"EC8\" for an EC8 target)", "",
     "\"ASCE 7-16\" | \"ASCE 7-10\" | \"EC8\" | \"none\"",
     "The scaling condition the suite mean must meet over the period range."},
    {"target_spectrum", "t_min", "number", "0.2 min(T1, T2)", "s", "[0.01, 20]",
     "Lower end of the period range (T1, T2: the buildings' median periods); the range of records select --period.",
     0.01, 20.0},
    {"target_spectrum", "t_max", "number", "2.0 max(T1, T2) (ASCE 7-10: 1.5 max(T1, T2))", "s", "[0.01, 20], > t_min",
     "Upper end of the period range.", 0.01, 20.0},
    {"target_spectrum", "points", "integer", "30", "", "[2, 1000]", "Periods at which the match is computed.", 2, 1000},
    {"target_spectrum", "damping", "number", "0.05", "", "[0, 0.5]", "Damping ratio of the spectra.", 0.0, 0.5},
    {"target_spectrum", "min_scale", "number", "0.25", "", "[0.001, 1000], <= max_scale",
     "Smallest amplitude factor of a record.", 1e-3, 1000.0},
    {"target_spectrum", "max_scale", "number", "4", "", "[0.001, 1000]", "Largest amplitude factor of a record.", 1e-3,
     1000.0},
};

std::string cell(std::string_view s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : c == '<' ? std::string("&lt;") : c == '>' ? std::string("&gt;") : std::string(1, c);
  return out;
}

}  // namespace

std::span<const StudySection> study_sections() { return sections; }
std::span<const StudyKey> study_keys() { return keys; }

std::string study_section_of(std::string_view name) {
  auto starts = [&](std::string_view p) { return name.substr(0, p.size()) == p; };
  auto ends = [&](std::string_view s) { return name.size() >= s.size() && name.substr(name.size() - s.size()) == s; };
  // [structures.buildingK], K = 1, 2, ... (a row: [structures] buildings)
  constexpr std::string_view stem = "structures.building";
  if (starts(stem) && name.size() > stem.size() && name[stem.size()] >= '1' && name[stem.size()] <= '9') {
    std::size_t end = stem.size();
    while (end < name.size() && name[end] >= '0' && name[end] <= '9') ++end;
    const std::string_view b = name.substr(0, end);
    if (name == b) return "structures.buildingN";
    if (name == std::string(b) + ".isolation") return "isolation";
    if (name == std::string(b) + ".moat") return "moat";
    if (starts(std::string(b) + ".")) {  // a distribution of one of its keys
      if (ends(".lognormal")) return "distribution.lognormal";
      if (ends(".uniform")) return "distribution.uniform";
      return "distribution";
    }
  }
  return std::string(name);
}

const StudyKey* find_study_key(std::string_view section, std::string_view key) {
  for (const StudyKey& k : keys)
    if (k.section == section && k.key == key) return &k;
  return nullptr;
}

std::string study_reference_markdown() {
  std::string out =
      "# Study-file reference\n\n"
      "<!-- Generated by `pounding study-reference` from src/config/study_keys.cpp; do not edit by hand. After a\n"
      "     change there: build/pounding study-reference -o docs/study-reference.md (ctest docs.study_reference\n"
      "     fails while this file differs). -->\n\n"
      "A study is a TOML file (studies/*.toml). Every key is optional unless its default says \"required\"; an\n"
      "unknown key, a value of the wrong type or one outside its allowed range is refused before any work starts,\n"
      "with the file, line and key. Numbers are SI inside the engine; accelerations are in g at the edges.\n"
      "Intervals: `[a, b]` includes both ends, `(a, b]` excludes a.\n";
  for (const StudySection& s : sections) {
    out += fmt::format("\n## {}\n\n{}\n\n", s.heading, s.text);
    out += "| key | type | default | units | allowed | meaning |\n|---|---|---|---|---|---|\n";
    for (const StudyKey& k : keys)
      if (k.section == s.name)
        out += fmt::format("| `{}` | {} | {} | {} | {} | {} |\n", k.key, cell(k.type), cell(k.def), cell(k.units),
                           cell(k.range), cell(k.meaning));
  }
  return out;
}

}  // namespace pounding::config
