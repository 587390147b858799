// Reads the bridge description of `pounding simulate --bridge` (bridge_file.hpp).
#include "cli/commands/bridge_file.hpp"

#include "pounding/config/config.hpp"
#include "pounding/core/files.hpp"
#include "pounding/sampling/bridge.hpp"

namespace pounding::cli {

physics::BridgeSpec read_bridge_file(const std::string& path, double kc_default, double e_default,
                                     const std::string& restitution_given_by) {
  const std::string text = files::read_text(path, "bridge file", 16u << 20);
  const toml::table root = config::parse(text, path, "fix the bridge file's syntax");
  // the file's top level is a study's [bridge] without the study's own keys (samples, period_cov, mass_cov)
  config::TableReader r(&root, path, "", "bridge");
  BridgeReadDefaults d;
  d.kc = kc_default, d.e = e_default, d.restitution_given_by = restitution_given_by;
  physics::BridgeSpec spec = read_bridge(r, path, "", d);
  r.finish("frame, joint, abutment");
  return spec;
}

}  // namespace pounding::cli
