#!/usr/bin/env python3
"""Include what you use, for the standard library: every C++ file under src, tests, bench and bin
that names a standard facility must include its header, itself or through one of the project's
own headers (which are under our control); what a standard header happens to include is not
counted. Why: each new libstdc++ includes less (g++ 13: <string> no longer brings <cstdint>, which
broke src/sim/room_metadata.h, issue 31), and a compiler only finds such a gap when it is the one
that drops the include. Heuristic (comments and strings are ignored, names are matched as text),
so the table below lists only unambiguous names. Exit status 1 with one line per gap.
Usage: utils/check_includes.py [ROOT]"""
import os
import re
import sys

# (pattern of uses, headers any one of which provides them; the first is the one to include)
RULES = [
    (r"\b(?:std::)?u?int(?:8|16|32|64|ptr|max)_t\b|\bU?INT(?:8|16|32|64)_(?:MAX|MIN|C)\b",
     ("cstdint", "stdint.h", "cinttypes", "inttypes.h")),
    (r"\bstd::(?:printf|fprintf|snprintf|fopen|fclose|FILE|fputs|fflush|perror|sscanf|fwrite|fread|fgets|popen|pclose)\b"
     r"|(?<![\w:.>])(?:printf|fprintf|snprintf|fopen|fclose|fputs|fflush|perror|sscanf|fwrite|fread|fgets|popen|pclose)\s*\("
     r"|\bFILE\s*\*", ("cstdio", "stdio.h")),
    (r"\bstd::(?:w?string|to_string|stoi|stol|stoll|stod|getline)\b", ("string",)),
    (r"\bstd::vector\b", ("vector",)),
    (r"\bstd::(?:multi)?map\b", ("map",)),
    (r"\bstd::(?:multi)?set\b", ("set",)),
    (r"\bstd::unordered_map\b", ("unordered_map",)),
    (r"\bstd::unordered_set\b", ("unordered_set",)),
    (r"\bstd::(?:unique_ptr|shared_ptr|make_unique|make_shared|weak_ptr)\b", ("memory",)),
    (r"\bstd::function\b", ("functional",)),
    (r"\bstd::(?:optional|nullopt)\b", ("optional",)),
    (r"\bstd::array\b", ("array",)),
    (r"\bstd::(?:mutex|lock_guard|unique_lock|once_flag|call_once)\b", ("mutex",)),
    (r"\bstd::thread\b", ("thread",)),
    (r"\bstd::atomic\b", ("atomic",)),
    (r"\bstd::(?:o|i)?stringstream\b", ("sstream",)),
    (r"\bstd::(?:o|i)?fstream\b", ("fstream",)),
    (r"\bstd::(?:runtime_error|invalid_argument|out_of_range|logic_error)\b", ("stdexcept",)),
    (r"\bstd::(?:pair|make_pair|move|forward|exchange)\b", ("utility", "map", "unordered_map", "tuple")),
    (r"\bstd::(?:sort|stable_sort|min_element|max_element|find|find_if|fill|fill_n|copy|reverse|any_of|all_of"
     r"|none_of|count|count_if|lower_bound|upper_bound|clamp|unique|nth_element|transform|equal|remove_if"
     r"|partial_sort)\s*\(", ("algorithm",)),
    (r"\bstd::(?:accumulate|iota|inner_product|partial_sum|gcd|lcm)\b", ("numeric",)),
    (r"\bstd::chrono\b", ("chrono",)),
    (r"\bstd::filesystem\b", ("filesystem",)),
    (r"\bstd::numeric_limits\b", ("limits",)),
    (r"\bstd::complex\b", ("complex",)),
    (r"\bstd::(?:tuple|tie)\b|\bstd::get<", ("tuple", "utility", "array", "variant")),
    (r"\bstd::(?:cout|cerr|clog)\b", ("iostream",)),
    (r"\bstd::(?:memcpy|memset|memcmp|strlen|strcmp|strncmp|strerror|memmove|strchr)\b", ("cstring", "string.h")),
    (r"\bstd::(?:abs|sqrt|exp|log|log10|pow|sin|cos|floor|ceil|round|lround|isfinite|isnan|fabs|hypot|atan2|tanh"
     r"|erf|erfc|lgamma|fmod|cbrt|trunc|llround|exp2|log2|log1p|expm1|tan|asin|acos|atan)\b",
     ("cmath", "math.h", "cstdlib", "complex", "valarray")),
    (r"\bstd::(?:getenv|exit|abort|strtod|strtol|strtoll|strtoul|strtoull|atoi|atof|atol|atoll|system|malloc|free"
     r"|qsort|rand)\b", ("cstdlib", "stdlib.h")),
]
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)


def code_only(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    return re.sub(r'"(?:\\.|[^"\\\n])*"', '""', text)


def main(root):
    files = []
    for top in ("src", "tests", "bench", "bin"):
        for d, _, names in os.walk(os.path.join(root, top)):
            files += [os.path.relpath(os.path.join(d, n), root) for n in names if re.search(r"\.(h|cc|cpp|hpp)$", n)]
    includes = {}
    for f in files:
        with open(os.path.join(root, f), errors="replace") as fh:
            includes[f] = INCLUDE.findall(fh.read())

    def project_header(f, name):
        for base in (os.path.dirname(f), "src", "tests", "tests/common"):
            cand = os.path.normpath(os.path.join(base, name))
            if cand in includes:
                return cand
        return None

    reach = {}

    def system_headers(f, seen):
        # The standard and library headers that f includes itself or through project headers.
        if f in reach:
            return reach[f]
        seen.add(f)
        out = set()
        for kind, name in includes[f]:
            own = project_header(f, name) if kind == '"' else None
            if own is None:
                out.add(name)
            elif own not in seen:
                out |= system_headers(own, seen)
        reach[f] = out
        return out

    gaps = []
    for f in sorted(files):
        with open(os.path.join(root, f), errors="replace") as fh:
            code = code_only(fh.read())
        have = system_headers(f, set())
        for pattern, headers in RULES:
            m = re.search(pattern, code)
            if m and not have.intersection(headers):
                gaps.append(f"{f}: uses {m.group(0).strip()} without #include <{headers[0]}>")
    for g in gaps:
        print(g)
    print(f"check_includes: {len(files)} files, {len(gaps)} gaps", file=sys.stderr)
    return 1 if gaps else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")))
