#include "io/sndfile_api.h"

#include "util/dynamic_library.h"

namespace tsrir {

const SndfileApi& sndfile() {
  static const SndfileApi api = [] {
    static const DynamicLibrary lib(TSRIR_SNDFILE_SONAME, "to decode audio other than plain WAV");
    SndfileApi a;
    a.open = lib.function<decltype(a.open)>("sf_open");
    a.open_virtual = lib.function<decltype(a.open_virtual)>("sf_open_virtual");
    a.close = lib.function<decltype(a.close)>("sf_close");
    a.readf_float = lib.function<decltype(a.readf_float)>("sf_readf_float");
    a.error = lib.function<decltype(a.error)>("sf_error");
    a.strerror = lib.function<decltype(a.strerror)>("sf_strerror");
    a.command = lib.function<decltype(a.command)>("sf_command");
    return a;
  }();
  return api;
}

}  // namespace tsrir
