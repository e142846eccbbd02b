// Shared by the libFuzzer harnesses. A harness calls one parser on arbitrary bytes and checks
// invariants. Policy: tsrir::Error is the expected answer to bad input (a clear message naming the
// file); any other exception reaching the user (std::out_of_range, std::length_error, bad_alloc...)
// would print an unhelpful message, so it counts as a finding, like a crash or a broken invariant.
#pragma once
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "util/error.h"

namespace tsrir::fuzz {

[[noreturn]] inline void fail(const char* what, const std::string& detail) {
  std::fprintf(stderr, "FUZZ INVARIANT BROKEN: %s: %s\n", what, detail.c_str());
  std::abort();
}

#define FUZZ_CHECK(cond, detail) \
  do {                           \
    if (!(cond)) ::tsrir::fuzz::fail(#cond, (detail)); \
  } while (0)

// Runs `body`; Error is accepted, anything else aborts.
template <typename F>
void expect_only_errors(F&& body) {
  try {
    body();
  } catch (const tsrir::Error&) {
  } catch (const std::exception& e) {
    fail("only tsrir::Error may escape a parser", std::string(typeid(e).name()) + ": " + e.what());
  }
}

inline std::string as_text(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// A scratch path unique to this process (fuzzers run several processes with -jobs).
std::string scratch_path(const std::string& name);
void write_file(const std::string& path, const std::string& bytes);

}  // namespace tsrir::fuzz
