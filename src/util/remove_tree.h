// Recursive removal of a file or directory tree without std::filesystem::remove_all: the
// libtorch.so of pip/conda torch exports its own copy of std::filesystem, whose remove_all jumps to
// address 0 (a reference its build left unbound; found with torch 2.11 on the GPU machine,
// docs/recipe.md), and in a program linked with it the dynamic linker binds std::filesystem calls
// to that copy. Code that LibTorch programs run, and their tests, remove trees through this.
#pragma once
#include <string>
#include <system_error>

namespace tsrir {

// Removes `path` and everything under it (symlinks are removed, not followed). A missing path is
// not an error. Returns false and sets `ec` on the first failure (the rest is still attempted).
bool remove_tree(const std::string& path, std::error_code& ec);
// The same; a failure throws std::system_error naming the path.
void remove_tree(const std::string& path);

}  // namespace tsrir
