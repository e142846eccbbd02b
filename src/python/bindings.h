// One function per area, each adding its part of the `_tsrir` extension (module.cc calls them).
#pragma once
#include <pybind11/pybind11.h>

namespace tsrir::python {

void bind_audio(pybind11::module_& m);       // read_audio, encode_wav, write_wav, resample
void bind_simulate(pybind11::module_& m);    // simulate (rir-simulate's model)
void bind_metrics(pybind11::module_& m);     // metrics (rir-metrics)
void bind_reverberate(pybind11::module_& m); // reverberate (wav-reverberate)
void bind_eq(pybind11::module_& m);          // eq_apply (rir-eq apply)
void bind_lists(pybind11::module_& m);       // Kaldi rir_list / noise_list
void bind_augmenter(pybind11::module_& m);   // Augmenter (reverberate-data's plan)

}  // namespace tsrir::python
