// Loss curves of a TS-RIRGAN run: <model-dir>/loss_curves.svg drawn from loss_log.csv, so that a
// person can see at a glance whether the discriminators won, the generators' adversarial terms
// stalled or the L1 terms ran away. Torch-free.
#pragma once
#include <string>

namespace tsrir {

// Reads the loss log (header + one row per step) and writes an SVG with one panel per loss
// family (discriminators, adversarial, cycle L1, identity L1), log-scaled y, at most 400 points per
// curve (bucket means). Returns false (and writes nothing) if the log has no rows.
bool write_loss_curves_svg(const std::string& loss_log_csv, const std::string& svg_path);

}  // namespace tsrir
