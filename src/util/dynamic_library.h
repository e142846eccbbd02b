// A shared library loaded on first need (dlopen) instead of at program start. Each library a
// program links is mapped and relocated at every start, whether the run uses it or not; Kaldi's
// pipes start wav-reverberate once per utterance, so codecs (libsndfile) and the resampler
// (libsox, which pulls ~10 more libraries) are loaded only by the runs that decode a FLAC or
// resample.
#pragma once
#include <string>

namespace tsrir {

class DynamicLibrary {
 public:
  // Loads `soname` (e.g. "libsndfile.so.1"). Throws Error saying what it is `needed_for` and why
  // it could not be loaded (the dynamic loader's message).
  DynamicLibrary(const std::string& soname, const std::string& needed_for);
  ~DynamicLibrary();  // the library stays loaded: its functions may still be referenced
  DynamicLibrary(const DynamicLibrary&) = delete;
  DynamicLibrary& operator=(const DynamicLibrary&) = delete;

  // The address of `name`; throws Error when the library lacks it (a wrong or old version).
  void* symbol(const char* name) const;
  // Typed: `fn = lib.function<decltype(&::sf_open)>("sf_open")`.
  template <typename F>
  F function(const char* name) const {
    return reinterpret_cast<F>(symbol(name));
  }

 private:
  std::string soname_;
  void* handle_ = nullptr;
};

}  // namespace tsrir
