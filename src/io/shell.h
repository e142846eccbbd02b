// Quoting for anything the toolkit writes into a shell command or a Kaldi pipe: a file named
// "a b;touch x.wav" must stay one inert word.
#pragma once
#include <string>

namespace tsrir {

// Single-quotes `word` for bash unless it consists only of safe characters [A-Za-z0-9_./:=@%+,-].
std::string shell_quote(const std::string& word);

}  // namespace tsrir
