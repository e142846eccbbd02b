// The model extensions rir-diagnose fits (one per cause of its catalog that needs a component):
// modes, air, band_absorption, scattering, transducer, onset_shift, noise_floor. Registered in the
// process-wide registry by register_extension_components() (idempotent); rir-diagnose calls it
// before parsing any model.
#pragma once

namespace tsrir::sim {

void register_extension_components();

}  // namespace tsrir::sim
