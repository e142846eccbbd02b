// reverberate-data's options (ReverberateDataOptions, the library's own struct and defaults) by
// name from Python: Augmenter(**options) takes the program's long option names with '_' for '-'
// (e.g. speech_rvb_probability for --speech-rvb-probability; seed = --random-seed). Only the
// options that decide what happens to a recording are settable (not num_replications,
// include_original_data, write_wavs, threads, pipes...).
#pragma once
#include <pybind11/pybind11.h>

#include <string>

#include "augment/reverberate_data.h"

namespace tsrir::python {

// Throws Error naming the option for an unknown name or a value of the wrong type.
void set_augment_option(ReverberateDataOptions& options, const std::string& name, const pybind11::handle& value);
// Every settable option and its value (defaults: ReverberateDataOptions{}).
pybind11::dict augment_options_dict(const ReverberateDataOptions& options);

}  // namespace tsrir::python
