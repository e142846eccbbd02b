#include "util/dynamic_library.h"

#include <dlfcn.h>

#include "util/error.h"

namespace tsrir {

DynamicLibrary::DynamicLibrary(const std::string& soname, const std::string& needed_for) : soname_(soname) {
  handle_ = dlopen(soname.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle_) {
    const char* why = dlerror();
    throw Error("cannot load " + soname + " (needed " + needed_for + "): " + (why ? why : "unknown reason"));
  }
}

DynamicLibrary::~DynamicLibrary() = default;

void* DynamicLibrary::symbol(const char* name) const {
  dlerror();
  void* p = dlsym(handle_, name);
  if (!p) {
    const char* why = dlerror();
    throw Error(soname_ + " has no " + name + (why ? std::string(": ") + why : std::string()) +
                " (an incompatible version?)");
  }
  return p;
}

}  // namespace tsrir
