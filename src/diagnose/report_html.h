// The self-contained HTML report of rir-diagnose: inline SVG plots, no scripts, no external files.
#pragma once
#include <ostream>
#include <string>

#include "diagnose/diagnose.h"

namespace tsrir::diagnose {

void write_report_html(const Diagnosis& diagnosis, const std::string& command_line, std::ostream& out);

}  // namespace tsrir::diagnose
