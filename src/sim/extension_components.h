// The model extensions rir-diagnose fits (one per cause of its catalog that needs a component):
// modes, air, band_absorption, scattering, directivity, transducer, onset_shift, noise_floor.
// Two ways to make them available:
//  - register_extension_components(): from a program or library, before the first Model::parse
//    (idempotent; rir-diagnose does this);
//  - register_extension_builtins(): one line inside register_builtin_components() in
//    components.cc, which makes them built-ins of every program (rir-simulate included).
#pragma once

namespace tsrir::sim {

void register_extension_components();
void register_extension_builtins();

}  // namespace tsrir::sim
